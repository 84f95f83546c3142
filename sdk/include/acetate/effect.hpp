// acetate/effect.hpp -- the C++ layer for plugin authors, header-only, over acetate/effect.h.
//
// Write a class deriving from acetate::sdk::Effect, describe it in info(), declare its passes
// in build(), and register it with ACETATE_REGISTER_EFFECT(ClassName) in one .cpp file. The
// macro defines the C entry point; every call into the plugin runs inside a catch-all that
// turns exceptions into ACETATE_ERROR_EXCEPTION with the message kept for last_error(), so no
// exception ever crosses the library boundary. See docs/plugin-guide.md.
//
// ABI 1.1: parameters are declared as typed constants (acetate/effect_params.hpp) and read back
// typed (floor[kTaps]); Graph and Floor expose what 1.1 added. Code written against the 1.0
// layer compiles unchanged. Anything 1.1 added is read only after checking the struct_size the
// host gave, so a plugin built here still loads in a 1.0 host as long as it uses 1.0 features;
// a 1.1 call on a 1.0 host throws HostRefused ("this host does not support ...").
#pragma once

#include <acetate/effect.h>

#include <acetate/effect_params.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#ifndef ACETATE_SOURCE_DIGEST
#define ACETATE_SOURCE_DIGEST ""  // acetate_add_effect() defines it from the plugin's sources
#endif

// Whether `object`, a struct the other side filled (struct_size first), reaches to the end of
// `field`: the one test before reading anything added after ABI 1.0. Undefined at the end.
#define ACETATE_SDK_HAS(object, Type, field) \
    ((object).struct_size >= offsetof(Type, field) + sizeof(Type::field))

namespace acetate::sdk {

// Thrown by Graph when the host refuses a declaration; caught at the boundary.
class HostRefused : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// What an effect is; turned into the C descriptor once, kept for the library's lifetime.
struct EffectInfo {
    std::string id;  // reverse-DNS, e.g. "com.example.tint"
    std::string display_name;
    uint32_t version_major = 1, version_minor = 0, version_patch = 0;
    uint32_t scope = ACETATE_SCOPE_FLOOR;
    uint32_t coverage = ACETATE_COVERAGE_PRESERVING;
    std::vector<std::string> masks;
    std::vector<Param> params;
    std::vector<Preset> presets;
    // 1.2: how far a render at another scale may stray, a fraction of the largest value there
    // (AcetateEffectDescriptor's scale_tolerance; docs/plugin-guide.md, "Cameras").
    float scale_tolerance = 0;
};

struct Pass {
    // Every member has an initialiser so designated initialisers may leave any out (no
    // -Wmissing-field-initializers).
    std::string name{};
    // After the host's declarations; defines main(). A view: a literal, an embedded shader, or
    // a string that outlives the graph.pass() call (a temporary inside the call does).
    std::string_view glsl{};
    std::vector<std::string> inputs{};  // "previous", "mask.<kind>", "texture.<name>", a target
    std::string output = "result";
    uint32_t blend = ACETATE_BLEND_REPLACE;
    uint32_t instance_count = 0;  // > 0: an instanced-quad pass (see acetate/effect.h)
    uint32_t instance_data_offset = 0;
    std::vector<uint32_t> spirv{};  // instead of glsl: a whole fragment module
    // 1.1. "#define NAME VALUE\n" lines the host puts before glsl; messages keep glsl's lines.
    std::string defines{};
    // 1.1. Empty, or one GLSL name per input ("" keeps the default), so one shader can serve
    // passes that read different targets.
    std::vector<std::string> input_names{};
};

// The pixels a floor's tiles cover, scene pixels; x1 and y1 exclusive.
struct Bounds {
    int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// A mask read at build: canvas-sized RGBA floats as the files hold them (data,
// not premultiplied), row-major, y down. The data is
// the host's and valid only until build() returns.
struct Mask {
    uint32_t width = 0, height = 0, channels = 0;
    std::span<const float> data;
};

// The floor an instance is built for, with parameters looked up by name.
class Floor {
  public:
    Floor(const AcetateFloorInfo& info, const EffectInfo& effect,
          const AcetateHostApi* host = nullptr, AcetateGraph* graph = nullptr)
        : info_(info), effect_(effect), host_(host), graph_(graph) {}
    bool is_global() const { return info_.floor_index == UINT32_MAX; }
    uint32_t index() const { return info_.floor_index; }
    std::string_view name() const { return info_.floor_name ? info_.floor_name : ""; }
    uint32_t canvas_width() const { return info_.canvas_width; }
    uint32_t canvas_height() const { return info_.canvas_height; }
    // ABI 1.0's point lights (no height, no sun); light_infos() has both.
    std::span<const AcetateLight> lights() const {
        return {info_.lights, info_.lights ? info_.light_count : 0};
    }
    // The resolved value of a parameter; throws for a name the effect did not declare.
    float param(std::string_view name) const { return info_.params[index_of(name)]; }

