#pragma once
// The frame as a list of passes that each say which images they read and write, compiled once
// per frame shape (the active floor, the view, the camera, what runs) into the passes that run
// and the barriers between them: Filament's FrameGraph and Granite's RenderGraph::bake are the
// models. A pass whose writes nothing later reads (and that is no sink) is culled; each image's
// first and last use is known; the barriers a pass needs are planned here, at compile time, and
// recorded together, one pipeline barrier before the pass (frame_barriers.hpp turns them into
// Vulkan). Pure logic: images are numbers here, so this is tested without a device.

#include <cstdint>
#include <string>
#include <vector>

namespace acetate {

// How a pass uses an image. Each maps to one layout and one pipeline stage (frame_barriers.cpp).
enum class ImageAccess : uint8_t {
    None,           // not used yet: its contents before the frame do not matter
    TransferWrite,  // cleared whole by a transfer command (what it held before is gone)
    ColourWrite,    // drawn into as the colour attachment (loads and blends read it too)
    StencilWrite,   // the stencil attachment, written (the tiles mark their coverage)
    StencilTest,    // the stencil attachment, only tested (the composite)
    Sampled,        // read by fragment shaders
};
const char* to_string(ImageAccess access);
bool is_write(ImageAccess access);
// Whether the access reads what the image held: a colour attachment loads and blends over it.
bool reads_contents(ImageAccess access);

struct ImageUse {
    uint32_t image = 0;  // an index into the frame's images
    ImageAccess access = ImageAccess::None;
};

// What the compiler knows of a pass: its name and its uses. The host keeps what records it.
struct FramePassDecl {
    std::string name;
    std::vector<ImageUse> uses;
    bool sink = false;  // runs even when nothing in the frame reads what it writes
};

// One image's barrier before a pass: from every access since the image's last barrier (or from
// its state before the frame) to the pass's access.
struct ImageBarrier {
    uint32_t image = 0;
    // The latest access before (it sets the old layout); None: the image's first use in the
    // frame, from the layout it has when the frame starts.
    ImageAccess last = ImageAccess::None;
    uint32_t since = 0;  // every access since the last barrier, a bit per ImageAccess
    ImageAccess next = ImageAccess::None;
};

// The first and last run pass (indices into FrameGraphPlan::passes) that use an image; an image
// no pass uses has first > last.
struct ImageLifetime {
    uint32_t first = UINT32_MAX;
    uint32_t last = 0;
    bool used() const { return first <= last; }
};

struct FrameGraphPlan {
    std::vector<uint32_t> passes;                     // indices of the passes that run, in order
    std::vector<std::vector<ImageBarrier>> barriers;  // before each of them (empty: none)
    std::vector<ImageLifetime> lifetimes;             // per image
    std::vector<ImageAccess> final_access;            // per image, after the frame
    std::vector<uint32_t> culled;                     // the passes that do not run
    // Barrier commands the frame records: passes with at least one barrier.
    size_t barrier_batches() const;
};

// Compiles `passes` over `read_after.size()` images. `read_after`: the images whose contents are
// read after the frame (the output, read-backs); a pass whose writes feed none of them, through
// any chain of later passes, is culled. Every image gets a barrier before its first use in the
// frame, from whatever state it is in then (ImageAccess::None: the host records it from the
// image's layout at that moment), so a frame does not depend on what ran between frames. A
// pass naming one image twice is a programming error (asserted).
FrameGraphPlan compile_frame_graph(const std::vector<FramePassDecl>& passes,
                                   const std::vector<bool>& read_after);

// Which image each of a frame's interchangeable images becomes (Filament's and Granite's
// aliasing of transient resources): images whose spans of use do not overlap share one. An
// image is shareable when the host declares that no pass reads what it held before the frame
// wrote it; one read after the frame is in use until the frame's end. Images of one slot
// follow each other strictly: one whose last use is the pass that first uses another does not
// share with it.
struct SharedSlots {
    static constexpr uint32_t kNone = UINT32_MAX;  // not shareable, or not used by the frame
    std::vector<uint32_t> slot;                    // per image
    uint32_t count = 0;                            // slots used: the images the frame needs
};
// Slots are given in order of first use, each the lowest one free (an interval graph coloured
// greedily needs no more slots than images in use at once, the fewest possible).
SharedSlots share_images(const FrameGraphPlan& plan, const std::vector<bool>& shareable,
                         const std::vector<bool>& read_after);

}  // namespace acetate
