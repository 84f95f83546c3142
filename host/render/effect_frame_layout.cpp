#include "render/effect_frame_layout.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace acetate {

EffectFrameLayout::EffectFrameLayout(size_t params, size_t phases)
    : params_(params), phases_(phases) {
    for (size_t i = 0; i < kMembers.size(); ++i) {
        offsets_[i] = floats_;
        floats_ += 4 * vec4s(kMembers[i]);
    }
}

size_t EffectFrameLayout::vec4s(const Member& m) const {
    switch (m.length) {
        case Length::One:
            return 1;
        case Length::PerParam:
            return std::max<size_t>(1, params_);
        case Length::PerPhase:
            return std::max<size_t>(1, phases_);
    }
    return 1;
}

std::optional<size_t> EffectFrameLayout::offset(std::string_view member) const {
    for (size_t i = 0; i < kMembers.size(); ++i)
        if (kMembers[i].name == member) return offsets_[i];
    return std::nullopt;
}

std::string EffectFrameLayout::glsl_members() const {
    std::string out;
    for (const Member& m : kMembers)
        out += m.length == Length::One
                   ? fmt::format("    vec4 {};  // {}\n", m.name, m.comment)
                   : fmt::format("    vec4 {}[{}];  // {}\n", m.name, vec4s(m), m.comment);
    return out;
}

}  // namespace acetate