    // Typed reads: the constant that declared the parameter gives back its type.
    float operator[](const FloatParam& p) const { return scalar(p.name, ACETATE_PARAM_FLOAT); }
    int operator[](const IntParam& p) const {
        return int(std::lround(scalar(p.name, ACETATE_PARAM_INT)));
    }
    bool operator[](const BoolParam& p) const { return scalar(p.name, ACETATE_PARAM_BOOL) > 0.5f; }
    std::array<float, 2> operator[](const Vec2Param& p) const {
        return components<2>(p.name, ACETATE_PARAM_VEC2);
    }
    std::array<float, 3> operator[](const Vec3Param& p) const {
        return components<3>(p.name, ACETATE_PARAM_VEC3);
    }
    std::array<float, 3> operator[](const ColorParam& p) const {
        return components<3>(p.name, ACETATE_PARAM_COLOR);
    }

    bool has_mask(std::string_view kind) const {
        for (uint32_t i = 0; i < info_.masks_present_count; ++i)
            if (kind == info_.masks_present[i]) return true;
        return false;
    }

    // 1.1: floors in the scene.
    uint32_t floor_count() const {
        if (!ACETATE_SDK_HAS(info_, AcetateFloorInfo, floor_count))
            throw HostRefused("this host does not support floor_count");
        return info_.floor_count;
    }
    // 1.1: the floor's coverage bounds (all 0 without tiles). A 1.0 host does not say, so the
    // whole canvas, which holds any floor's coverage, is the safe answer there.
    Bounds coverage_bounds() const {
        if (!ACETATE_SDK_HAS(info_, AcetateFloorInfo, coverage_bounds))
            return {0, 0, int32_t(info_.canvas_width), int32_t(info_.canvas_height)};
        const int32_t* b = info_.coverage_bounds;
        return {b[0], b[1], b[2], b[3]};
    }
    // 1.1: the point lights in scene order, then the sun if any. From a 1.0 host: its lights,
    // as points at height 0 (all a 1.0 scene could say).
    std::vector<AcetateLightInfo> light_infos() const {
        std::vector<AcetateLightInfo> out;
        if (ACETATE_SDK_HAS(info_, AcetateFloorInfo, light_info_count)) {
            for (uint32_t i = 0; info_.light_infos && i < info_.light_info_count; ++i) {
                const AcetateLightInfo* l = info_.light_infos[i];
                if (!l) continue;
                // Each light's own struct_size says how much of it the host filled; the rest
                // stays 0.
                AcetateLightInfo copy{};
                std::memcpy(&copy, l, std::min<size_t>(l->struct_size, sizeof copy));
                out.push_back(copy);
            }
            return out;
        }
        for (const AcetateLight& l : lights()) {
            AcetateLightInfo info{};
            info.struct_size = sizeof info;
            info.kind = ACETATE_LIGHT_POINT;
            std::copy_n(l.pos, 2, info.pos);
            info.radius = l.radius;
            std::copy_n(l.color, 3, info.color);
            info.intensity = l.intensity;
            out.push_back(info);
        }
        return out;
    }
    std::optional<AcetateLightInfo> sun() const {
        for (const AcetateLightInfo& l : light_infos())
            if (l.kind == ACETATE_LIGHT_SUN) return l;
        return std::nullopt;
    }
    // 1.2: the ABI minor the host implements (1.0 and 1.1 hosts do not say: 0 for either,
    // which only matters to a plugin that wants to know whether a camera can exist).
    uint32_t host_abi_minor() const {
        return ACETATE_SDK_HAS(info_, AcetateFloorInfo, host_abi_minor) ? info_.host_abi_minor : 0;
    }
    // 1.2: render pixels per scene pixel this instance is built for, and the size of
    // "previous" and "result". A host before 1.2 has no camera: scale 1, the canvas.
    float render_scale() const {
        return ACETATE_SDK_HAS(info_, AcetateFloorInfo, render_scale) ? info_.render_scale : 1.0f;
    }
    uint32_t render_width() const {
        return ACETATE_SDK_HAS(info_, AcetateFloorInfo, render_height) ? info_.render_width
                                                                       : info_.canvas_width;
    }
    uint32_t render_height() const {
        return ACETATE_SDK_HAS(info_, AcetateFloorInfo, render_height) ? info_.render_height
                                                                       : info_.canvas_height;
    }
    // A length in scene pixels (a blur radius, a flame's height) in render pixels at this
    // instance's scale: what a pass that counts texels needs.
    float render_pixels(float scene_pixels) const { return scene_pixels * render_scale(); }

