#include "param_flags.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <limits>

#include "core/number_text.hpp"

namespace acetate {
namespace {

bool all_digits(std::string_view text) {
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); });
}

Error flag_error(const std::string& flag, std::string_view text, const std::string& why) {
    return Error{ErrorCode::InvalidInput, fmt::format("{} {}: {}", flag, text, why)};
}

}  // namespace

Result<ParamFlag> parse_param_flag(std::string_view text, bool preset) {
    ParamFlag out;
    out.text = std::string(text);
    out.flag = preset ? "--preset" : "--param";
    const size_t equals = text.find('=');
    if (equals == std::string_view::npos)
        return flag_error(
            out.flag, text,
            preset ? "expected FLOOR.EFFECT=PRESET" : "expected FLOOR.EFFECT.NAME=VALUE");
    std::string_view where = text.substr(0, equals);
    const std::string_view value = text.substr(equals + 1);
    if (!preset) {
        const size_t dot = where.rfind('.');
        if (dot == std::string_view::npos || dot + 1 == where.size())
            return flag_error(out.flag, text, "expected FLOOR.EFFECT.NAME=VALUE");
        out.name = std::string(where.substr(dot + 1));
        where = where.substr(0, dot);
    }
    const size_t dot = where.find('.');
    if (dot == 0 || dot == std::string_view::npos || dot + 1 == where.size())
        return flag_error(out.flag, text,
                          "expected FLOOR.EFFECT (a floor's name or index, or \"global\"; a "
                          "plugin id or the entry's index)");
    out.floor = std::string(where.substr(0, dot));
    out.effect = std::string(where.substr(dot + 1));
    if (preset) {
        out.preset = std::string(value);
        return out;
    }
    size_t start = 0;
    while (true) {
        const size_t comma = value.find(',', start);
        const std::string_view item =
            value.substr(start, comma == value.npos ? comma : comma - start);
        auto number = number_text::finite_number(item, out.flag + " " + out.text,
                                                 -double(std::numeric_limits<float>::max()),
                                                 double(std::numeric_limits<float>::max()));
        if (!number) return number.error();
        out.value.push_back(float(number.value()));
        if (comma == value.npos) break;
        start = comma + 1;
    }
    if (out.value.size() > 3) return flag_error(out.flag, text, "a value has 1, 2 or 3 numbers");
    return out;
}

Result<host::EffectSlot> resolve_param_flag(const ParamFlag& flag, const host::SceneInfo& scene) {
    const std::string file = scene.file.string();
    host::EffectSlot slot;
    const std::vector<std::string>* effects = &scene.global_effects;
    if (flag.floor != "global") {
        const auto named =
            std::find(scene.floor_names.begin(), scene.floor_names.end(), flag.floor);
        if (named != scene.floor_names.end()) {
            slot.floor = uint32_t(named - scene.floor_names.begin());
        } else if (all_digits(flag.floor) && flag.floor.size() < 10 &&
                   std::stoul(flag.floor) < scene.floor_names.size()) {
            slot.floor = uint32_t(std::stoul(flag.floor));
        } else {
            return flag_error(flag.flag, flag.text,
                              fmt::format("{} has no floor \"{}\" (floors 0..{} by index or name, "
                                          "or \"global\")",
                                          file, flag.floor, scene.floor_names.size() - 1));
        }
        effects = &scene.floor_effects[*slot.floor];
    }
    if (all_digits(flag.effect)) {
        if (flag.effect.size() >= 10 || std::stoul(flag.effect) >= effects->size())
            return flag_error(
                flag.flag, flag.text,
                fmt::format("{}: {} lists {} effects", file,
                            slot.floor ? "the floor" : "global_effects", effects->size()));
        slot.index = uint32_t(std::stoul(flag.effect));
        return slot;
    }
    const auto count = std::count(effects->begin(), effects->end(), flag.effect);
    if (count != 1)
        return flag_error(
            flag.flag, flag.text,
            fmt::format("{}: {} lists \"{}\" {} times; name it by its index", file,
                        slot.floor ? "the floor" : "global_effects", flag.effect, count));
    slot.index =
        uint32_t(std::find(effects->begin(), effects->end(), flag.effect) - effects->begin());
    return slot;
}

}  // namespace acetate
