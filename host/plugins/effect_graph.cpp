#include "plugins/effect_graph.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

// The host's side of the opaque handle the plugin receives.
struct AcetateGraph {
    const acetate::EffectDescriptor* descriptor = nullptr;
    std::string label;
    acetate::EffectGraph graph;
    std::set<std::string> written;  // targets some earlier pass wrote
    std::string error;              // the first refusal, reported by build_effect_graph
};

namespace acetate {
namespace {

AcetateStatus refuse(AcetateGraph* g, std::string message) {
    if (g->error.empty()) g->error = std::move(message);
    return ACETATE_ERROR_INVALID_ARGUMENT;
}

bool is_target(const AcetateGraph* g, const std::string& name) {
    return std::any_of(g->graph.targets.begin(), g->graph.targets.end(),
                       [&](const GraphTarget& t) { return t.name == name; });
}

AcetateStatus declare_target(AcetateGraph* g, const AcetateTargetDesc* t) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (!t || !t->name) return refuse(g, fmt::format("{}: declare_target with no name", g->label));
    const std::string name = t->name;
    if (!is_simple_name(name) || name == "previous" || name == "result")
        return refuse(g, fmt::format("{}: target \"{}\": name must match [a-z][a-z0-9_]* and not "
                                     "be \"previous\" or \"result\"",
                                     g->label, name));
    if (is_target(g, name))
        return refuse(g, fmt::format("{}: target \"{}\" is declared twice", g->label, name));
    const uint32_t d = t->divisor;
    if (d == 0 || d > 4096 || (d & (d - 1)) != 0)
        return refuse(g, fmt::format("{}: target \"{}\": divisor {} is not a power of two "
                                     "between 1 and 4096",
                                     g->label, name, d));
    g->graph.targets.push_back({name, d});
    return ACETATE_OK;
}

AcetateStatus add_pass(AcetateGraph* g, const AcetatePassDesc* p) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (!p || p->struct_size < sizeof(AcetatePassDesc))
        return refuse(
            g, fmt::format("{}: add_pass with a missing or short AcetatePassDesc", g->label));
    const std::string name = p->name ? p->name : "";
    const std::string pass = fmt::format("pass \"{}.{}\"", g->label, name);
    if (!is_simple_name(name)) return refuse(g, pass + ": name must match [a-z][a-z0-9_]*");
    for (const GraphPass& earlier : g->graph.passes)
        if (earlier.name == name) return refuse(g, pass + ": declared twice");
    if (p->kind != ACETATE_PASS_FULLSCREEN && p->kind != ACETATE_PASS_INSTANCED_QUADS)
        return refuse(g, fmt::format("{}: unknown kind {}", pass, p->kind));
    const bool instanced = p->kind == ACETATE_PASS_INSTANCED_QUADS;
    if (instanced && (p->instance_count == 0 || p->instance_count > (1u << 20)))
        return refuse(
            g, fmt::format("{}: instance_count {} is not in 1..1048576", pass, p->instance_count));
    const bool has_glsl = p->glsl && *p->glsl;
    if (has_glsl == bool(p->spirv && p->spirv_word_count))
        return refuse(g, pass + ": give exactly one of glsl (non-empty) and spirv");
    if (p->input_count > 8 || (p->input_count && !p->inputs))
        return refuse(g, fmt::format("{}: {} inputs (at most 8, and inputs must not be NULL)", pass,
                                     p->input_count));
    if (p->blend > ACETATE_BLEND_OVER)
        return refuse(g, fmt::format("{}: unknown blend {}", pass, p->blend));
    GraphPass out;
    out.name = name;
    out.blend = p->blend;
    out.kind = p->kind;
    out.instance_count = instanced ? p->instance_count : 0;
    out.instance_data_offset = instanced ? p->instance_data_offset : 0;
    if (has_glsl) {
        out.glsl = p->glsl;
    } else {
        // The driver must never see a malformed module: check the header here (magic number,
        // and the five header words), and glslang-produced modules only are the tested path.
        if (p->spirv_word_count < 5 || p->spirv[0] != 0x07230203u)
            return refuse(g,
                          pass + ": spirv is not a SPIR-V module (bad magic number or too short)");
        out.spirv.assign(p->spirv, p->spirv + p->spirv_word_count);
    }
    for (uint32_t i = 0; i < p->input_count; ++i) {
        const std::string input = p->inputs[i] ? p->inputs[i] : "";
        if (input == "previous") {
        } else if (input.rfind("mask.", 0) == 0) {
            const std::string kind = input.substr(5);
            const auto& masks = g->descriptor->masks;
            if (std::find(masks.begin(), masks.end(), kind) == masks.end())
                return refuse(g, fmt::format("{} reads \"{}\", a mask kind the descriptor does not "
                                             "list in masks",
                                             pass, input));
        } else if (input.rfind("texture.", 0) == 0) {
            const std::string texture = input.substr(8);
            const auto& textures = g->graph.textures;
            if (std::none_of(textures.begin(), textures.end(),
                             [&](const GraphTexture& t) { return t.name == texture; }))
                return refuse(g, fmt::format("{} reads \"{}\", which add_texture has not declared",
                                             pass, input));
        } else if (!is_target(g, input)) {
            return refuse(g, fmt::format("{} reads \"{}\", which is neither \"previous\", a mask "
                                         "nor a declared target",
                                         pass, input));
        } else if (!g->written.count(input)) {
            return refuse(
                g, fmt::format("{} reads \"{}\", which no earlier pass writes", pass, input));
        }
        if (std::count(out.inputs.begin(), out.inputs.end(), input))
            return refuse(g, fmt::format("{} reads \"{}\" twice", pass, input));
        out.inputs.push_back(input);
    }
    out.output = p->output ? p->output : "";
    if (out.output != "result" && !is_target(g, out.output))
        return refuse(g, fmt::format("{} writes \"{}\", which is neither \"result\" nor a declared "
                                     "target",
                                     pass, out.output));
    if (std::count(out.inputs.begin(), out.inputs.end(), out.output))
        return refuse(g, fmt::format("{} reads and writes \"{}\"", pass, out.output));
    // Targets are shared and not cleared between frames: blending onto one before any pass of
    // this instance replaced it would read what another floor or frame left there. An
    // instanced pass shades only its quads, so it cannot be the first writer either.
    if ((out.blend != ACETATE_BLEND_REPLACE || instanced) && !g->written.count(out.output))
        return refuse(g, fmt::format("{} blends onto \"{}\" before any full-size pass replaced "
                                     "it",
                                     pass, out.output));
    g->written.insert(out.output);
    g->graph.passes.push_back(std::move(out));
    return ACETATE_OK;
}