    // 1.1: the floor's mask of `kind` (one the effect lists in masks), read on the CPU at build.
    Mask mask(std::string_view kind) const {
        if (!host_ || !ACETATE_SDK_HAS(*host_, AcetateHostApi, read_mask) || !host_->read_mask)
            throw HostRefused("this host does not support read_mask");
        const std::string name(kind);
        AcetateMaskImage image{};
        image.struct_size = sizeof image;
        if (host_->read_mask(graph_, name.c_str(), &image) != ACETATE_OK)
            throw HostRefused("read_mask(" + name + ") was refused by the host");
        const size_t count = size_t(image.width) * image.height * image.channels;
        return {image.width, image.height, image.channels, {image.data, image.data ? count : 0}};
    }

  private:
    size_t index_of(std::string_view name) const {
        for (size_t i = 0; i < effect_.params.size() && i < info_.param_count; ++i)
            if (effect_.params[i].name == name) return i;
        throw std::invalid_argument("unknown parameter \"" + std::string(name) + "\"");
    }
    // A typed read of a parameter declared with another type is a bug in the plugin.
    size_t typed_index(std::string_view name, uint32_t type) const {
        const size_t i = index_of(name);
        if (effect_.params[i].type != type)
            throw std::invalid_argument("parameter \"" + std::string(name) +
                                        "\" is read with another type than it was declared");
        return i;
    }
    float scalar(std::string_view name, uint32_t type) const {
        return info_.params[typed_index(name, type)];
    }
    // From param_vectors; a host without them gives only the first component (in params), so
    // the others keep their defaults.
    template <size_t N>
    std::array<float, N> components(std::string_view name, uint32_t type) const {
        const size_t i = typed_index(name, type);
        std::array<float, N> v{};
        const bool has =
            ACETATE_SDK_HAS(info_, AcetateFloorInfo, param_vectors) && info_.param_vectors;
        for (size_t c = 0; c < N; ++c)
            v[c] = has      ? info_.param_vectors[4 * i + c]
                   : c == 0 ? info_.params[i]
                            : effect_.params[i].default_vector[c];
        return v;
    }

