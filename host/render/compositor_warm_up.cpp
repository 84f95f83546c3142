// The warm-up at load. lavapipe compiles a pipeline's shaders at its first draw (30-100 ms
// each: docs/design.md, "Facts about lavapipe"), so every pipeline in use draws one pixel here
// and the first real frame does not stall (L-warm-switch). It also clears every target whole,
// and poisons the effects' own targets when the harness asks. Its passes are a compiled frame
// (render/compiled_frame.hpp), as a render's are: the barriers between them are planned.
#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "render/compositor.hpp"  // the class whose warm-up this is
#include "render/renderer.hpp"
#include "vulkan/render_commands.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

Result<void> Compositor::warm_pipelines() {
    GpuBuffer& violations = targets_.violations();
    std::memset(violations.mapped(), 0, violations.size());
    // lavapipe keys its shader variants on texture and sampler state too (a power-of-two
    // texture and another size compile apart, nearest and linear too), so the tile passes draw
    // once with every distinct texture and the sampler each of its tiles is drawn with.
    std::vector<std::pair<const GpuImage*, VkSampler>> textures;
    for (const LoadedFloor& f : resources_->floors())
        for (const LoadedTile& t : f.tiles)
            if (const std::pair used{t.texture, tile_sampler(t)};
                std::find(textures.begin(), textures.end(), used) == textures.end())
                textures.push_back(used);
    const PixelRect pixel{0, 0, 1, 1};
    GpuImage& accumulation = targets_.accumulation();
    GpuImage& output = targets_.output();
    GpuImage* stencil = targets_.floor_stencil();
    // The shared images stand for the roles here: the floor's colour target is the first, an
    // effect's "result" the last (the same image when there is one).
    std::vector<GpuImage>& shared = targets_.shared();
    GpuImage* floor_colour = targets_.has(SharedRole::FloorColour) ? &shared.front() : nullptr;

    // A compiled frame like any other, but every pass is a sink: nothing reads what it draws,
    // it runs for what it leaves behind (compiled shaders, committed memory, cleared targets).
    FrameBuilder frame;
    auto add = [&](std::string name, std::vector<std::pair<GpuImage*, ImageAccess>> uses,
                   std::function<void(PassRecording&)> record) {
        frame.add(std::move(name), std::move(uses), ReportIndex(ReportSlot::Frame),
                  std::move(record), true);
    };
    // Clearing every target whole makes the driver commit their memory now: on lavapipe the
    // first touch of a fresh 1080p target otherwise costs the first frame ~20 ms. It also means
    // no target ever holds what the allocation happened to contain: an effect that reads a
    // target it wrote only in part reads zeros (or the one pixel the warm-up below draws), the
    // same in every process.
    for (GpuImage* target : targets_.images())
        add("clear " + target->name(), {{target, ImageAccess::TransferWrite}},
            [target, is_stencil = target == stencil](PassRecording& r) {
                if (is_stencil)
                    clear_stencil(r.cmd, *target);
                else
                    clear_image(r.cmd, *target);
            });
    // One pixel drawn with `pass` into `target` (and the stencil), sampling `input`: a tile
    // texture (written at load only, so not a use the frame orders) or a target.
    auto draw_one_pixel = [&](HostPass pass, GpuImage& target, bool with_stencil,
                              const GpuImage& input, VkSampler tile_sampler = VK_NULL_HANDLE) {
        std::vector<std::pair<GpuImage*, ImageAccess>> uses{{&target, ImageAccess::ColourWrite}};
        if (with_stencil) uses.emplace_back(stencil, ImageAccess::StencilWrite);
        if (&input == &output || &input == &accumulation)
            uses.emplace_back(const_cast<GpuImage*>(&input), ImageAccess::Sampled);
        add(fmt::format("warm {} into {}", host_pass_name(pass), target.name()), std::move(uses),
            [this, pass, &target, with_stencil, &input, tile_sampler, pixel](PassRecording& r) {
                const StencilAttachment stencil_attachment{targets_.floor_stencil(), LoadOp::Clear,
                                                           1, true};
                begin_rendering(r.cmd, pixel, {&target, LoadOp::Clear},
                                with_stencil ? &stencil_attachment : nullptr);
                set_scissor(r.cmd, pixel);
                // The same sampler as the real draws: lavapipe's shader variants depend on it.
                const bool is_tile_pass =
                    pass == HostPass::TileToTarget || pass == HostPass::TileToAccum;
                bind(r.cmd, pass, input.view(), input.view(),
                     is_tile_pass ? tile_sampler : pipelines_->nearest_sampler());
                if (is_tile_pass) {
                    TilePushConstants push;
                    push.tile_rect[2] = push.tile_rect[3] = 1;
                    push.canvas_size[0] = float(width_);
                    push.canvas_size[1] = float(height_);
                    pipelines_->push(r.cmd, push);
                } else if (pass == HostPass::Output) {
                    pipelines_->push(r.cmd, OutputPushConstants{});
                } else if (pass == HostPass::Composite || pass == HostPass::CompositeByAlpha) {
                    pipelines_->push(r.cmd, CompositePushConstants{});
                } else {
                    pipelines_->push(r.cmd, InjectPushConstants{});
                }
                vkCmdDraw(r.cmd, is_tile_pass ? 4 : 3, 1, 0, 0);
                vkCmdEndRendering(r.cmd);
            });
    };
    // Inputs are sampled while another image is the attachment: the output is drawn with the
    // accumulation as input, everything else with a tile texture or the output.
    if (options_.plan.draw_direct)
        for (const auto& [texture, sampler] : textures)
            draw_one_pixel(HostPass::TileToAccum, accumulation, false, *texture, sampler);
    if (floor_colour) {
        for (const auto& [texture, sampler] : textures)
            draw_one_pixel(HostPass::TileToTarget, *floor_colour, true, *texture, sampler);
        if (options_.inject) draw_one_pixel(inject_pass(), *floor_colour, true, output);
        draw_one_pixel(HostPass::Composite, accumulation, true, output);
        for (uint32_t f = 0; f < floor_count(); ++f)
            if (expands(f)) {
                draw_one_pixel(HostPass::CompositeByAlpha, accumulation, true, output);
                break;
            }
    }
    draw_one_pixel(HostPass::Output, output, false, accumulation);
    // Every effect pass too, reading the (cleared) output and writing one pixel.
    for (auto& floor : floor_effects_)
        for (auto& effect : floor)
            add_effect_passes(frame, {effect.get(), &output, &shared.back(), pixel, nullptr,
                                      ReportIndex(ReportSlot::Frame), true});
    for (auto& effect : global_effects_)
        add_effect_passes(frame, {effect.get(), &output, &shared.back(), pixel, nullptr,
                                  ReportIndex(ReportSlot::Frame), true});
    // Poisoned after the warm-up, which wrote a pixel of some targets: until an effect writes
    // it, every texel reads as the poison. Once only: what one floor or frame wrote must stay
    // for the next (a plugin reading it is then caught by the isolation checks, not by the
    // poison).
    if (options_.poison)
        for (GpuImage* target : targets_.effect_targets().images())
            add("poison " + target->name(), {{target, ImageAccess::TransferWrite}},
                [this, target](PassRecording& r) {
                    clear_image(r.cmd, *target, *options_.poison);
                });
    const CompiledFrame compiled = frame.compile({}, {}, std::nullopt);
    FrameStats ignored;
    return context_.submit_and_wait(
        [&](VkCommandBuffer cmd) { compiled.execute(cmd, 0, ignored); });
}

}  // namespace acetate
