// acetate/effect.hpp -- the C++ layer for plugin authors, header-only, over acetate/effect.h.
//
// Write a class deriving from acetate::sdk::Effect, describe it in info(), declare its passes
// in build(), and register it with ACETATE_REGISTER_EFFECT(ClassName) in one .cpp file. The
// macro defines the C entry point; every call into the plugin runs inside a catch-all that
// turns exceptions into ACETATE_ERROR_EXCEPTION with the message kept for last_error(), so no
// exception ever crosses the library boundary. See docs/plugin-guide.md.
#pragma once

#include <acetate/effect.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#ifndef ACETATE_SOURCE_DIGEST
#define ACETATE_SOURCE_DIGEST ""  // acetate_add_effect() defines it from the plugin's sources
#endif

namespace acetate::sdk {

// Thrown by Graph when the host refuses a declaration; caught at the boundary.
class HostRefused : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct Param {
    std::string name;
    std::string description;
    float default_value = 0, min_value = 0, max_value = 1;
    uint32_t type = ACETATE_PARAM_FLOAT;
};

struct Preset {
    std::string name;  // "low", "medium", "high" or "ultra"
    std::vector<std::pair<std::string, float>> values;
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
};

struct Pass {
    std::string name;
    std::string glsl;                 // after the host's declarations; defines main()
    std::vector<std::string> inputs;  // "previous", "mask.<kind>", "texture.<name>", a target
    std::string output = "result";
    uint32_t blend = ACETATE_BLEND_REPLACE;
    uint32_t instance_count = 0;  // > 0: an instanced-quad pass (see acetate/effect.h)
    uint32_t instance_data_offset = 0;
    std::vector<uint32_t> spirv;  // instead of glsl: a whole fragment module
};

// The floor an instance is built for, with parameters looked up by name.
class Floor {
  public:
    Floor(const AcetateFloorInfo& info, const EffectInfo& effect) : info_(info), effect_(effect) {}
    bool is_global() const { return info_.floor_index == UINT32_MAX; }
    uint32_t index() const { return info_.floor_index; }
    std::string_view name() const { return info_.floor_name ? info_.floor_name : ""; }
    uint32_t canvas_width() const { return info_.canvas_width; }
    uint32_t canvas_height() const { return info_.canvas_height; }
    std::span<const AcetateLight> lights() const {
        return {info_.lights, info_.lights ? info_.light_count : 0};
    }
    // The resolved value of a parameter; throws for a name the effect did not declare.
    float param(std::string_view name) const {
        for (size_t i = 0; i < effect_.params.size() && i < info_.param_count; ++i)
            if (effect_.params[i].name == name) return info_.params[i];
        throw std::invalid_argument("unknown parameter \"" + std::string(name) + "\"");
    }
    bool has_mask(std::string_view kind) const {
        for (uint32_t i = 0; i < info_.masks_present_count; ++i)
            if (kind == info_.masks_present[i]) return true;
        return false;
    }

  private:
    const AcetateFloorInfo& info_;
    const EffectInfo& effect_;
};

// Declares an instance's work to the host.
class Graph {
  public:
    Graph(const AcetateHostApi& host, AcetateGraph* graph) : host_(host), graph_(graph) {}
    void target(const std::string& name, uint32_t divisor) {
        const AcetateTargetDesc desc{name.c_str(), divisor};
        check(host_.declare_target(graph_, &desc), "declare_target", name);
    }
    void pass(const Pass& pass) {
        std::vector<const char*> inputs;
        for (const std::string& input : pass.inputs) inputs.push_back(input.c_str());
        AcetatePassDesc desc{};
        desc.struct_size = sizeof(desc);
        desc.name = pass.name.c_str();
        desc.kind = pass.instance_count ? ACETATE_PASS_INSTANCED_QUADS : ACETATE_PASS_FULLSCREEN;
        desc.instance_count = pass.instance_count;
        desc.instance_data_offset = pass.instance_data_offset;
        desc.glsl = pass.spirv.empty() ? pass.glsl.c_str() : nullptr;
        desc.spirv = pass.spirv.empty() ? nullptr : pass.spirv.data();
        desc.spirv_word_count = uint32_t(pass.spirv.size());
        desc.inputs = inputs.data();
        desc.input_count = uint32_t(inputs.size());
        desc.output = pass.output.c_str();
        desc.blend = pass.blend;
        check(host_.add_pass(graph_, &desc), "add_pass", pass.name);
    }
    void floor_data(std::span<const float> data) {
        check(host_.set_floor_data(graph_, data.data(), uint32_t(data.size())), "set_floor_data",
              "");
    }
    void log(const std::string& message) { host_.log(graph_, message.c_str()); }
    // A texture for "texture.<name>" inputs: width * height premultiplied RGBA floats.
    void texture(const std::string& name, uint32_t width, uint32_t height,
                 std::span<const float> rgba) {
        if (rgba.size() != size_t(width) * height * 4)
            throw std::invalid_argument("texture \"" + name + "\": expected width*height*4 floats");
        // add_texture was appended to the table: a host whose table ends before it lacks it.
        if (host_.struct_size < offsetof(AcetateHostApi, add_texture) + sizeof(void*) ||
            !host_.add_texture)
            throw HostRefused("this host does not support add_texture");
        const AcetateTextureDesc desc{name.c_str(), width, height, rgba.data()};
        check(host_.add_texture(graph_, &desc), "add_texture", name);
    }

  private:
    void check(AcetateStatus status, const char* call, const std::string& what) {
        if (status != ACETATE_OK)
            throw HostRefused(std::string(call) + "(" + what + ") was refused by the host");
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
        for (const Param& p : info_.params)
            params_.push_back({p.name.c_str(), p.description.c_str(), p.type, p.default_value,
                               p.min_value, p.max_value});
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
                       ACETATE_SOURCE_DIGEST};
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
        r.effect().build(g, Floor(*floor, r.info()));
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

// Defines the plugin's entry point for EffectClass (one per shared library).
#define ACETATE_REGISTER_EFFECT(EffectClass)                                          \
    extern "C" ACETATE_EXPORT AcetateStatus acetate_effect_entry_v1(                  \
        uint32_t host_abi_version, const AcetateEffectApi** out_api) {                \
        return ::acetate::sdk::detail::entry<EffectClass>(host_abi_version, out_api); \
    }
