#pragma once
// Relations that need no oracle (docs/harness.md, "Relations"): the plugin's output in the
// case's scene against its output in a related scene, with a stated tolerance. A contract case
// whose spec names a relation runs it beside the contract checks.
//
// - canvas-size (a floor effect): the same floors on a canvas grown to the right and below give
//   the same pixels on the original canvas. The case's floors are transparent along those two
//   edges, so what lies past them reads the same either way; an effect that measures distances
//   in fractions of the canvas (a blur radius of 3% of its width) fails.
// - format-agreement: the scene in rgba32f and in rgba16f agree within half precision; an
//   effect that keeps data a 16-bit float cannot hold (pixel positions past 2048) in a target
//   of the floor's format fails.
// - camera-region (ABI 1.2): the same scene through a camera whose region starts left of and
//   above the canvas, so the canvas lands kCameraShift pixels into the output, gives the same
//   pixels there. The floors are transparent within kCanvasEdgeBand pixels of every edge. An
//   effect that takes gl_FragCoord for scene pixels (its lights, its pattern shifted by the
//   camera) or the output's size for the canvas's fails.
// - camera-scale (ABI 1.2): the same scene through a camera over the whole canvas at scale 1/2.
//   Each output pixel must lie within the range the whole render takes over the 2x2 scene
//   pixels it covers and kCameraScaleReach around them, widened by the plugin's declared
//   scale_tolerance (a fraction of the range's largest magnitude). An effect that measures a
//   length in render pixels (a blur of so many texels, a pattern of so many pixels) draws it
//   twice as large in the scene and fails.

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "case_session.hpp"

namespace acetate::harness {

// The case's floors are transparent this many pixels from the canvas's right and bottom edges
// (case_layout), and the canvas grows by this much for canvas-size.
inline constexpr uint32_t kCanvasEdgeBand = 8;
inline constexpr uint32_t kCanvasGrowth[2] = {61, 43};
// Where the canvas lands in the camera-region relation's output (which is this much larger on
// every side): odd, and different on the two axes, so no pattern of 2 or 4 pixels hides a shift.
inline constexpr uint32_t kCameraShift[2] = {13, 7};
// How far the render at 1/2 may lie outside the whole render's range, in half-float units at
// the range's largest value: its inputs are the tiles averaged over 2x2 pixels and rounded to
// the target's half float, once more than the whole render's, and its output rounds once.
inline constexpr float kCameraScaleUnits = 2;
// The scene pixels around an output pixel's 2x2 that the whole render's range takes in: at 1/2
// the tiles reach an effect averaged over 2x2 pixels, so a neighbour read one scene pixel away
// mixes in pixels one further.
inline constexpr uint32_t kCameraScaleReach = 1;
// How far rgba32f and rgba16f may drift apart, in units in the last place of a half float at
// the larger of the value and the input's largest value. The output's own rounding is half a
// unit; each pass through a target of the floor's format, and each blend onto one, rounds
// again, and an effect can amplify that. Of the shipped plugins fire goes furthest, 4.7 units
// over six seeds: its particles are blended one onto another.
inline constexpr float kFormatAgreementUnits = 8;

// The relation `c.spec.relation` for the plugin outputs `floors` (their `output`), rendered
// from the case's scene with `params`; heat maps per floor into `heat`.
Result<CheckResult> check_relation(const CaseContext& c, Session& s, CaseWriter& w,
                                   const nlohmann::json& params, const std::string& name,
                                   const std::vector<FloorImages>& floors,
                                   std::map<int64_t, ImageRGBA>& heat);

// One unit in the last place of a half float at |v| (2^-24 below the smallest normal half).
float half_ulp(float v);

}  // namespace acetate::harness