    const AcetateFloorInfo& info_;
    const EffectInfo& effect_;
    const AcetateHostApi* host_;
    AcetateGraph* graph_;
};

// Declares an instance's work to the host.
class Graph {
  public:
    Graph(const AcetateHostApi& host, AcetateGraph* graph) : host_(host), graph_(graph) {}
    // An intermediate target, ceil(canvas / divisor); 1.1: a format other than the floor's.
    // Through declare_target_info, the one form for new code; a 1.0 host lacks it, and then a
    // target in the floor's format goes through declare_target, which every host has.
    void target(const std::string& name, uint32_t divisor, uint32_t format = ACETATE_FORMAT_FLOOR) {
        const bool has_info = ACETATE_SDK_HAS(host_, AcetateHostApi, declare_target_info) &&
                              host_.declare_target_info;
        if (!has_info && format == ACETATE_FORMAT_FLOOR) {
            const AcetateTargetDesc desc{name.c_str(), divisor};
            check(host_.declare_target(graph_, &desc), "declare_target", name);
            return;
        }
        require(has_info, "declare_target_info (target formats)");
        const AcetateTargetInfo desc{sizeof(AcetateTargetInfo), name.c_str(), divisor, format};
        check(host_.declare_target_info(graph_, &desc), "declare_target_info", name);
    }
    void pass(const Pass& pass) {
        std::vector<const char*> inputs;
        for (const std::string& input : pass.inputs) inputs.push_back(input.c_str());
        std::vector<const char*> names;
        for (const std::string& n : pass.input_names)
            names.push_back(n.empty() ? nullptr : n.c_str());
        if (!names.empty() && names.size() != inputs.size())
            throw std::invalid_argument("pass \"" + pass.name +
                                        "\": input_names must name every input or be empty");
        // A 1.0 host would ignore both and then fail to compile the shader, far from the cause.
        if (!names.empty() || !pass.defines.empty())
            require(ACETATE_SDK_HAS(host_, AcetateHostApi, declare_phase),
                    "input_names and defines");
        const std::string glsl(pass.glsl);  // the C ABI wants it NUL-terminated
        AcetatePassDesc desc{};
        desc.struct_size = sizeof(desc);
        desc.name = pass.name.c_str();
        desc.kind = pass.instance_count ? ACETATE_PASS_INSTANCED_QUADS : ACETATE_PASS_FULLSCREEN;
        desc.instance_count = pass.instance_count;
        desc.instance_data_offset = pass.instance_data_offset;
        desc.glsl = pass.spirv.empty() ? glsl.c_str() : nullptr;
        desc.spirv = pass.spirv.empty() ? nullptr : pass.spirv.data();
        desc.spirv_word_count = uint32_t(pass.spirv.size());
        desc.inputs = inputs.data();
        desc.input_count = uint32_t(inputs.size());
        desc.output = pass.output.c_str();
        desc.blend = pass.blend;
        desc.input_names = names.empty() ? nullptr : names.data();
        desc.defines = pass.defines.empty() ? nullptr : pass.defines.c_str();
        check(host_.add_pass(graph_, &desc), "add_pass", pass.name);
    }
    void floor_data(std::span<const float> data) {
        check(host_.set_floor_data(graph_, data.data(), uint32_t(data.size())), "set_floor_data",
              "");
    }
    void log(const std::string& message) { host_.log(graph_, message.c_str()); }
    // A texture for "texture.<name>" inputs: width * height premultiplied RGBA floats; 1.1: or
    // in a format of one or two channels (R16F, RG16F, R32F, RG32F: 1 or 2 floats per texel)
    // or 32-bit RGBA, for data the floor's format would waste memory or precision on.
    void texture(const std::string& name, uint32_t width, uint32_t height,
                 std::span<const float> texels, uint32_t format = ACETATE_FORMAT_FLOOR) {
        const size_t channels = format == ACETATE_FORMAT_R16F || format == ACETATE_FORMAT_R32F ? 1
                                : format == ACETATE_FORMAT_RG16F || format == ACETATE_FORMAT_RG32F
                                    ? 2
                                    : 4;
        if (texels.size() != size_t(width) * height * channels)
            throw std::invalid_argument("texture \"" + name + "\": expected width*height*" +
                                        std::to_string(channels) + " floats");
        // Through add_texture_format, the one form for new code. Only a host that has it reads
        // the format (an older one would read width * height * 4 floats from a shorter array),
        // so without it only a texture in the floor's format can go, through add_texture.
        const bool has_format =
            ACETATE_SDK_HAS(host_, AcetateHostApi, add_texture_format) && host_.add_texture_format;
        if (has_format || format != ACETATE_FORMAT_FLOOR) {
            require(has_format, "add_texture_format (texture formats)");
            const AcetateTextureInfo info{
                sizeof(AcetateTextureInfo), name.c_str(), width, height, texels.data(), format};
            check(host_.add_texture_format(graph_, &info), "add_texture_format", name);
            return;
        }
        // add_texture was appended to the table: a host whose table ends before it lacks it.
        require(ACETATE_SDK_HAS(host_, AcetateHostApi, add_texture) && host_.add_texture,
                "add_texture");
        const AcetateTextureDesc desc{name.c_str(), width, height, texels.data()};
        check(host_.add_texture(graph_, &desc), "add_texture", name);
    }
    // 1.1: how far past the floor's coverage bounds a coverage-expanding effect changes pixels;
    // the host then shades only that much of "result" instead of the whole canvas.
    void reach(uint32_t pixels) {
        require(ACETATE_SDK_HAS(host_, AcetateHostApi, set_reach) && host_.set_reach, "set_reach");
        check(host_.set_reach(graph_, pixels), "set_reach", std::to_string(pixels));
    }
    // 1.1: declares phase_<name> = fract(time / period_seconds), computed in double precision,
    // so a periodic animation stays smooth however long the scene has run.
    void phase(const std::string& name, double period_seconds) {
        require(ACETATE_SDK_HAS(host_, AcetateHostApi, declare_phase) && host_.declare_phase,
                "declare_phase");
        check(host_.declare_phase(graph_, name.c_str(), period_seconds), "declare_phase", name);
    }

