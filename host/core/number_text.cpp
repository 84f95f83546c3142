#include "core/number_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>

#include "core/json_fields.hpp"

namespace acetate::number_text {
namespace {

// What a message shows of the text: quoted and escaped as the JSON field reader shows a
// string, and cut short, so a megabyte argument still makes one readable line.
std::string quoted(std::string_view text) {
    constexpr size_t kShown = 64;
    if (text.size() <= kShown) return json_fields::json_quoted(text);
    return json_fields::json_quoted(text.substr(0, kShown)) +
           fmt::format("... ({} characters)", text.size());
}

// A number that parsed is shown as typed (it holds only digits, '-', '.', 'e'), shortened the
// same way.
std::string as_typed(std::string_view text) {
    constexpr size_t kShown = 64;
    if (text.size() <= kShown) return std::string(text);
    return fmt::format("{}... ({} characters)", text.substr(0, kShown), text.size());
}

Error refused(std::string_view label, const std::string& what) {
    return make_error(ErrorCode::InvalidInput,
                      label.empty() ? what : fmt::format("{}: {}", label, what));
}

bool is_digit(char c) {
    return c >= '0' && c <= '9';
}

size_t digits_from(std::string_view s, size_t i) {
    while (i < s.size() && is_digit(s[i])) ++i;
    return i;
}

// -?(D+(.D*)?|.D+)([eE][-+]?D+)? : what from_chars reads, minus the infinities and NaNs it
// also takes, so "1e5x" or "1." followed by garbage never reads as a prefix.
bool is_decimal(std::string_view s) {
    size_t i = !s.empty() && s[0] == '-' ? 1 : 0;
    const size_t whole_end = digits_from(s, i);
    bool any_digit = whole_end > i;
    i = whole_end;
    if (i < s.size() && s[i] == '.') {
        const size_t fraction_end = digits_from(s, i + 1);
        any_digit = any_digit || fraction_end > i + 1;
        i = fraction_end;
    }
    if (!any_digit) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
        const size_t exponent_end = digits_from(s, i);
        if (exponent_end == i) return false;
        i = exponent_end;
    }
    return i == s.size();
}

// "nan", "-inf", "Infinity": what strtod and from_chars would read as a number that is not
// finite, refused as such rather than as "not a number".
bool names_non_finite(std::string_view s) {
    if (!s.empty() && (s[0] == '-' || s[0] == '+')) s.remove_prefix(1);
    std::string lower(s);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return lower == "nan" || lower == "inf" || lower == "infinity";
}

std::string month_name(int month) {
    static const std::array<const char*, 12> names = {
        "January", "February", "March",     "April",   "May",      "June",
        "July",    "August",   "September", "October", "November", "December"};
    return names.at(size_t(month - 1));
}

}  // namespace

Result<double> finite_number(std::string_view text, std::string_view label, double min,
                             double max) {
    if (names_non_finite(text))
        return refused(label, "must be a finite number, got " + quoted(text));
    if (!is_decimal(text)) return refused(label, "must be a number, got " + quoted(text));
    double value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc::result_out_of_range) {
        // Too large for a double (1e999), or too small (1e-999): strtod tells which, and a
        // tiny number is as good as its nearest double.
        const std::string copy(text);
        errno = 0;
        value = std::strtod(copy.c_str(), nullptr);
        if (std::isinf(value))
            return refused(label, "must be a finite number, got " + quoted(text));
    } else if (ec != std::errc() || end != text.data() + text.size()) {
        return refused(label, "must be a number, got " + quoted(text));
    }
    if (value < min)
        return refused(label, fmt::format("must be at least {}, got {}", min, as_typed(text)));
    if (value > max)
        return refused(label, fmt::format("must be at most {}, got {}", max, as_typed(text)));
    return value;
}

namespace {

// -?D+ as a sign and a magnitude; nullopt for any other text. `overflow` when the magnitude
// does not fit 64 bits.
struct Magnitude {
    bool negative = false;
    uint64_t value = 0;
    bool overflow = false;
};

std::optional<Magnitude> magnitude_of(std::string_view text) {
    Magnitude m;
    m.negative = !text.empty() && text[0] == '-';
    const std::string_view digits = text.substr(m.negative ? 1 : 0);
    if (digits.empty() || digits_from(digits, 0) != digits.size()) return std::nullopt;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), m.value);
    m.overflow = ec == std::errc::result_out_of_range;
    return m;
}

}  // namespace

Result<int64_t> integer(std::string_view text, std::string_view label, int64_t min, int64_t max) {
    const auto m = magnitude_of(text);
    if (!m) return refused(label, "must be an integer, got " + quoted(text));
    // The magnitude of INT64_MIN is one more than INT64_MAX.
    const uint64_t limit = m->negative ? uint64_t(INT64_MAX) + 1 : uint64_t(INT64_MAX);
    const bool fits = !m->overflow && m->value <= limit;
    const int64_t value = !fits               ? 0
                          : !m->negative      ? int64_t(m->value)
                          : m->value == limit ? INT64_MIN
                                              : -int64_t(m->value);
    if ((!fits && m->negative) || (fits && value < min))
        return refused(label, fmt::format("must be at least {}, got {}", min, as_typed(text)));
    if (!fits || value > max)
        return refused(label, fmt::format("must be at most {}, got {}", max, as_typed(text)));
    return value;
}

Result<uint64_t> unsigned_integer(std::string_view text, std::string_view label, uint64_t min,
                                  uint64_t max) {
    const auto m = magnitude_of(text);
    if (!m) return refused(label, "must be an integer, got " + quoted(text));
    // "-0" is zero; any other negative is below every unsigned minimum.
    const bool negative = m->negative && (m->overflow || m->value != 0);
    if (!negative && (m->overflow || m->value > max))
        return refused(label, fmt::format("must be at most {}, got {}", max, as_typed(text)));
    if (negative || m->value < min)
        return refused(label, fmt::format("must be at least {}, got {}", min, as_typed(text)));
    return m->value;
}

int days_in_month(int year, int month) {
    static const std::array<int, 12> days = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    return month == 2 && leap ? 29 : days.at(size_t(month - 1));
}

Result<Day> day(std::string_view text, std::string_view label) {
    const bool shaped = text.size() == 10 && text[4] == '-' && text[7] == '-' &&
                        digits_from(text, 0) == 4 && digits_from(text, 5) == 7 &&
                        digits_from(text, 8) == 10;
    if (!shaped) return refused(label, "must be a day YYYY-MM-DD, got " + quoted(text));
    auto number = [&](size_t at, size_t length) {
        int n = 0;
        for (size_t i = at; i < at + length; ++i) n = n * 10 + (text[i] - '0');
        return n;
    };
    const Day d{number(0, 4), number(5, 2), number(8, 2)};
    if (d.month < 1 || d.month > 12)
        return refused(
            label,
            fmt::format("must be a day that exists, got {} (there is no month {})", text, d.month));
    const int days = days_in_month(d.year, d.month);
    if (d.day < 1 || d.day > days)
        return refused(label, fmt::format("must be a day that exists, got {} ({} {} has {} days)",
                                          text, month_name(d.month), d.year, days));
    return d;
}

Result<std::string> name(std::string_view text, std::string_view label) {
    if (text.empty()) return refused(label, "must not be empty");
    if (std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c) != 0; }))
        return refused(label, "must not be only spaces, got " + quoted(text));
    if (std::any_of(text.begin(), text.end(),
                    [](unsigned char c) { return c < 0x20 || c == 0x7f; }))
        return refused(label, "must be one line without control characters, got " + quoted(text));
    return std::string(text);
}

}  // namespace acetate::number_text
