#include "render/floor_facts.hpp"

#include <algorithm>
#include <array>

#include "render/effect_runtime.hpp"

namespace acetate {

void describe_floor(const SceneDesc& scene, int64_t floor, const EffectDescriptor& d,
                    const ParamVectors& params, const ViewTransform& view, FloorFacts& facts) {
    if (floor >= 0) {
        const FloorDesc& f = scene.floors[size_t(floor)];
        facts.floor_name = f.name;
        for (const LightDesc& l : f.lights) {
            facts.lights.push_back({{l.pos[0], l.pos[1]},
                                    l.radius,
                                    {l.color[0], l.color[1], l.color[2]},
                                    l.intensity});
            AcetateLightInfo info{sizeof(AcetateLightInfo), ACETATE_LIGHT_POINT};
            info.pos[0] = l.pos[0], info.pos[1] = l.pos[1];
            info.height = l.height;
            info.radius = l.radius;
            std::copy(l.color.begin(), l.color.end(), info.color);
            info.intensity = l.intensity;
            facts.light_infos.push_back(info);
        }
        if (f.sun) {
            AcetateLightInfo info{sizeof(AcetateLightInfo), ACETATE_LIGHT_SUN};
            const std::array<float, 3> direction = f.sun->direction();
            std::copy(direction.begin(), direction.end(), info.direction);
            std::copy(f.sun->color.begin(), f.sun->color.end(), info.color);
            info.intensity = f.sun->intensity;
            facts.light_infos.push_back(info);
        }
        for (const std::string& kind : d.masks)
            if (std::any_of(f.tiles.begin(), f.tiles.end(),
                            [&](const TileDesc& t) { return t.masks.count(kind) != 0; }))
                facts.masks_present.push_back(kind.c_str());
    }
    for (const AcetateLightInfo& l : facts.light_infos) facts.light_pointers.push_back(&l);
    for (const auto& v : params) {
        facts.params.push_back(v[0]);
        facts.param_vectors.insert(facts.param_vectors.end(), v.begin(), v.end());
    }
    AcetateFloorInfo& info = facts.info;
    info.struct_size = sizeof(info);
    info.floor_index = floor < 0 ? UINT32_MAX : uint32_t(floor);
    info.floor_name = facts.floor_name.c_str();
    info.canvas_width = scene.width;
    info.canvas_height = scene.height;
    info.lights = facts.lights.empty() ? nullptr : facts.lights.data();
    info.light_count = uint32_t(facts.lights.size());
    info.params = facts.params.data();
    info.param_count = uint32_t(facts.params.size());
    info.masks_present = facts.masks_present.empty() ? nullptr : facts.masks_present.data();
    info.masks_present_count = uint32_t(facts.masks_present.size());
    info.light_infos = facts.light_pointers.empty() ? nullptr : facts.light_pointers.data();
    info.light_info_count = uint32_t(facts.light_pointers.size());
    const PixelRect bounds = floor < 0 ? PixelRect{0, 0, scene.width, scene.height}
                                       : floor_coverage_bounds(scene, size_t(floor));
    info.coverage_bounds[0] = int32_t(bounds.x0), info.coverage_bounds[1] = int32_t(bounds.y0);
    info.coverage_bounds[2] = int32_t(bounds.x1), info.coverage_bounds[3] = int32_t(bounds.y1);
    info.floor_count = uint32_t(scene.floors.size());
    info.param_vectors = facts.param_vectors.data();
    info.host_abi_minor = ACETATE_ABI_MINOR;
    info.render_scale = float(view.scale);
    info.render_width = view.width;
    info.render_height = view.height;
}

}  // namespace acetate
