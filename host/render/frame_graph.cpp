#include "render/frame_graph.hpp"

#include <cassert>

namespace acetate {
namespace {

// Accesses that share a layout need no transition between them, only a memory dependency.
enum class LayoutClass { Undefined, TransferDst, ColourAttachment, StencilAttachment, ShaderRead };

LayoutClass layout_class(ImageAccess access) {
    switch (access) {
        case ImageAccess::None:
            return LayoutClass::Undefined;
        case ImageAccess::TransferWrite:
            return LayoutClass::TransferDst;
        case ImageAccess::ColourWrite:
            return LayoutClass::ColourAttachment;
        case ImageAccess::StencilWrite:
        case ImageAccess::StencilTest:
            return LayoutClass::StencilAttachment;
        case ImageAccess::Sampled:
            return LayoutClass::ShaderRead;
    }
    return LayoutClass::Undefined;
}

uint32_t bit(ImageAccess access) {
    return 1u << uint32_t(access);
}

// What is known of an image between its barriers.
struct ImageState {
    ImageAccess last = ImageAccess::None;
    uint32_t since = 0;    // accesses since its last barrier
    bool written = false;  // some access since then wrote it
    bool read = false;     // some access since then read it
};

}  // namespace

const char* to_string(ImageAccess access) {
    switch (access) {
        case ImageAccess::None:
            return "none";
        case ImageAccess::TransferWrite:
            return "transfer-write";
        case ImageAccess::ColourWrite:
            return "colour-write";
        case ImageAccess::StencilWrite:
            return "stencil-write";
        case ImageAccess::StencilTest:
            return "stencil-test";
        case ImageAccess::Sampled:
            return "sampled";
    }
    return "?";
}

bool is_write(ImageAccess access) {
    return access == ImageAccess::TransferWrite || access == ImageAccess::ColourWrite ||
           access == ImageAccess::StencilWrite;
}

bool reads_contents(ImageAccess access) {
    return access == ImageAccess::ColourWrite || access == ImageAccess::StencilTest ||
           access == ImageAccess::Sampled;
}

size_t FrameGraphPlan::barrier_batches() const {
    size_t count = 0;
    for (const auto& batch : barriers) count += batch.empty() ? 0 : 1;
    return count;
}

FrameGraphPlan compile_frame_graph(const std::vector<FramePassDecl>& passes,
                                   const std::vector<bool>& read_after) {
    const size_t images = read_after.size();
    FrameGraphPlan plan;

    // Culling, from the last pass back: a pass runs when it is a sink or writes an image that is
    // read later (by a pass that runs, or after the frame). A transfer clear replaces the whole
    // image, so what was written into it before is read by nobody through it.
    std::vector<bool> needed = read_after;
    std::vector<bool> runs(passes.size(), false);
    for (size_t p = passes.size(); p-- > 0;) {
        const FramePassDecl& pass = passes[p];
        bool run = pass.sink;
        for (const ImageUse& use : pass.uses) {
            assert(use.image < images);
            if (is_write(use.access) && needed[use.image]) run = true;
        }
        if (!run) continue;
        runs[p] = true;
        for (const ImageUse& use : pass.uses)
            if (use.access == ImageAccess::TransferWrite) needed[use.image] = false;
        for (const ImageUse& use : pass.uses)
            if (reads_contents(use.access)) needed[use.image] = true;
    }

    // Barriers, from the first pass on: one where the layout changes, where anything was written
    // since the image's last barrier (read after write, write after write), and where a write
    // follows reads (write after read). Reads after reads in one layout need none.
    std::vector<ImageState> state(images);
    plan.lifetimes.resize(images);
    for (size_t p = 0; p < passes.size(); ++p) {
        if (!runs[p]) {
            plan.culled.push_back(uint32_t(p));
            continue;
        }
        const uint32_t index = uint32_t(plan.passes.size());
        plan.passes.push_back(uint32_t(p));
        std::vector<ImageBarrier> batch;
        for (size_t u = 0; u < passes[p].uses.size(); ++u) {
            const ImageUse& use = passes[p].uses[u];
            for (size_t v = 0; v < u; ++v) assert(passes[p].uses[v].image != use.image);
            ImageState& s = state[use.image];
            const bool barrier = s.last == ImageAccess::None ||
                                 layout_class(s.last) != layout_class(use.access) || s.written ||
                                 (is_write(use.access) && s.read);
            if (barrier) {
                batch.push_back({use.image, s.last, s.since, use.access});
                s = ImageState{};
            }
            s.last = use.access;
            s.since |= bit(use.access);
            s.written = s.written || is_write(use.access);
            s.read = s.read || !is_write(use.access);
            ImageLifetime& life = plan.lifetimes[use.image];
            if (!life.used()) life.first = index;
            life.last = index;
        }
        plan.barriers.push_back(std::move(batch));
    }
    plan.final_access.resize(images);
    for (size_t i = 0; i < images; ++i) plan.final_access[i] = state[i].last;
    return plan;
}

SharedSlots share_images(const FrameGraphPlan& plan, const std::vector<bool>& shareable,
                         const std::vector<bool>& read_after) {
    const size_t images = plan.lifetimes.size();
    assert(shareable.size() == images && read_after.size() == images);
    SharedSlots out;
    out.slot.assign(images, SharedSlots::kNone);
    std::vector<uint32_t> order;
    for (uint32_t i = 0; i < images; ++i)
        if (shareable[i] && plan.lifetimes[i].used()) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return plan.lifetimes[a].first < plan.lifetimes[b].first;
    });
    const uint32_t frame_end = uint32_t(plan.passes.size());
    std::vector<uint32_t> busy_until;  // per slot: the last pass its current image is used by
    for (uint32_t image : order) {
        const ImageLifetime& life = plan.lifetimes[image];
        const uint32_t last = read_after[image] ? frame_end : life.last;
        uint32_t slot = 0;
        while (slot < busy_until.size() && busy_until[slot] >= life.first) ++slot;
        if (slot == busy_until.size()) busy_until.push_back(0);
        busy_until[slot] = last;
        out.slot[image] = slot;
    }
    out.count = uint32_t(busy_until.size());
    return out;
}

}  // namespace acetate
