#include "plugins/effect_graph.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <regex>
#include <set>

#include "core/sha256.hpp"
#include "plugins/plugin_calls.hpp"

// The host's side of the opaque handle the plugin receives.
struct AcetateGraph {
    const acetate::EffectDescriptor* descriptor = nullptr;
    const acetate::GraphContext* context = nullptr;
    std::string label;
    acetate::EffectGraph graph;
    std::set<std::string> written;  // targets some earlier pass wrote
    std::string error;              // the first refusal, reported by build_effect_graph
    acetate::ImageRGBA blank_mask;  // read_mask's answer for a kind the floor lacks (made once)
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

const GraphTarget* find_target(const AcetateGraph* g, const std::string& name) {
    for (const GraphTarget& t : g->graph.targets)
        if (t.name == name) return &t;
    return nullptr;
}

AcetateStatus declare_target(AcetateGraph* g, const char* target_name, uint32_t divisor,
                             uint32_t format) {
    if (!target_name) return refuse(g, fmt::format("{}: declare_target with no name", g->label));
    const std::string name = target_name;
    if (!is_simple_name(name) || name == "previous" || name == "result")
        return refuse(g, fmt::format("{}: target \"{}\": name must match [a-z][a-z0-9_]* and not "
                                     "be \"previous\" or \"result\"",
                                     g->label, name));
    if (is_target(g, name))
        return refuse(g, fmt::format("{}: target \"{}\" is declared twice", g->label, name));
    const uint32_t d = divisor;
    if (d == 0 || d > 4096 || (d & (d - 1)) != 0)
        return refuse(g, fmt::format("{}: target \"{}\": divisor {} is not a power of two "
                                     "between 1 and 4096",
                                     g->label, name, d));
    if (format_name(format).empty())
        return refuse(g,
                      fmt::format("{}: target \"{}\": unknown format {}", g->label, name, format));
    if (format != ACETATE_FORMAT_FLOOR && g->context->format_problem)
        if (std::string why = g->context->format_problem(format, false); !why.empty())
            return refuse(g, fmt::format("{}: target \"{}\": format {} {}", g->label, name,
                                         format_name(format), why));
    g->graph.targets.push_back({name, d, format});
    return ACETATE_OK;
}

AcetateStatus declare_target(AcetateGraph* g, const AcetateTargetDesc* t) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (!t) return refuse(g, fmt::format("{}: declare_target with no target", g->label));
    return declare_target(g, t->name, t->divisor, ACETATE_FORMAT_FLOOR);
}

AcetateStatus declare_target_info(AcetateGraph* g, const AcetateTargetInfo* t) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (!t || t->struct_size < offsetof(AcetateTargetInfo, format) + sizeof(uint32_t))
        return refuse(g, fmt::format("{}: declare_target_info with a missing or short "
                                     "AcetateTargetInfo",
                                     g->label));
    return declare_target(g, t->name, t->divisor, t->format);
}

// A name the plugin chooses for an input's sampler: lowercase like every other name it gives,
// so it cannot meet the host's own declarations (AcetateLight, ACETATE_LIGHT_*); not starting
// with a prefix GLSL or the host reserves; no "__" (reserved by GLSL).
bool is_input_name(const std::string& name) {
    for (const char* reserved : {"gl_", "acetate", "param_", "phase_"})
        if (name.rfind(reserved, 0) == 0) return false;
    return is_simple_name(name) && name.find("__") == std::string::npos && name != "floor_data" &&
           name != "out_color";
}

