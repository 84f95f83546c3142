#pragma once
// The in-process fake plugin the no-GPU effect graph tests share (effect_graph_test.cpp,
// effect_graph_refusals_test.cpp): no shared library, no Vulkan device; build() runs the
// current test's body against the host's real AcetateHostApi.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "plugins/effect_descriptor.hpp"
#include "plugins/effect_graph.hpp"

namespace acetate::fake {

inline const std::string kLabel = "floor1.test.fake";
inline const char* const kGlsl = "void main() { out_color = vec4(0.0); }\n";
inline const std::vector<uint32_t> kSpirv = {0x07230203u, 0x00010000u, 0u, 1u, 0u};

// `<label>: <rest>` and `pass "<label>.<name>"<rest>`, as the host words them.
inline std::string at(const std::string& rest) {
    return kLabel + ": " + rest;
}
inline std::string pass_at(const std::string& name, const std::string& rest) {
    return "pass \"" + kLabel + "." + name + "\"" + rest;
}

// One AcetatePassDesc, with storage for what it points to. Defaults: a fullscreen GLSL pass
// "p" reading "previous" and replacing "result".
struct Pass {
    const char* name = "p";
    std::vector<const char*> inputs{"previous"};
    const char* output = "result";
    uint32_t blend = ACETATE_BLEND_REPLACE;
    uint32_t kind = ACETATE_PASS_FULLSCREEN;
    uint32_t instance_count = 0;
    uint32_t instance_data_offset = 0;
    const char* glsl = kGlsl;
    std::vector<uint32_t> spirv{};
    std::vector<const char*> input_names{};
    const char* defines = nullptr;
    uint32_t struct_size = sizeof(AcetatePassDesc);
};

inline thread_local AcetateStatus t_last = ACETATE_OK;  // what the fake's last host call returned

// What build() is given, with one helper per host function. Each notes its status in t_last and
// returns the Host, so that a body reads as one chain of declarations; a refused call makes the
// whole build fail with its message, so a graph that builds had every call accepted.
struct Host {
    const AcetateHostApi* api;
    AcetateGraph* graph;

    Host& note(AcetateStatus s) {
        t_last = s;
        return *this;
    }
    Host& target(const char* name, uint32_t divisor = 1) {
        const AcetateTargetDesc t{name, divisor};
        return note(api->declare_target(graph, &t));
    }
    Host& target_info(const char* name, uint32_t format, uint32_t divisor = 1,
                      uint32_t size = sizeof(AcetateTargetInfo)) {
        const AcetateTargetInfo t{size, name, divisor, format};
        return note(api->declare_target_info(graph, &t));
    }
    Host& pass(const Pass& p) {
        AcetatePassDesc d{};
        d.struct_size = p.struct_size;
        d.name = p.name;
        d.kind = p.kind;
        d.glsl = p.glsl;
        d.spirv = p.spirv.empty() ? nullptr : p.spirv.data();
        d.spirv_word_count = uint32_t(p.spirv.size());
        d.inputs = p.inputs.data();
        d.input_count = uint32_t(p.inputs.size());
        d.output = p.output;
        d.blend = p.blend;
        d.instance_count = p.instance_count;
        d.instance_data_offset = p.instance_data_offset;
        d.input_names = p.input_names.empty() ? nullptr : p.input_names.data();
        d.defines = p.defines;
        return note(api->add_pass(graph, &d));
    }
    Host& floor_data(const float* data, uint32_t count) {
        return note(api->set_floor_data(graph, data, count));
    }
    Host& floor_data(const std::vector<float>& v) {
        return floor_data(v.data(), uint32_t(v.size()));
    }
    Host& texture(const char* name, uint32_t w, uint32_t h, float fill = 0.5f) {
        const std::vector<float> rgba(std::max<size_t>(1, size_t(w) * h * 4), fill);
        const AcetateTextureDesc t{name, w, h, rgba.data()};
        return note(api->add_texture(graph, &t));
    }
    Host& mask(const char* kind, AcetateMaskImage* image) {
        return note(api->read_mask(graph, kind, image));
    }
    Host& mask(const char* kind, uint32_t struct_size) {  // into a scratch image
        AcetateMaskImage image{};
        image.struct_size = struct_size;
        return mask(kind, &image);
    }
    Host& reach(uint32_t pixels) { return note(api->set_reach(graph, pixels)); }
    Host& phase(const char* name, double period) {
        return note(api->declare_phase(graph, name, period));
    }
};

using Body = std::function<void(Host&)>;

inline AcetateMaskImage mask_image(uint32_t struct_size = sizeof(AcetateMaskImage)) {
    AcetateMaskImage m{};
    m.struct_size = struct_size;
    return m;
}

// The fake plugin's C side: build() runs the current test's body.
inline thread_local const Body* t_body = nullptr;
inline thread_local AcetateStatus t_status = ACETATE_OK;
inline thread_local const char* t_error = nullptr;

inline AcetateStatus fake_build(const AcetateHostApi* api, AcetateGraph* graph,
                                const AcetateFloorInfo*) {
    Host host{api, graph};
    (*t_body)(host);
    return t_status;
}
inline const char* fake_last_error() {
    return t_error;
}

// A fake plugin "test.fake" reading the mask kinds "water" and "shadow", built for floor 1 of an
// 8x6 canvas.
struct Fake {
    const char* masks[2] = {"water", "shadow"};
    AcetateEffectDescriptor descriptor{};
    AcetateEffectApi api{sizeof(AcetateEffectApi), &descriptor, &fake_build, &fake_last_error};
    GraphContext context;