  private:
    void check(AcetateStatus status, const char* call, const std::string& what) {
        if (status != ACETATE_OK)
            throw HostRefused(std::string(call) + "(" + what + ") was refused by the host");
    }
    void require(bool supported, const char* what) {
        if (!supported) throw HostRefused(std::string("this host does not support ") + what);
    }
    const AcetateHostApi& host_;
    AcetateGraph* graph_;
};

class Effect {
  public:
    virtual ~Effect() = default;
    virtual EffectInfo info() const = 0;
    // Declares targets, passes and floor data of one instance. Throw to fail the load.
    virtual void build(Graph& graph, const Floor& floor) const = 0;
};

namespace detail {

inline std::string& last_error_text() {
    thread_local std::string text;
    return text;
}

// Owns the C descriptor and every array and string it points to.
class Registration {
  public:
    explicit Registration(std::unique_ptr<Effect> effect)
        : effect_(std::move(effect)), info_(effect_->info()) {
        for (const std::string& m : info_.masks) masks_.push_back(m.c_str());
        for (const Param& p : info_.params) {
            params_.push_back({p.name.c_str(), p.description.c_str(), p.type, p.default_value,
                               p.min_value, p.max_value});
            AcetateParamExt ext{sizeof(AcetateParamExt), p.flags, {}};
            std::copy(p.default_vector.begin(), p.default_vector.end(), ext.default_vector);
            exts_.push_back(ext);
        }
        // Pointers only once exts_ stops growing.
        for (const AcetateParamExt& ext : exts_) ext_pointers_.push_back(&ext);
        for (const Preset& preset : info_.presets) {
            std::vector<AcetatePresetValue> values;
            for (const auto& [name, value] : preset.values) values.push_back({name.c_str(), value});
            preset_values_.push_back(std::move(values));
        }
        for (size_t i = 0; i < info_.presets.size(); ++i)
            presets_.push_back({info_.presets[i].name.c_str(), preset_values_[i].data(),
                                uint32_t(preset_values_[i].size())});
        descriptor_ = {sizeof(AcetateEffectDescriptor),
                       ACETATE_ABI_VERSION,
                       info_.id.c_str(),
                       info_.display_name.c_str(),
                       info_.version_major,
                       info_.version_minor,
                       info_.version_patch,
                       info_.scope,
                       info_.coverage,
                       masks_.empty() ? nullptr : masks_.data(),
                       uint32_t(masks_.size()),
                       params_.empty() ? nullptr : params_.data(),
                       uint32_t(params_.size()),
                       presets_.empty() ? nullptr : presets_.data(),
                       uint32_t(presets_.size()),
                       ACETATE_SOURCE_DIGEST,
                       ACETATE_ABI_MINOR,
                       ext_pointers_.empty() ? nullptr : ext_pointers_.data(),
                       info_.scale_tolerance};
        api_ = {sizeof(AcetateEffectApi), &descriptor_, nullptr, nullptr};
    }
    const Effect& effect() const { return *effect_; }
    const EffectInfo& info() const { return info_; }
    AcetateEffectApi& api() { return api_; }