// Pass 1.1 fields: chosen input names and defines. Empty when the pass is fine.
std::string pass_extras(const AcetatePassDesc* p, GraphPass& out, const std::string& pass) {
    out.input_names.clear();
    for (const std::string& input : out.inputs) out.input_names.push_back(input_variable(input));
    constexpr size_t kEnd = offsetof(AcetatePassDesc, defines) + sizeof(const char*);
    const bool has_extras = p->struct_size >= kEnd;  // a 1.0 pass has neither field
    if (has_extras && p->input_names)
        for (uint32_t i = 0; i < p->input_count; ++i) {
            if (!p->input_names[i]) continue;
            const std::string name = p->input_names[i];
            if (!is_input_name(name))
                return fmt::format(
                    "{}: input_names[{}] \"{}\" is not a name [a-z][a-z0-9_]* free "
                    "for the plugin (not gl_, acetate, param_ or phase_; no __)",
                    pass, i, name);
            out.input_names[i] = name;
        }
    for (size_t i = 0; i < out.input_names.size(); ++i)
        if (std::count(out.input_names.begin(), out.input_names.end(), out.input_names[i]) > 1)
            return fmt::format("{}: two inputs are named \"{}\" in GLSL", pass, out.input_names[i]);
    out.defines = has_extras && p->defines ? p->defines : "";
    size_t line_number = 0;
    for (size_t start = 0; start < out.defines.size(); ++line_number) {
        size_t end = out.defines.find('\n', start);
        if (end == std::string::npos) end = out.defines.size();
        const std::string line = out.defines.substr(start, end - start);
        if (!line.empty() && line.rfind("#define ", 0) != 0)
            return fmt::format("{}: defines line {} is not a \"#define NAME VALUE\" line: \"{}\"",
                               pass, line_number + 1, line);
        start = end + 1;
    }
    if (!out.defines.empty() && out.defines.back() != '\n') out.defines += '\n';
    return "";
}

AcetateStatus add_pass(AcetateGraph* g, const AcetatePassDesc* p) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    // ABI 1.0's AcetatePassDesc ends before input_names; later fields are read when present.
    if (!p || p->struct_size < offsetof(AcetatePassDesc, input_names))
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
    if (std::string why = pass_extras(p, out, pass); !why.empty()) return refuse(g, why);
    if (const GraphTarget* target = find_target(g, out.output);
        target && target->format != ACETATE_FORMAT_FLOOR && out.blend != ACETATE_BLEND_REPLACE &&
        g->context->format_problem)
        if (std::string why = g->context->format_problem(target->format, true); !why.empty())
            return refuse(g, fmt::format("{} blends onto \"{}\": format {} {}", pass, out.output,
                                         format_name(target->format), why));
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

AcetateStatus add_texture(AcetateGraph* g, const char* texture_name, uint32_t width,
                          uint32_t height, const float* texels, uint32_t format) {
    if (!texture_name) return refuse(g, fmt::format("{}: add_texture with no name", g->label));
    const std::string name = texture_name;
    const std::string what = fmt::format("{}: texture \"{}\"", g->label, name);
    if (!is_simple_name(name)) return refuse(g, what + ": name must match [a-z][a-z0-9_]*");
    for (const GraphTexture& earlier : g->graph.textures)
        if (earlier.name == name) return refuse(g, what + ": declared twice");
    if (width == 0 || height == 0 || width > 16384 || height > 16384 || !texels)
        return refuse(
            g, fmt::format("{}: {}x{} (1..16384 per side, data not NULL)", what, width, height));
    if (format_name(format).empty())
        return refuse(g, fmt::format("{}: unknown format {}", what, format));
    if (format != ACETATE_FORMAT_FLOOR && g->context->format_problem)
        if (std::string why = g->context->format_problem(format, false); !why.empty())
            return refuse(g, fmt::format("{}: format {} {}", what, format_name(format), why));
    GraphTexture texture{name, width, height, {}, format, format_channels(format)};
    texture.texels.assign(texels, texels + size_t(width) * height * texture.channels);
    if (!std::all_of(texture.texels.begin(), texture.texels.end(),
                     [](float v) { return std::isfinite(v); }))
        return refuse(g, what + ": holds a value that is not finite");
    g->graph.textures.push_back(std::move(texture));
    return ACETATE_OK;
}

AcetateStatus add_texture(AcetateGraph* g, const AcetateTextureDesc* t) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (!t) return refuse(g, fmt::format("{}: add_texture with no texture", g->label));
    return add_texture(g, t->name, t->width, t->height, t->rgba, ACETATE_FORMAT_FLOOR);
}

AcetateStatus add_texture_info(AcetateGraph* g, const AcetateTextureInfo* t) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (!t || t->struct_size < offsetof(AcetateTextureInfo, rgba) + sizeof(const float*))
        return refuse(g, fmt::format("{}: add_texture_info with a missing or short "
                                     "AcetateTextureInfo",
                                     g->label));
    // Never reads `format`: a host that had add_texture_info before formats existed did not
    // either, so the format goes through add_texture_format, whose presence says it is read.
    return add_texture(g, t->name, t->width, t->height, t->rgba, ACETATE_FORMAT_FLOOR);
}