    explicit Fake(uint32_t coverage = ACETATE_COVERAGE_PRESERVING) {
        descriptor.struct_size = sizeof descriptor;
        descriptor.abi_version = ACETATE_ABI_VERSION;
        descriptor.id = "test.fake";
        descriptor.abi_minor = ACETATE_ABI_MINOR;
        descriptor.coverage = coverage;
        descriptor.masks = masks;
        descriptor.mask_count = 2;
        context.canvas_width = 8;
        context.canvas_height = 6;
        t_status = ACETATE_OK;
        t_error = nullptr;
        t_last = ACETATE_OK;
    }

    Result<EffectGraph> build(const Body& body) {
        auto copied = copy_descriptor(&descriptor, "fake.so");
        if (!copied) return copied.error();
        LoadedPlugin plugin;  // in-process: no file, no library
        plugin.api = &api;
        plugin.descriptor = copied.value();
        AcetateFloorInfo floor{};
        floor.struct_size = sizeof floor;
        floor.floor_index = 1;
        floor.canvas_width = context.canvas_width;
        floor.canvas_height = context.canvas_height;
        t_body = &body;
        auto graph = build_effect_graph(plugin, floor, kLabel, context);
        t_body = nullptr;
        return graph;
    }
};

// The refusal's message, after checking it is one line of invalid input.
inline std::string refusal(const Result<EffectGraph>& graph) {
    if (graph.ok()) return "(accepted)";
    EXPECT_EQ(graph.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(graph.error().message.find('\n'), std::string::npos) << graph.error().message;
    return graph.error().message;
}

inline const std::string kBadTarget =
    "name must match [a-z][a-z0-9_]* and not be \"previous\" or \"result\"";
inline const float kNaN = std::numeric_limits<float>::quiet_NaN();
inline const double kInf = std::numeric_limits<double>::infinity();
inline const float kOne = 1;
inline constexpr uint32_t kQuads = ACETATE_PASS_INSTANCED_QUADS, kAdd = ACETATE_BLEND_ADD,
                          kOver = ACETATE_BLEND_OVER, kRG16F = ACETATE_FORMAT_RG16F;

}  // namespace acetate::fake
