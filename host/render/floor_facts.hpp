#pragma once
// What build() is told about its floor: the AcetateFloorInfo of one effect instance (ABI 1.0,
// 1.1 and 1.2 fields) and everything it points to, made from the scene's description of the floor
// and the instance's parameters. The host's load and `acetate check-shaders` both use it.

#include <acetate/effect.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/view_transform.hpp"
#include "plugins/effect_descriptor.hpp"
#include "plugins/resolve_params.hpp"
#include "scene/scene.hpp"

namespace acetate {

// Everything AcetateFloorInfo points to, kept alive for the duration of build().
struct FloorFacts {
    std::string floor_name;
    std::vector<AcetateLight> lights;           // ABI 1.0's view
    std::vector<AcetateLightInfo> light_infos;  // 1.1: point lights, then the sun
    std::vector<const AcetateLightInfo*> light_pointers;
    std::vector<const char*> masks_present;
    std::vector<float> params;         // x of each parameter (1.0)
    std::vector<float> param_vectors;  // 4 per parameter (1.1)
    AcetateFloorInfo info{};
};

// Fills `facts` for an instance on `floor` of `scene` (-1: a global instance) rendered through
// `view` (its scale and output size; ViewTransform::whole without a camera). `facts` must not
// move afterwards: `facts.info` points into it.
void describe_floor(const SceneDesc& scene, int64_t floor, const EffectDescriptor& d,
                    const ParamVectors& params, const ViewTransform& view, FloorFacts& facts);

}  // namespace acetate
