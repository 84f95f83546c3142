// Compositor::necessary_pixels (compositor.hpp): the floor of what any renderer of this frame
// must shade, so FrameStats::pixels_shaded can be judged against it.
#include <algorithm>
#include <cmath>
#include <span>

#include "render/compositor.hpp"

namespace acetate {

uint64_t Compositor::necessary_pixels(uint32_t active_floor) const {
    const PixelRect canvas{0, 0, int64_t(width_), int64_t(height_)};
    // Floors the planner finds hidden under opaque floors above cannot show: nothing of them
    // is necessary.
    const FramePlan plan = plan_frame(width_, height_, geometry_, active_floor, PlanOptions{});
    uint64_t pixels = uint64_t(canvas.area());  // the output pass writes every pixel
    for (const FloorStep& step : plan.steps) {
        if (step.path == FloorPath::Skipped) continue;
        const LoadedFloor& floor = resources_->floors()[step.floor];
        std::vector<PixelRect> covered;
        for (size_t t = 0; t < floor.tiles.size(); ++t) {
            const PixelRect shaded = intersect(tile_pixels_[step.floor][t], canvas);
            pixels += uint64_t(shaded.area());  // each layer's pixels are blended once
            covered.push_back(shaded);
        }
        const auto& all_effects = floor_effects_[step.floor];
        const size_t run = std::min<size_t>(all_effects.size(), floor_effects_run_);
        if (run == 0 || !effects_enabled_) continue;
        const std::span effects(all_effects.data(), run);
        // What the floor's effects may change: its tiles' pixels, each grown by the reach the
        // expanding effects declared (all of the output for one that declared none), scene
        // pixels through the camera's scale.
        int64_t reach = 0;
        bool unbounded = false;
        for (const auto& e : effects)
            if (e->expanding) {
                if (e->reach)
                    reach += *e->reach;
                else
                    unbounded = true;
            }
        reach = int64_t(std::ceil(double(reach) * view_.scale));
        std::vector<PixelRect> grown;
        for (const PixelRect& r : covered)
            grown.push_back(intersect(
                canvas, PixelRect{r.x0 - reach, r.y0 - reach, r.x1 + reach, r.y1 + reach}));
        const uint64_t area = unbounded ? uint64_t(canvas.area()) : union_area(grown);
        for (const auto& e : effects)
            for (const EffectPassRuntime& pass : e->passes) {
                if (pass.instance_count)
                    pixels += pass.instanced_pixels;  // its quads bound what it draws
                else if (!pass.target)                // "result"
                    pixels += area;
                else  // the effect's own target (a mip level, a mask): all of it
                    pixels += uint64_t(pass.target->width()) * pass.target->height();
            }
        pixels += area;  // the composite over the accumulation
    }
    const size_t global_run = std::min<size_t>(global_effects_.size(), global_effects_run_);
    for (size_t i = 0; i < global_run; ++i)
        for (const EffectPassRuntime& pass : global_effects_[i]->passes)
            pixels += !pass.target ? uint64_t(canvas.area())
                                   : uint64_t(pass.target->width()) * pass.target->height();
    return pixels;
}

}  // namespace acetate
