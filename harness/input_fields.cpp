// Every field a plugin can observe, with its edges and the case that tries each
// (input_model.hpp, InputField). Kept beside the planner's case ids: a case renamed or dropped
// fails tests/unit/input_fields_test.cpp, as does a field added to the format without a line
// here.
#include "input_model.hpp"

namespace acetate::harness {
namespace {

InputField observed(std::string field, std::string dimension, std::vector<InputEdge> edges) {
    return {std::move(field), std::move(dimension), std::move(edges), ""};
}
InputField unobserved(std::string field, std::string why) {
    return {std::move(field), "", {}, std::move(why)};
}

// Edges shared by a scene field and the ABI member that carries it.
const std::vector<InputEdge> kWidths = {{"1", "sizes/1x1"},
                                        {"odd", "sizes/odd"},
                                        {"the large size (1920 at strictness 5)", "sizes/large"},
                                        {"2048, three floors", "sizes/wide-floors"}};
const std::vector<InputEdge> kHeights = {{"1", "sizes/thin"},
                                         {"odd", "sizes/even-odd"},
                                         {"the large size (1080 at strictness 5)", "sizes/large"}};
const std::vector<InputEdge> kFloorCounts = {{"1", "contract/standard"},
                                             {"8", "floors/eight"},
                                             {"3 on a 2048x40 canvas", "sizes/wide-floors"}};
const std::vector<InputEdge> kNames = {{"floor<N>", "contract/standard"},
                                       {"300 characters", "floors/long-names"},
                                       {"beyond ASCII (UTF-8)", "floors/unicode-names"}};
const std::vector<InputEdge> kLightLists = {
    {"none", "lights/none"}, {"one", "lights/one"}, {"100, over any preset's cap", "lights/many"}};
const std::vector<InputEdge> kPositions = {
    {"off the canvas", "lights/off-canvas"},
    {"whole-pixel corners: (0, 0) and (width, height)", "lights/on-the-floor"}};
const std::vector<InputEdge> kRadii = {{"10^-4", "lights/tiny-radius"},
                                       {"10^6", "lights/huge-radius"}};
const std::vector<InputEdge> kDark = {{"0", "lights/dark"}};
const std::vector<InputEdge> kHeightsAboveFloor = {{"exactly 0", "lights/on-the-floor"},
                                                   {"up to 0.6 radius", "contract/standard"}};
const std::vector<InputEdge> kParams = {{"every one at its minimum", "params/min"},
                                        {"every one at its maximum", "params/max"},
                                        {"each over its range", "params/sweep-{param}"}};
const std::vector<InputEdge> kMasksPresent = {{"absent", "masks/absent"},
                                              {"present", "contract/standard"}};
const std::vector<InputEdge> kRenderSizes = {
    {"the canvas: no camera", "contract/standard"},
    {"larger than the canvas: a camera's region around it", "relations/camera-region"},
    {"half the canvas's: the whole canvas at scale 1/2", "relations/camera-scale"}};
const std::vector<InputEdge> kRenderScales = {{"1", "contract/standard"},
                                              {"1/2", "relations/camera-scale"}};
const std::vector<InputEdge> kPluginFloor = {{"floor 0 (of one)", "contract/standard"},
                                             {"floor 1 of two", "floors/one-of-two"},
                                             {"floor 4 of five", "floors/top-of-five"}};

}  // namespace

const std::vector<InputField>& input_fields() {
    static const std::vector<InputField> fields = {
        // ---- docs/scene-format.md ----
        unobserved("scene.format", "checked by the host before any other field"),
        observed("scene.canvas", "canvas",
                 {{"1x1", "sizes/1x1"}, {"the large size", "sizes/large"}}),
        observed("scene.floors", "floors", kFloorCounts),
        observed("scene.global_effects", "plugin floor",
                 {{"the plugin alone (or none, for a floor effect)", "contract/standard"},
                  {"the other integrated plugins' global effects", "integration/stack"}}),
        observed("scene.active_floor", "plugin floor",
                 {{"the top floor", "contract/standard"},
                  {"floors 0, 1, 0 in turn", "isolation/state"}}),
        observed("canvas.width", "canvas", kWidths),
        observed("canvas.height", "canvas", kHeights),
        unobserved("canvas.background",
                   "added at output, after every effect; global effects see the composite "
                   "without it"),
        observed("floor.name", "floor names and tiles", kNames),
        observed("floor.tiles", "floor names and tiles",
                 {{"one", "contract/standard"}, {"none", "floors/top-floor-empty"}}),
        observed("floor.lights", "lights", kLightLists),
        observed("floor.sun", "lights",
                 {{"none", "contract/standard"},
                  {"elevation 0", "lights/grazing-sun"},
                  {"elevation 90", "lights/zenith-sun"}}),
        observed("floor.effects", "plugin floor", kPluginFloor),
        observed("tile.image", "pixels",
                 {{"alpha 0 everywhere", "inputs/empty"},
                  {"alpha 1 everywhere", "inputs/opaque"},
                  {"alpha 2^-24 under colour up to 1000 times alpha", "inputs/subnormal"},
                  {"colour 65504", "inputs/hdr"},
                  {"alpha from 1 to 1/65535", "inputs/alpha-ramp"}}),
        observed("tile.rect", "floors",
                 {{"the whole canvas", "contract/standard"},
                  {"part of the canvas, touching its edges", "contract/three-floors"},
                  {"one pixel", "sizes/1x1"}}),
        observed("tile.masks", "masks",
                 {{"absent", "masks/absent"},
                  {"0", "masks/empty"},
                  {"1", "masks/full"},
                  {"half 0", "masks/partial"},
                  {"1 to 4", "masks/above-one"},
                  {"one-pixel lines, at the tile's edges too", "masks/thin"}}),
        observed("light.pos", "lights", kPositions),
        observed("light.radius", "lights", kRadii),
        observed("light.color", "lights", kDark),
        observed("light.intensity", "lights", kDark),
        observed("light.height", "lights", kHeightsAboveFloor),
        observed("sun.azimuth", "lights",
                 {{"-360", "lights/zenith-sun"}, {"200", "lights/grazing-sun"}}),
        observed("sun.elevation", "lights",
                 {{"0", "lights/grazing-sun"}, {"40", "lights/sun"}, {"90", "lights/zenith-sun"}}),
        observed("sun.color", "lights", kDark),
        observed("sun.intensity", "lights", kDark),
        unobserved("effect.plugin", "which plugin runs: the plugin under test's own id"),
        observed("effect.params", "params", kParams),
        observed("effect.preset", "params",
                 {{"each preset", "params/preset-{preset}"},
                  {"a preset with every parameter overridden at its maximum",
                   "params/preset-{preset}-overridden"}}),
        // ---- effect.h: what build() is given ----
        unobserved("AcetateFloorInfo.struct_size", "the host's build, not the scene"),
        observed("AcetateFloorInfo.floor_index", "plugin floor", kPluginFloor),
        observed("AcetateFloorInfo.floor_name", "floor names and tiles", kNames),
        observed("AcetateFloorInfo.canvas_width", "canvas", kWidths),
        observed("AcetateFloorInfo.canvas_height", "canvas", kHeights),
        observed("AcetateFloorInfo.lights", "lights", kLightLists),
        observed("AcetateFloorInfo.light_count", "lights", kLightLists),
        observed("AcetateFloorInfo.params", "params", kParams),
        observed("AcetateFloorInfo.param_count", "params", kParams),
        observed("AcetateFloorInfo.masks_present", "masks", kMasksPresent),
        observed("AcetateFloorInfo.masks_present_count", "masks", kMasksPresent),
        observed("AcetateFloorInfo.light_infos", "lights", kLightLists),
        observed("AcetateFloorInfo.light_info_count", "lights", kLightLists),
        observed("AcetateFloorInfo.coverage_bounds", "floor names and tiles",
                 {{"the whole canvas", "contract/standard"},
                  {"part of the canvas", "contract/three-floors"},
                  {"all 0: no tiles", "floors/top-floor-empty"}}),
        observed("AcetateFloorInfo.floor_count", "floors", kFloorCounts),
        observed("AcetateFloorInfo.param_vectors", "params", kParams),
        unobserved("AcetateFloorInfo.host_abi_minor", "the host's build, not the scene"),
        observed("AcetateFloorInfo.render_scale", "camera", kRenderScales),
        observed("AcetateFloorInfo.render_width", "camera", kRenderSizes),
        observed("AcetateFloorInfo.render_height", "camera", kRenderSizes),
        unobserved("AcetateLightInfo.struct_size", "the host's build, not the scene"),
        observed(
            "AcetateLightInfo.kind", "lights",
            {{"point lights only", "contract/standard"}, {"point lights and a sun", "lights/sun"}}),
        observed("AcetateLightInfo.pos", "lights", kPositions),
        observed("AcetateLightInfo.height", "lights", kHeightsAboveFloor),
        observed("AcetateLightInfo.radius", "lights", kRadii),
        observed("AcetateLightInfo.direction", "lights",
                 {{"exactly (0, 0, 1): overhead", "lights/zenith-sun"},
                  {"on the horizon", "lights/grazing-sun"}}),
        observed("AcetateLightInfo.color", "lights", kDark),
        observed("AcetateLightInfo.intensity", "lights", kDark),
        observed("AcetateLight.pos", "lights", kPositions),
        observed("AcetateLight.radius", "lights", kRadii),
        observed("AcetateLight.color", "lights", kDark),
        observed("AcetateLight.intensity", "lights", kDark),
    };
    return fields;
}

}  // namespace acetate::harness
