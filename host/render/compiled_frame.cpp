#include "render/compiled_frame.hpp"

#include <algorithm>
#include <cassert>

namespace acetate {
namespace {

// The layout, stages and accesses of each way a pass uses an image.
struct AccessScope {
    VkImageLayout layout;
    VkPipelineStageFlags2 stages;
    VkAccessFlags2 access;
};

AccessScope scope(ImageAccess access) {
    constexpr VkPipelineStageFlags2 kTests =
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    switch (access) {
        case ImageAccess::None:
            break;
        case ImageAccess::TransferWrite:
            return {VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT};
        case ImageAccess::ColourWrite:
            return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
        case ImageAccess::StencilWrite:
            return {VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, kTests,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
        case ImageAccess::StencilTest:
            return {VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, kTests,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT};
        case ImageAccess::Sampled:
            return {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    }
    // Before its first use in a frame an image may have been written by anything (the last
    // frame, a read-back, the load's clears), so the first barrier waits for all of it.
    return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
            VK_ACCESS_2_MEMORY_WRITE_BIT};
}

ImageTransition transition(GpuImage* image, const ImageBarrier& barrier) {
    ImageTransition t;
    t.image = image;
    for (uint32_t a = 0; a <= uint32_t(ImageAccess::Sampled); ++a) {
        if (!(barrier.since & (1u << a)) && !(a == 0 && barrier.last == ImageAccess::None))
            continue;
        const AccessScope before = scope(ImageAccess(a));
        t.src_stages |= before.stages;
        // Only writes need making available; a read before a write needs the stages alone.
        if (is_write(ImageAccess(a)) || a == 0) t.src_access |= before.access;
    }
    const AccessScope after = scope(barrier.next);
    t.dst_stages = after.stages;
    t.dst_access = after.access;
    t.layout = after.layout;
    return t;
}

}  // namespace

CompiledFrame::CompiledFrame(std::vector<FramePass> passes, std::vector<GpuImage*> images,
                             const std::vector<bool>& read_after,
                             std::vector<FloorFrameReport> reports,
                             std::optional<FloorFrameReport> global)
    : passes_(std::move(passes)),
      images_(std::move(images)),
      reports_(std::move(reports)),
      global_(std::move(global)) {
    std::vector<FramePassDecl> decls;
    decls.reserve(passes_.size());
    for (const FramePass& pass : passes_) decls.push_back(pass.decl);
    plan_ = compile_frame_graph(decls, read_after);
    // The barriers' stages and accesses are the plan's: worked out here once, not per frame.
    for (const std::vector<ImageBarrier>& batch : plan_.barriers) {
        std::vector<ImageTransition>& out = transitions_.emplace_back();
        for (const ImageBarrier& barrier : batch)
            out.push_back(transition(images_[barrier.image], barrier));
    }
}

void CompiledFrame::execute(VkCommandBuffer cmd, double time, FrameStats& stats) const {
    stats.floors = reports_;
    stats.global = global_;
    stats.frame_passes = uint32_t(plan_.passes.size());
    stats.frame_passes_culled = uint32_t(plan_.culled.size());
    FloorFrameReport frame;  // the output pass's count, straight into the totals
    for (size_t i = 0; i < plan_.passes.size(); ++i) {
        const FramePass& pass = passes_[plan_.passes[i]];
        if (!transitions_[i].empty())
            GpuImage::record_barrier(cmd, transitions_[i].data(), transitions_[i].size());
        PassRecording recording{cmd, time, &frame, &stats.floors};
        if (pass.report >= 0)
            recording.report = &stats.floors[size_t(pass.report)];
        else if (pass.report == ReportIndex(ReportSlot::Global) && stats.global)
            recording.report = &*stats.global;
        pass.record(recording);
    }
    auto add = [&](const FloorFrameReport& report) {
        stats.passes += report.passes;
        stats.pixels_shaded += report.pixels_shaded;
    };
    for (const FloorFrameReport& report : stats.floors) add(report);
    if (stats.global) add(*stats.global);
    add(frame);
}

void FrameBuilder::add(std::string name, std::vector<std::pair<GpuImage*, ImageAccess>> uses,
                       ReportIndex report, std::function<void(PassRecording&)> record, bool sink) {
    FramePass pass;
    pass.decl.name = std::move(name);
    pass.decl.sink = sink;
    for (const auto& [image, access] : uses) {
        assert(image);
        pass.decl.uses.push_back({id(image), access});
    }
    pass.report = report;
    pass.record = std::move(record);
    passes_.push_back(std::move(pass));
}

uint32_t FrameBuilder::id(GpuImage* image) {
    const auto found = std::find(images_.begin(), images_.end(), image);
    if (found != images_.end()) return uint32_t(found - images_.begin());
    images_.push_back(image);
    return uint32_t(images_.size() - 1);
}

std::vector<bool> FrameBuilder::read_flags(const std::vector<const GpuImage*>& read_after) const {
    std::vector<bool> read(images_.size(), false);
    for (const GpuImage* image : read_after)
        for (size_t i = 0; i < images_.size(); ++i)
            if (images_[i] == image) read[i] = true;
    return read;
}

FrameGraphPlan FrameBuilder::plan(const std::vector<const GpuImage*>& read_after) const {
    std::vector<FramePassDecl> decls;
    decls.reserve(passes_.size());
    for (const FramePass& pass : passes_) decls.push_back(pass.decl);
    return compile_frame_graph(decls, read_flags(read_after));
}

void FrameBuilder::drop(const std::vector<uint32_t>& passes) {
    std::vector<bool> dropped(passes_.size(), false);
    for (uint32_t index : passes) dropped.at(index) = true;
    size_t kept = 0;
    for (size_t i = 0; i < passes_.size(); ++i) {
        if (dropped[i]) continue;
        if (kept != i) passes_[kept] = std::move(passes_[i]);  // not onto itself: that empties it
        ++kept;
    }
    passes_.resize(kept);
}

CompiledFrame FrameBuilder::compile(const std::vector<const GpuImage*>& read_after,
                                    std::vector<FloorFrameReport> reports,
                                    std::optional<FloorFrameReport> global) {
    const std::vector<bool> read = read_flags(read_after);
    return CompiledFrame(std::move(passes_), std::move(images_), read, std::move(reports),
                         std::move(global));
}

}  // namespace acetate
