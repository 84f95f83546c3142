#pragma once
// The frame block every effect pass reads (AcetateFrame), laid out once.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace acetate {

// The frame uniforms, the GLSL block AcetateFrame (std140, every member a vec4 or an array of
// vec4), declared once, here: the block every effect pass declares (effect_glsl_preamble) is
// written from kMembers, and so are the offsets the host fills each frame (record_effect).
// tests/unit/frame_block_test.cpp compiles the block, and host/shaders/instanced_quad.vert, and
// compares the offsets glslang gave each member with these. The block only grows at its end,
// so a SPIR-V module built for ABI 1.0 reads the same offsets.
class EffectFrameLayout {
  public:
    enum class Length { One, PerParam, PerPhase };  // an array has one vec4 at least
    struct Member {
        std::string_view name;
        Length length;
        std::string_view comment;
    };
    static constexpr std::array<Member, 6> kMembers = {{
        {"acetate_canvas", Length::One, "width, height, 1/width, 1/height"},
        {"acetate_output", Length::One, "this pass's output: width, height, 1/width, 1/height"},
        {"acetate_misc", Length::One,
         "time (s), floor index (-1: global), instanced quads' first float in floor_data"},
        {"acetate_params", Length::PerParam, "a parameter's components"},
        {"acetate_clock", Length::One, "whole seconds, fraction of the second (double on the CPU)"},
        {"acetate_phases", Length::PerPhase, "a phase in .x"},
    }};

    explicit EffectFrameLayout(size_t params = 0, size_t phases = 0);
    // The first float of a member, by name (none for a name the block lacks); and each
    // member's, as the host writes them.
    std::optional<size_t> offset(std::string_view member) const;
    size_t canvas() const { return offsets_[0]; }
    size_t output() const { return offsets_[1]; }
    size_t misc() const { return offsets_[2]; }
    size_t param(size_t i) const { return offsets_[3] + 4 * i; }
    size_t clock() const { return offsets_[4]; }
    size_t phase(size_t i) const { return offsets_[5] + 4 * i; }
    size_t bytes() const { return floats_ * sizeof(float); }
    // The block's members as GLSL declares them, one a line.
    std::string glsl_members() const;

  private:
    size_t vec4s(const Member& m) const;
    size_t params_, phases_;
    std::array<size_t, kMembers.size()> offsets_{};
    size_t floats_ = 0;
};

}  // namespace acetate