AcetateStatus add_texture_format(AcetateGraph* g, const AcetateTextureInfo* t) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (!t || t->struct_size < offsetof(AcetateTextureInfo, format) + sizeof(uint32_t))
        return refuse(g, fmt::format("{}: add_texture_format with a missing or short "
                                     "AcetateTextureInfo",
                                     g->label));
    return add_texture(g, t->name, t->width, t->height, t->rgba, t->format);
}

AcetateStatus read_mask(AcetateGraph* g, const char* kind_name, AcetateMaskImage* mask) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    const std::string kind = kind_name ? kind_name : "";
    const auto& declared = g->descriptor->masks;
    if (std::find(declared.begin(), declared.end(), kind) == declared.end())
        return refuse(g, fmt::format("{}: read_mask(\"{}\"): a mask kind the descriptor does not "
                                     "list in masks",
                                     g->label, kind));
    if (!mask || mask->struct_size < offsetof(AcetateMaskImage, data) + sizeof(const float*))
        return refuse(g, fmt::format("{}: read_mask(\"{}\") with a missing or short "
                                     "AcetateMaskImage",
                                     g->label, kind));
    const ImageRGBA* image = nullptr;
    if (g->context->masks)
        if (auto found = g->context->masks->find(kind); found != g->context->masks->end())
            image = &found->second;
    if (!image) {  // a floor without the kind reads zeros of the same size, never NULL
        if (g->blank_mask.pixels.empty())
            g->blank_mask = ImageRGBA(std::max(1u, g->context->canvas_width),
                                      std::max(1u, g->context->canvas_height));
        image = &g->blank_mask;
    }
    mask->width = image->width;
    mask->height = image->height;
    mask->channels = 4;
    mask->data = image->pixels.data();
    return ACETATE_OK;
}

AcetateStatus set_reach(AcetateGraph* g, uint32_t pixels) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    if (g->descriptor->coverage != ACETATE_COVERAGE_EXPANDING)
        return refuse(g, fmt::format("{}: set_reach({}): only a coverage-expanding effect has a "
                                     "reach",
                                     g->label, pixels));
    if (pixels > 16384)
        return refuse(g, fmt::format("{}: set_reach({}): at most 16384 pixels", g->label, pixels));
    if (g->descriptor->scope == ACETATE_SCOPE_GLOBAL)
        return refuse(g, fmt::format("{}: set_reach({}): a global effect runs on the whole "
                                     "composite; only a floor effect has a reach",
                                     g->label, pixels));
    g->graph.reach = pixels;
    return ACETATE_OK;
}

AcetateStatus declare_phase(AcetateGraph* g, const char* phase_name, double period) {
    if (!g) return ACETATE_ERROR_INVALID_ARGUMENT;
    const std::string name = phase_name ? phase_name : "";
    const std::string what = fmt::format("{}: phase \"{}\"", g->label, name);
    if (!is_simple_name(name)) return refuse(g, what + ": name must match [a-z][a-z0-9_]*");
    for (const GraphPhase& earlier : g->graph.phases)
        if (earlier.name == name) return refuse(g, what + ": declared twice");
    // Below a microsecond a phase means nothing at any frame rate, and time / period could
    // overflow to Inf (a NaN phase) for a long-running host.
    if (!std::isfinite(period) || !(period >= 1e-6))
        return refuse(g, fmt::format("{}: period {} s is not a finite number of at least 1e-6 s",
                                     what, period));
    if (g->graph.phases.size() >= 64) return refuse(g, what + ": at most 64 phases");
    g->graph.phases.push_back({name, period});
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

const AcetateHostApi kHostApi = {
    sizeof(AcetateHostApi),
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
    },
    [](AcetateGraph* g, const AcetateTargetInfo* t) noexcept {
        return guarded([&] { return declare_target_info(g, t); });
    },
    [](AcetateGraph* g, const AcetateTextureInfo* t) noexcept {
        return guarded([&] { return add_texture_info(g, t); });
    },
    [](AcetateGraph* g, const char* kind, AcetateMaskImage* mask) noexcept {
        return guarded([&] { return read_mask(g, kind, mask); });
    },
    [](AcetateGraph* g, uint32_t pixels) noexcept {
        return guarded([&] { return set_reach(g, pixels); });
    },
    [](AcetateGraph* g, const char* name, double period) noexcept {
        return guarded([&] { return declare_phase(g, name, period); });
    },
    [](AcetateGraph* g, const AcetateTextureInfo* t) noexcept {
        return guarded([&] { return add_texture_format(g, t); });
    }};

}  // namespace

