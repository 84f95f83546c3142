#pragma once
// A frame as the compositor runs it: its passes, host and effect passes alike, each a
// FramePassDecl (what it reads and writes) and what records it, compiled once per frame shape by
// compile_frame_graph (frame_graph.hpp) and then executed every frame: the planned barriers
// before each pass in one command, then the pass. A FrameBuilder names the images and collects
// the passes; Compositor::compile_frame (floor_recording.cpp) is the one that builds frames.

#include <vulkan/vulkan.h>

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/frame_graph.hpp"
#include "render/frame_stats.hpp"
#include "vulkan/gpu_image.hpp"

namespace acetate {

// What a pass is given when it records.
struct PassRecording {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    double time = 0;                                  // what effects animate with
    FloorFrameReport* report = nullptr;               // where its passes and pixels are counted
    std::vector<FloorFrameReport>* floors = nullptr;  // every floor's (a pass of several floors)
};

// Where a pass counts what it shades: a floor's report (its index in the frame's reports), the
// global effects' report, or the frame's own total (the output pass).
enum class ReportSlot : int32_t { Global = -1, Frame = -2 };
using ReportIndex = int32_t;  // >= 0: a floor report; or a ReportSlot

struct FramePass {
    FramePassDecl decl;
    ReportIndex report = ReportIndex(ReportSlot::Frame);
    std::function<void(PassRecording&)> record;
};

class CompiledFrame {
  public:
    CompiledFrame() = default;
    CompiledFrame(std::vector<FramePass> passes, std::vector<GpuImage*> images,
                  const std::vector<bool>& read_after, std::vector<FloorFrameReport> reports,
                  std::optional<FloorFrameReport> global);

    // Records the frame into `cmd`: each pass that runs, after its planned barriers. Fills
    // stats' floor and global reports and adds their passes and pixels to the totals.
    void execute(VkCommandBuffer cmd, double time, FrameStats& stats) const;

    const FrameGraphPlan& plan() const { return plan_; }
    const std::vector<FramePass>& passes() const { return passes_; }
    const std::vector<GpuImage*>& images() const { return images_; }

  private:
    std::vector<FramePass> passes_;
    std::vector<GpuImage*> images_;
    FrameGraphPlan plan_;
    std::vector<std::vector<ImageTransition>> transitions_;  // plan_.barriers in Vulkan terms
    std::vector<FloorFrameReport> reports_;  // in order, counts zero: copied into each frame
    std::optional<FloorFrameReport> global_;
};

// Collects a frame's passes, numbering each image the first time a pass names it.
class FrameBuilder {
  public:
    void add(std::string name, std::vector<std::pair<GpuImage*, ImageAccess>> uses,
             ReportIndex report, std::function<void(PassRecording&)> record, bool sink = false);
    // Compiles what was added; `read_after`: images read after the frame (null entries are
    // ignored).
    CompiledFrame compile(const std::vector<const GpuImage*>& read_after,
                          std::vector<FloorFrameReport> reports,
                          std::optional<FloorFrameReport> global);
    // The plan alone (which passes run, each image's first and last use), for a frame built to
    // learn when its images are used and then built again over other images.
    FrameGraphPlan plan(const std::vector<const GpuImage*>& read_after) const;
    // Removes the passes at these indices (in the order they were added), before compile().
    void drop(const std::vector<uint32_t>& passes);
    // Every image named so far: its index is its number in the plan.
    const std::vector<GpuImage*>& images() const { return images_; }
    // One flag per image: whether `read_after` names it.
    std::vector<bool> read_flags(const std::vector<const GpuImage*>& read_after) const;

  private:
    uint32_t id(GpuImage* image);
    std::vector<FramePass> passes_;
    std::vector<GpuImage*> images_;
};

}  // namespace acetate
