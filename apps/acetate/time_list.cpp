#include "time_list.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/number_text.hpp"

namespace acetate {
namespace {

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    size_t start = 0;
    while (true) {
        const size_t at = text.find(separator, start);
        parts.push_back(text.substr(start, at == std::string_view::npos ? at : at - start));
        if (at == std::string_view::npos) return parts;
        start = at + 1;
    }
}

Result<double> seconds(std::string_view text, double max_seconds) {
    return number_text::finite_number(text, "--times", -max_seconds, max_seconds);
}

// Seconds as S or N/D ("1/12": the double ratio, so 11/12 and 1/12 * 11 agree).
Result<double> seconds_or_fraction(std::string_view text, double max_seconds) {
    const std::vector<std::string_view> fraction = split(text, '/');
    if (fraction.size() > 2)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("--times: \"{}\": expected S or N/D", text));
    auto numerator = seconds(fraction[0], max_seconds);
    if (!numerator || fraction.size() == 1) return numerator;
    auto denominator = seconds(fraction[1], max_seconds);
    if (!denominator) return denominator.error();
    if (denominator.value() <= 0)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("--times: \"{}\": the divisor must be above 0", text));
    return numerator.value() / denominator.value();
}

Result<std::vector<double>> parse_range(const std::vector<std::string_view>& parts,
                                        double max_seconds) {
    auto start = seconds_or_fraction(parts[0], max_seconds);
    if (!start) return start.error();
    auto end = seconds_or_fraction(parts[1], max_seconds);
    if (!end) return end.error();
    auto step = seconds_or_fraction(parts[2], max_seconds);
    if (!step) return step.error();
    if (!(step.value() > 0))
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("--times: step \"{}\": must be above 0", parts[2]));
    if (end.value() < start.value())
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("--times: the range ends ({}) before it starts ({})",
                                      end.value(), start.value()));
    // Times are start + i * step (not summed step by step, which drifts); the end is included
    // when it lands on a step up to a millionth of one.
    const double count = std::floor((end.value() - start.value()) / step.value() + 1e-6) + 1;
    if (count > double(kMaxRenderTimes))
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("--times: {} times; at most {} in one run", count, kMaxRenderTimes));
    std::vector<double> times;
    for (size_t i = 0; i < size_t(count); ++i)
        times.push_back(start.value() + double(i) * step.value());
    return times;
}

}  // namespace

Result<std::vector<double>> parse_render_times(std::string_view text, double max_seconds) {
    if (text.find(':') != std::string_view::npos) {
        const std::vector<std::string_view> parts = split(text, ':');
        if (parts.size() != 3)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("--times: \"{}\": expected START:END:STEP", text));
        return parse_range(parts, max_seconds);
    }
    std::vector<double> times;
    for (std::string_view item : split(text, ',')) {
        auto value = seconds(item, max_seconds);
        if (!value) return value.error();
        times.push_back(value.value());
        if (times.size() > kMaxRenderTimes)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("--times: at most {} times in one run", kMaxRenderTimes));
    }
    return times;
}

}  // namespace acetate
