// The warm-up at load. lavapipe compiles a pipeline's shaders at its first draw (30-100 ms
// each: docs/design.md, "Facts about lavapipe"), so every pipeline in use draws one pixel here
// and the first real frame does not stall (L-warm-switch). It also clears every target whole,
// and poisons the effects' own targets when the harness asks.
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
    // The shared images stand for the roles here: the floor's colour target is the first, an
    // effect's "result" the last (the same image when there is one).
    std::vector<GpuImage>& shared = targets_.shared();
    GpuImage* floor_colour = targets_.has(SharedRole::FloorColour) ? &shared.front() : nullptr;
    auto draw_one_pixel = [&](VkCommandBuffer cmd, HostPass pass, GpuImage& target, bool stencil,
                              VkImageView input, VkSampler tile_sampler = VK_NULL_HANDLE) {
        const StencilAttachment stencil_attachment{targets_.floor_stencil(), LoadOp::Clear, 1,
                                                   true};
        begin_rendering(cmd, pixel, {&target, LoadOp::Clear},
                        stencil ? &stencil_attachment : nullptr);
        set_scissor(cmd, pixel);
        // The same sampler as the real draws: lavapipe's shader variants depend on it too.
        const bool is_tile_pass = pass == HostPass::TileToTarget || pass == HostPass::TileToAccum;
        bind(cmd, pass, input, input, is_tile_pass ? tile_sampler : pipelines_->nearest_sampler());
        if (is_tile_pass) {
            TilePushConstants push;
            push.tile_rect[2] = push.tile_rect[3] = 1;
            push.canvas_size[0] = float(width_);
            push.canvas_size[1] = float(height_);
            pipelines_->push(cmd, push);
        } else if (pass == HostPass::Output) {
            pipelines_->push(cmd, OutputPushConstants{});
        } else if (pass == HostPass::Composite || pass == HostPass::CompositeByAlpha) {
            pipelines_->push(cmd, CompositePushConstants{});
        } else {
            pipelines_->push(cmd, InjectPushConstants{});
        }
        vkCmdDraw(cmd, is_tile_pass ? 4 : 3, 1, 0, 0);
        vkCmdEndRendering(cmd);
    };
    return context_.submit_and_wait([&](VkCommandBuffer cmd) {
        // Clearing every target whole makes the driver commit their memory now: on lavapipe
        // the first touch of a fresh 1080p target otherwise costs the first frame ~20 ms. It
        // also means no target ever holds what the allocation happened to contain: an effect
        // that reads a target it wrote only in part reads zeros (or the one pixel the warm-up
        // below draws), the same in every process.
        for (GpuImage* target : targets_.images()) {
            if (target == targets_.floor_stencil())
                clear_stencil_image(cmd, *target);
            else
                clear_image(cmd, *target);
        }
        // Inputs are sampled while another image is the attachment: the output is drawn with
        // the accumulation as input, everything else with a tile texture or the output.
        if (options_.plan.draw_direct)
            for (const auto& [texture, sampler] : textures)
                draw_one_pixel(cmd, HostPass::TileToAccum, accumulation, false, texture->view(),
                               sampler);
        output.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        if (floor_colour) {
            for (const auto& [texture, sampler] : textures)
                draw_one_pixel(cmd, HostPass::TileToTarget, *floor_colour, true, texture->view(),
                               sampler);
            if (options_.inject)
                draw_one_pixel(cmd, inject_pass(), *floor_colour, true, output.view());
            draw_one_pixel(cmd, HostPass::Composite, accumulation, true, output.view());
            for (uint32_t f = 0; f < floor_count(); ++f)
                if (expands(f)) {
                    draw_one_pixel(cmd, HostPass::CompositeByAlpha, accumulation, true,
                                   output.view());
                    break;
                }
        }
        accumulation.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        draw_one_pixel(cmd, HostPass::Output, output, false, accumulation.view());
        // Every effect pass too, reading the (cleared) output and writing one pixel.
        auto warm_effect = [&](EffectInstance& effect, GpuImage& result) {
            EffectIo io = effect_io(0);
            io.previous = &output;
            io.result = &result;
            io.result_scissor = pixel;
            io.timer = nullptr;
            io.warm_up = true;
            FloorFrameReport ignored;
            record_effect(cmd, renderer_, effect, io, ignored);
        };
        for (auto& floor : floor_effects_)
            for (auto& effect : floor) warm_effect(*effect, shared.back());
        for (auto& effect : global_effects_) warm_effect(*effect, shared.back());
        // Poisoned after the warm-up, which wrote a pixel of some targets: until an effect
        // writes it, every texel reads as the poison. Once only: what one floor or frame
        // wrote must stay for the next (a plugin reading it is then caught by the isolation
        // checks, not by the poison).
        if (options_.poison)
            for (GpuImage* target : targets_.effect_targets().images())
                clear_image(cmd, *target, *options_.poison);
    });
}

}  // namespace acetate