  private:
    std::unique_ptr<Effect> effect_;
    EffectInfo info_;
    std::vector<const char*> masks_;
    std::vector<AcetateParamDesc> params_;
    std::vector<AcetateParamExt> exts_;
    std::vector<const AcetateParamExt*> ext_pointers_;
    std::vector<std::vector<AcetatePresetValue>> preset_values_;
    std::vector<AcetatePresetDesc> presets_;
    AcetateEffectDescriptor descriptor_{};
    AcetateEffectApi api_{};
};

// Runs `body` and maps any exception to a status, keeping its message for last_error().
template <class Body>
AcetateStatus guarded(Body&& body) noexcept {
    try {
        last_error_text().clear();
        return body();
    } catch (const std::bad_alloc&) {
        last_error_text() = "out of memory";
        return ACETATE_ERROR_OUT_OF_MEMORY;
    } catch (const std::exception& e) {
        last_error_text() = e.what();
        return ACETATE_ERROR_EXCEPTION;
    } catch (...) {
        last_error_text() = "unknown exception";
        return ACETATE_ERROR_EXCEPTION;
    }
}

template <class EffectClass>
Registration& registration() {
    static Registration instance(std::make_unique<EffectClass>());
    return instance;
}

template <class EffectClass>
AcetateStatus build(const AcetateHostApi* host, AcetateGraph* graph,
                    const AcetateFloorInfo* floor) {
    return guarded([&] {
        if (!host || !graph || !floor) return ACETATE_ERROR_INVALID_ARGUMENT;
        Registration& r = registration<EffectClass>();
        Graph g(*host, graph);
        r.effect().build(g, Floor(*floor, r.info(), host, graph));
        return ACETATE_OK;
    });
}

inline const char* last_error() {
    return last_error_text().empty() ? nullptr : last_error_text().c_str();
}

template <class EffectClass>
AcetateStatus entry(uint32_t host_abi_version, const AcetateEffectApi** out_api) {
    return guarded([&] {
        if (!out_api) return ACETATE_ERROR_INVALID_ARGUMENT;
        if (host_abi_version != ACETATE_ABI_VERSION) return ACETATE_ERROR_UNSUPPORTED_ABI;
        AcetateEffectApi& api = registration<EffectClass>().api();
        api.build = &build<EffectClass>;
        api.last_error = &last_error;
        *out_api = &api;
        return ACETATE_OK;
    });
}

}  // namespace detail
}  // namespace acetate::sdk

#undef ACETATE_SDK_HAS

// Defines the plugin's entry point for EffectClass (one per shared library).
#define ACETATE_REGISTER_EFFECT(EffectClass)                                          \
    extern "C" ACETATE_EXPORT AcetateStatus acetate_effect_entry_v1(                  \
        uint32_t host_abi_version, const AcetateEffectApi** out_api) {                \
        return ::acetate::sdk::detail::entry<EffectClass>(host_abi_version, out_api); \
    }