AcetateStatus set_floor_data(AcetateGraph* g, const float* data, uint32_t count) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (count > (1u << 20) || (count && !data))
        return refuse(g, fmt::format("{}: set_floor_data with {} floats (at most 1048576, data "
                                     "not NULL)",
                                     g->label, count));
    if (!std::all_of(data, data + count, [](float v) { return std::isfinite(v); }))
        return refuse(g, fmt::format("{}: set_floor_data: a value is not finite", g->label));
    g->graph.floor_data.assign(data, data + count);
    return ACETATE_OK;
}

AcetateStatus add_texture(AcetateGraph* g, const AcetateTextureDesc* t) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (!t || !t->name) return refuse(g, fmt::format("{}: add_texture with no name", g->label));
    const std::string name = t->name;
    const std::string what = fmt::format("{}: texture \"{}\"", g->label, name);
    if (!is_simple_name(name)) return refuse(g, what + ": name must match [a-z][a-z0-9_]*");
    for (const GraphTexture& earlier : g->graph.textures)
        if (earlier.name == name) return refuse(g, what + ": declared twice");
    if (t->width == 0 || t->height == 0 || t->width > 16384 || t->height > 16384 || !t->rgba)
        return refuse(g, fmt::format("{}: {}x{} (1..16384 per side, data not NULL)", what, t->width,
                                     t->height));
    GraphTexture texture{name, t->width, t->height, {}};
    texture.rgba.assign(t->rgba, t->rgba + size_t(t->width) * t->height * 4);
    if (!std::all_of(texture.rgba.begin(), texture.rgba.end(),
                     [](float v) { return std::isfinite(v); }))
        return refuse(g, what + ": holds a value that is not finite");
    g->graph.textures.push_back(std::move(texture));
    return ACETATE_OK;
}

void log(AcetateGraph* g, const char* message) {
    if (g && message) g->graph.log.push_back(fmt::format("{}: {}", g->label, message));
}

// No exception may unwind into the plugin's frames (it may be C, or built without unwind
// tables): every callback runs inside a catch-all.
template <class Body>
AcetateStatus guarded(Body&& body) noexcept {
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return ACETATE_ERROR_OUT_OF_MEMORY;
    } catch (...) {
        return ACETATE_ERROR_FAILED;
    }
}

const AcetateHostApi kHostApi = {sizeof(AcetateHostApi),
                                 [](AcetateGraph* g, const AcetateTargetDesc* t) noexcept {
                                     return guarded([&] { return declare_target(g, t); });
                                 },
                                 [](AcetateGraph* g, const AcetatePassDesc* p) noexcept {
                                     return guarded([&] { return add_pass(g, p); });
                                 },
                                 [](AcetateGraph* g, const float* data, uint32_t count) noexcept {
                                     return guarded([&] { return set_floor_data(g, data, count); });
                                 },
                                 [](AcetateGraph* g, const char* message) noexcept {
                                     guarded([&] {
                                         log(g, message);
                                         return ACETATE_OK;
                                     });
                                 },
                                 [](AcetateGraph* g, const AcetateTextureDesc* t) noexcept {
                                     return guarded([&] { return add_texture(g, t); });
                                 }};

}  // namespace

Result<EffectGraph> build_effect_graph(const LoadedPlugin& plugin, const AcetateFloorInfo& floor,
                                       const std::string& label) {
    AcetateGraph graph;
    graph.descriptor = &plugin.descriptor;
    graph.label = label;
    const AcetateStatus status = plugin.api->build(&kHostApi, &graph, &floor);
    if (!graph.error.empty()) return make_error(ErrorCode::InvalidInput, graph.error);
    if (status != ACETATE_OK) {
        const char* why = plugin.api->last_error();
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: build failed with status {}: {}", label, status,
                                      why ? why : "(no message)"));
    }
    if (!graph.written.count("result"))
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: no pass writes \"result\"", label));
    // Instanced quads read their rects from floor_data, which build() may set after the pass.
    for (const GraphPass& pass : graph.graph.passes) {
        const uint64_t end = uint64_t(pass.instance_data_offset) + 4ull * pass.instance_count;
        if (pass.kind == ACETATE_PASS_INSTANCED_QUADS && end > graph.graph.floor_data.size())
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("pass \"{}.{}\" draws {} quads whose rects end at "
                                          "floor_data[{}], but floor_data has {} floats",
                                          label, pass.name, pass.instance_count, end,
                                          graph.graph.floor_data.size()));
    }
    return std::move(graph.graph);
}

}  // namespace acetate
