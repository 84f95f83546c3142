#include "plugins/effect_descriptor.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <regex>
#include <set>

namespace acetate {

bool is_simple_name(const std::string& name) {
    static const std::regex pattern("[a-z][a-z0-9_]*");
    return std::regex_match(name, pattern);
}

bool is_preset_name(const std::string& name) {
    static const std::regex pattern("[a-z][a-z0-9_-]*");
    return name.size() <= kMaxPresetNameLength && std::regex_match(name, pattern);
}

int EffectDescriptor::param_index(const std::string& name) const {
    for (size_t i = 0; i < params.size(); ++i)
        if (params[i].name == name) return int(i);
    return -1;
}

uint32_t EffectParam::components() const {
    return type == ACETATE_PARAM_VEC2                                  ? 2
           : type == ACETATE_PARAM_VEC3 || type == ACETATE_PARAM_COLOR ? 3
                                                                       : 1;
}

std::string abi_version_string(uint32_t minor) {
    return fmt::format("1.{}", minor);
}

std::string EffectDescriptor::version_string() const {
    return fmt::format("{}.{}.{}", version[0], version[1], version[2]);
}

namespace {

Error bad(const std::string& where, const std::string& what) {
    return make_error(ErrorCode::InvalidInput, fmt::format("{}: descriptor: {}", where, what));
}

}  // namespace

Result<EffectDescriptor> copy_descriptor(const AcetateEffectDescriptor* d,
                                         const std::string& where) {
    if (!d) return bad(where, "the plugin returned no descriptor (NULL)");
    // ABI 1.0's descriptor ends at source_digest; later fields are read only when present.
    constexpr size_t kSize10 = offsetof(AcetateEffectDescriptor, abi_minor);
    if (d->struct_size < kSize10)
        return bad(where, fmt::format("struct_size {} is smaller than ABI 1.0's {}", d->struct_size,
                                      kSize10));
    if (d->abi_version != ACETATE_ABI_VERSION)
        return bad(where, fmt::format("built for ABI version {}, this host speaks {}",
                                      d->abi_version, ACETATE_ABI_VERSION));
    auto has = [&](size_t offset, size_t size) { return d->struct_size >= offset + size; };
    EffectDescriptor out;
    if (has(offsetof(AcetateEffectDescriptor, abi_minor), sizeof(uint32_t))) {
        out.abi_minor = d->abi_minor;
        if (out.abi_minor > ACETATE_ABI_MINOR)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: built for Acetate ABI {}; this host supports ABI {}",
                                          where, abi_version_string(out.abi_minor),
                                          abi_version_string(ACETATE_ABI_MINOR)));
    }
    const AcetateParamExt* const* exts =
        has(offsetof(AcetateEffectDescriptor, param_exts), sizeof(void*)) ? d->param_exts : nullptr;
    if (has(offsetof(AcetateEffectDescriptor, scale_tolerance), sizeof(float))) {
        out.scale_tolerance = d->scale_tolerance;
        if (!(out.scale_tolerance >= 0 && out.scale_tolerance <= kMaxScaleTolerance))
            return bad(where, fmt::format("scale_tolerance {} is not a number from 0 to {}",
                                          out.scale_tolerance, kMaxScaleTolerance));
    }
    if (!d->id || !is_reverse_dns(d->id))
        return bad(where,
                   fmt::format("id \"{}\" is not a reverse-DNS name like \"com.example.glow\"",
                               d->id ? d->id : "(null)"));
    out.id = d->id;
    out.display_name = d->display_name ? d->display_name : out.id;
    out.source_digest = d->source_digest ? d->source_digest : "";
    out.version[0] = d->version_major;
    out.version[1] = d->version_minor;
    out.version[2] = d->version_patch;
    if (d->scope != ACETATE_SCOPE_FLOOR && d->scope != ACETATE_SCOPE_GLOBAL)
        return bad(where, fmt::format("scope {} is neither floor (0) nor global (1)", d->scope));
    if (d->coverage != ACETATE_COVERAGE_PRESERVING && d->coverage != ACETATE_COVERAGE_EXPANDING)
        return bad(where, fmt::format("coverage {} is neither preserving (0) nor expanding (1)",
                                      d->coverage));
    out.scope = d->scope;
    out.coverage = d->coverage;

    if (d->mask_count && !d->masks) return bad(where, "mask_count > 0 but masks is NULL");
    for (uint32_t i = 0; i < d->mask_count; ++i) {
        if (!d->masks[i] || !is_simple_name(d->masks[i]))
            return bad(where, fmt::format("masks[{}] is not a name like \"water\"", i));
        out.masks.emplace_back(d->masks[i]);
    }

    if (d->param_count && !d->params) return bad(where, "param_count > 0 but params is NULL");
    if (d->param_count > 256)
        return bad(where, fmt::format("{} parameters; at most 256", d->param_count));
    std::set<std::string> names;
    for (uint32_t i = 0; i < d->param_count; ++i) {
        const AcetateParamDesc& p = d->params[i];
        const std::string name = p.name ? p.name : "";
        const std::string field = fmt::format("params[{}] \"{}\"", i, name);
        if (!is_simple_name(name)) return bad(where, field + ": name must match [a-z][a-z0-9_]*");
        if (!names.insert(name).second) return bad(where, field + ": duplicate name");
        const uint32_t last_type = out.abi_minor >= 1 ? ACETATE_PARAM_COLOR : ACETATE_PARAM_BOOL;
        if (p.type > last_type)
            return bad(where, fmt::format("{}: unknown type {}", field, p.type));
        EffectParam param{name,        p.description ? p.description : "",
                          p.type,      p.default_value,
                          p.min_value, p.max_value};
        param.default_vector[0] = p.default_value;
        const AcetateParamExt* ext = exts ? exts[i] : nullptr;
        if (ext && ext->struct_size < offsetof(AcetateParamExt, default_vector) + sizeof(float[4]))
            return bad(where, fmt::format("{}: param_exts[{}].struct_size {} is too small", field,
                                          i, ext->struct_size));
        if (ext) {
            if (ext->flags & ~uint32_t(ACETATE_PARAM_HIDDEN))
                return bad(where, fmt::format("{}: unknown flags {:#x}", field, ext->flags));
            param.hidden = (ext->flags & ACETATE_PARAM_HIDDEN) != 0;
        }
        const uint32_t components = param.components();
        if (components > 1) {
            if (!ext)
                return bad(where, field + ": a vector parameter needs param_exts[" +
                                      std::to_string(i) + "] for its default");
            for (uint32_t c = 0; c < 4; ++c)
                param.default_vector[c] = c < components ? ext->default_vector[c] : 0.0f;
            if (param.default_vector[0] != p.default_value)
                return bad(where, fmt::format("{}: default_value {} differs from "
                                              "default_vector[0] {}",
                                              field, p.default_value, param.default_vector[0]));
            for (uint32_t c = 1; c < components; ++c) {
                const float v = param.default_vector[c];
                if (!std::isfinite(v) || v < p.min_value || v > p.max_value)
                    return bad(where, fmt::format("{}: default component {} = {} is outside "
                                                  "[{}, {}]",
                                                  field, c, v, p.min_value, p.max_value));
            }
        }
        if (!std::isfinite(p.default_value) || !std::isfinite(p.min_value) ||
            !std::isfinite(p.max_value))
            return bad(where, field + ": default, min and max must be finite");
        if (p.min_value > p.max_value)
            return bad(where, fmt::format("{}: min {} is greater than max {}", field, p.min_value,
                                          p.max_value));
        if (p.default_value < p.min_value || p.default_value > p.max_value)
            return bad(where, fmt::format("{}: default {} is outside [{}, {}]", field,
                                          p.default_value, p.min_value, p.max_value));
        const bool whole = std::floor(p.default_value) == p.default_value;
        if ((p.type == ACETATE_PARAM_INT || p.type == ACETATE_PARAM_BOOL) && !whole)
            return bad(where, fmt::format("{}: default {} of an int/bool parameter is not a whole "
                                          "number",
                                          field, p.default_value));
        out.params.push_back(param);
    }

    if (d->preset_count && !d->presets) return bad(where, "preset_count > 0 but presets is NULL");
    for (uint32_t i = 0; i < d->preset_count; ++i) {
        const AcetatePresetDesc& preset = d->presets[i];
        const std::string name = preset.name ? preset.name : "";
        if (!is_preset_name(name))
            return bad(where, fmt::format("presets[{}] \"{}\": a preset's name is 1 to {} "
                                          "lower-case letters, digits, '-' or '_', starting with "
                                          "a letter",
                                          i, name, kMaxPresetNameLength));
        if (out.presets.count(name))
            return bad(where, fmt::format("presets[{}] \"{}\": duplicate", i, name));
        if (preset.value_count && !preset.values)
            return bad(where, fmt::format("presets[{}]: value_count > 0 but values is NULL", i));
        out.preset_order.push_back(name);
        auto& values = out.presets[name];
        for (uint32_t v = 0; v < preset.value_count; ++v) {
            const std::string param = preset.values[v].param ? preset.values[v].param : "";
            const int index = out.param_index(param);
            if (index < 0)
                return bad(where, fmt::format("presets[{}] \"{}\": unknown parameter \"{}\"", i,
                                              name, param));
            const EffectParam& p = out.params[size_t(index)];
            if (p.components() > 1)
                return bad(where, fmt::format("presets[{}] \"{}\": \"{}\" is a vector parameter; "
                                              "presets set scalar parameters only",
                                              i, name, param));
            const float value = preset.values[v].value;
            if (!(value >= p.min_value && value <= p.max_value))
                return bad(where, fmt::format("presets[{}] \"{}\": {} = {} is outside [{}, {}]", i,
                                              name, param, value, p.min_value, p.max_value));
            values[param] = value;
        }
    }
    return out;
}

}  // namespace acetate