std::string input_variable(const std::string& input) {
    std::string name = input;
    for (char& c : name)
        if (c == '.') c = '_';
    return name;
}

uint32_t format_channels(uint32_t format) {
    switch (format) {
        case ACETATE_FORMAT_R16F:
        case ACETATE_FORMAT_R32F:
            return 1;
        case ACETATE_FORMAT_RG16F:
        case ACETATE_FORMAT_RG32F:
            return 2;
        default:
            return 4;
    }
}

std::string format_name(uint32_t format) {
    switch (format) {
        case ACETATE_FORMAT_FLOOR:
            return "FLOOR";
        case ACETATE_FORMAT_R16F:
            return "R16F";
        case ACETATE_FORMAT_RG16F:
            return "RG16F";
        case ACETATE_FORMAT_RGBA16F:
            return "RGBA16F";
        case ACETATE_FORMAT_R32F:
            return "R32F";
        case ACETATE_FORMAT_RG32F:
            return "RG32F";
        case ACETATE_FORMAT_RGBA32F:
            return "RGBA32F";
        default:
            return "";
    }
}

Result<EffectGraph> build_effect_graph(const LoadedPlugin& plugin, const AcetateFloorInfo& floor,
                                       const std::string& label, const GraphContext& context) {
    AcetateGraph graph;
    graph.descriptor = &plugin.descriptor;
    graph.context = &context;
    graph.label = label;
    AcetateStatus status = ACETATE_OK;
    std::string why;
    {
        PluginCallGuard building("build", label);
        status = plugin.api->build(&kHostApi, &graph, &floor);
        if (status != ACETATE_OK && graph.error.empty()) {
            const char* text = plugin.api->last_error();
            why = text ? text : "(no message)";
        }
    }
    if (!graph.error.empty()) return make_error(ErrorCode::InvalidInput, graph.error);
    if (status != ACETATE_OK) {
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: build failed with status {}: {}", label, status, why));
    }
    // Nothing declared at all: the instance has nothing to do on this floor (an effect that
    // needs a mask the floor lacks), and the host skips it; "result" is then "previous".
    const EffectGraph& declared = graph.graph;
    if (declared.passes.empty() && declared.targets.empty() && declared.textures.empty() &&
        declared.floor_data.empty() && declared.phases.empty())
        return std::move(graph.graph);
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

std::string effect_graph_digest(const EffectGraph& graph) {
    // Each field with its length first, so no two different graphs write the same bytes.
    std::string bytes;
    auto add_bytes = [&](const void* data, size_t size) {
        bytes.append(reinterpret_cast<const char*>(&size), sizeof size);
        bytes.append(static_cast<const char*>(data), size);
    };
    auto add_text = [&](const std::string& text) { add_bytes(text.data(), text.size()); };
    auto add_number = [&](auto value) { add_bytes(&value, sizeof value); };
    auto add_texts = [&](const std::vector<std::string>& texts) {
        add_number(texts.size());
        for (const std::string& t : texts) add_text(t);
    };
    add_number(graph.targets.size());
    for (const GraphTarget& t : graph.targets) {
        add_text(t.name);
        add_number(t.divisor);
        add_number(t.format);
    }
    add_number(graph.passes.size());
    for (const GraphPass& p : graph.passes) {
        add_text(p.name);
        add_text(p.glsl);
        add_bytes(p.spirv.data(), p.spirv.size() * sizeof(uint32_t));
        add_texts(p.inputs);
        add_text(p.output);
        add_number(p.blend);
        add_number(p.kind);
        add_number(p.instance_count);
        add_number(p.instance_data_offset);
        add_texts(p.input_names);
        add_text(p.defines);
    }
    add_number(graph.textures.size());
    for (const GraphTexture& t : graph.textures) {
        add_text(t.name);
        add_number(t.width);
        add_number(t.height);
        add_number(t.format);
        add_number(t.channels);
        add_bytes(t.texels.data(), t.texels.size() * sizeof(float));
    }
    add_bytes(graph.floor_data.data(), graph.floor_data.size() * sizeof(float));
    add_number(graph.phases.size());
    for (const GraphPhase& p : graph.phases) {
        add_text(p.name);
        add_number(p.period);
    }
    add_number(graph.reach.has_value());
    add_number(graph.reach.value_or(0));
    return sha256_hex(bytes);
}

}  // namespace acetate
