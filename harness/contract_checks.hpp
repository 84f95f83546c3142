#pragma once
// The image contract, checked on the CPU from what the GPU left (docs/contract.md):
// each function compares an effect's input and output images of one floor (or of the
// composite, for a global effect) and returns a CheckResult with every offending pixel counted,
// the first few as examples, and a heat map of where they are.
//
// A non-finite value is reported once, by check_finite; the other checks skip such pixels so a
// NaN does not also read as a coverage or premultiplication failure.

#include <optional>
#include <vector>

#include "report.hpp"
#include "scene/image_io.hpp"

namespace acetate::harness {

// Alpha below this is zero in an rgba16f target (the smallest positive half is 2^-24), and a
// colour channel may not exceed it there: `a ≈ 0 ⇒ rgb ≈ 0` with both thresholds at 2^-24.
inline constexpr float kZeroAlpha = 0x1p-24f;

// One floor's (or the composite's) images around an effect.
struct FloorImages {
    int64_t floor = -1;  // -1: the composite, around global effects
    const ImageRGBA* input = nullptr;
    const ImageRGBA* output = nullptr;
};

// Accumulates one check over several floors into a CheckResult and a heat map per floor.
class CheckAccumulator {
  public:
    CheckAccumulator(std::string check, std::string passing_message);
    void violation(const FloorImages& floor, uint32_t x, uint32_t y, std::string what);
    CheckResult finish(Verdict failing = Verdict::Fail);
    // Red where a pixel failed, over the input's alpha in grey, per floor that had any.
    const std::map<int64_t, ImageRGBA>& heat_maps() const { return heat_; }

  private:
    CheckResult result_;
    std::string passing_message_;
    std::map<int64_t, ImageRGBA> heat_;
};
inline constexpr size_t kMaxExamples = 8;

// a < 2^-24 ⇒ |rgb| ≤ 2^-24 × max(1, the input's largest rgb/a). Why the ratio: a correct
// effect that scales or averages alpha (a blur, a glow) can take an alpha of 2^-24 below
// 2^-25, where RGBA16F rounds it to 0, while the colour it premultiplies, up to rgb/a times
// larger (1000 in inputs/subnormal), survives.
float colour_at_zero_alpha_tolerance(const ImageRGBA& input);
void check_premultiplied(const FloorImages& floor, CheckAccumulator& out);
// Preserving: out.a == in.a bit for bit. Expanding: in.a ≤ out.a ≤ 1.
void check_coverage(const FloorImages& floor, bool expanding, CheckAccumulator& out);
// Inside opaque coverage (in.a == 1) the output stays opaque, so nothing below shows through.
void check_alpha_leak(const FloorImages& floor, CheckAccumulator& out);
// No NaN or infinity in any channel.
void check_finite(const FloorImages& floor, CheckAccumulator& out);
// No channel below 0 (rule 1: premultiplied colour and alpha are never negative; -0 is 0).
void check_non_negative(const FloorImages& floor, CheckAccumulator& out);

// The five checks above over `floors`, in that order, with their heat maps as images of
// `heat_maps` (check -> floor -> image). `finite_only` (a composite, say: no input to compare
// with) is checked for NaN and infinity alone.
std::vector<CheckResult> check_contract(
    const std::vector<FloorImages>& floors, bool expanding,
    std::map<std::string, std::map<int64_t, ImageRGBA>>* heat_maps,
    const std::vector<FloorImages>& finite_only = {});

// Where two images differ bit for bit: the number of pixels and the first few as examples
// (input = a, output = b). Sizes must match.
struct ImageDifference {
    uint64_t pixels = 0;
    std::vector<Violation> examples;
};
ImageDifference compare_exact(const ImageRGBA& a, const ImageRGBA& b, int64_t floor,
                              const ImageRGBA* only_where_transparent = nullptr);

// Every pixel where `a` and `b` differ bit for bit (only where `only_where_transparent` has
// alpha 0, when given) is a violation of `out` on `floor`: all counted and on the heat map,
// the first few kept as examples with `why` and both values.
void record_differences(const ImageRGBA& a, const ImageRGBA& b, int64_t floor,
                        const std::string& why, CheckAccumulator& out,
                        const ImageRGBA* only_where_transparent = nullptr);

// SHA-256 of the images' bytes, in order (the determinism digest).
std::string digest_images(const std::vector<const ImageRGBA*>& images);

std::string format_rgba(const float* p);

}  // namespace acetate::harness
