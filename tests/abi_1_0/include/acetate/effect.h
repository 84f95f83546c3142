/*
 * acetate/effect.h -- the Acetate effect plugin ABI, version 1.
 *
 * A plugin is a shared library exporting ONE function, acetate_effect_entry_v1. Everything
 * crossing the boundary is C: plain structs of fixed-size fields, opaque handles, int32 status
 * codes, function tables. No C++ type and no exception crosses it (the C++ layer in
 * acetate/effect.hpp catches every exception at the boundary and maps it to a status).
 *
 * Plugins never call Vulkan. At load, the host asks each effect instance (one per floor that
 * uses the effect, or one for a global effect) to BUILD its passes: fullscreen fragment passes
 * in GLSL or SPIR-V, the inputs each reads (the previous result, the floor's masks, targets it
 * declared), what each writes, and per-floor data the plugin computed on the CPU. The host
 * compiles, allocates, validates the whole frame once, and records the commands.
 *
 * The contract every effect keeps (docs/contract.md): premultiplied linear RGBA in and out;
 * alpha preserved (out.a == in.a) unless the effect declares itself coverage-expanding, and then
 * alpha may only grow; rgb == 0 wherever a == 0; no NaN or Inf; deterministic; blind to other
 * floors.
 *
 * Names, fields, values and function signatures in this file are fixed by ABI version 1. A
 * later version adds fields only at the end of structs that carry struct_size.
 */
#ifndef ACETATE_EFFECT_H
#define ACETATE_EFFECT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The ABI version this header describes. Fixed by ABI. */
#define ACETATE_ABI_VERSION 1u
/* The one symbol a plugin exports. Fixed by ABI. */
#define ACETATE_ENTRY_POINT_NAME "acetate_effect_entry_v1"

#if defined(_WIN32)
#define ACETATE_EXPORT __declspec(dllexport)
#else
#define ACETATE_EXPORT __attribute__((visibility("default")))
#endif

/* ---- Status codes. Fixed by ABI. A host treats any value it does not know as failure. ---- */
typedef int32_t AcetateStatus;
#define ACETATE_OK 0
#define ACETATE_ERROR_FAILED 1           /* the call failed; see last_error() */
#define ACETATE_ERROR_INVALID_ARGUMENT 2 /* an argument is NULL, out of range or malformed */
#define ACETATE_ERROR_OUT_OF_MEMORY 3
/* the host's ABI version is one the plugin cannot serve */
#define ACETATE_ERROR_UNSUPPORTED_ABI 4
#define ACETATE_ERROR_EXCEPTION 5 /* a C++ exception was caught at the boundary */

/* ---- Descriptor values. Fixed by ABI. ---- */
#define ACETATE_SCOPE_FLOOR 0u  /* runs on each floor that lists it, on that floor alone */
#define ACETATE_SCOPE_GLOBAL 1u /* runs once on the composite of all floors */

#define ACETATE_COVERAGE_PRESERVING 0u /* out.a == in.a at every pixel */
/* may raise alpha (glow past a tile edge), never lower it */
#define ACETATE_COVERAGE_EXPANDING 1u

#define ACETATE_PARAM_FLOAT 0u
#define ACETATE_PARAM_INT 1u  /* a whole number held in a float */
#define ACETATE_PARAM_BOOL 2u /* 0 or 1 held in a float */

#define ACETATE_PASS_FULLSCREEN 0u      /* one fragment per pixel of the pass's output */
#define ACETATE_PASS_INSTANCED_QUADS 1u /* instance_count quads (particles, sprites), see below */

#define ACETATE_BLEND_REPLACE 0u /* the pass's output replaces the target's pixels */
#define ACETATE_BLEND_ADD 1u     /* the pass's output is added to the target's pixels */
#define ACETATE_BLEND_OVER 2u    /* premultiplied over: out = src + dst * (1 - src.a) */

/* One typed parameter. The host clamps every value to [min_value, max_value]. */
typedef struct AcetateParamDesc {
    const char* name;        /* [a-z][a-z0-9_]*, unique within the effect */
    const char* description; /* one sentence for docs and reports */
    uint32_t type;           /* ACETATE_PARAM_* */
    float default_value;     /* must lie in [min_value, max_value] */
    float min_value;
    float max_value;
} AcetateParamDesc;

/* One value of a quality preset. */
typedef struct AcetatePresetValue {
    const char* param; /* a parameter name of this effect */
    float value;
} AcetatePresetValue;

/* A quality preset: "low", "medium", "high" or "ultra", mapping to parameter values. */
typedef struct AcetatePresetDesc {
    const char* name;
    const AcetatePresetValue* values;
    uint32_t value_count;
} AcetatePresetDesc;

/*
 * What an effect is. Owned by the plugin; must stay valid and unchanged while the library is
 * loaded. Checked by the host at load (docs/plugin-guide.md lists every check).
 */
typedef struct AcetateEffectDescriptor {
    uint32_t struct_size;     /* sizeof(AcetateEffectDescriptor) as the plugin was built */
    uint32_t abi_version;     /* ACETATE_ABI_VERSION the plugin was built against */
    const char* id;           /* reverse-DNS, e.g. "acetate.lighting" */
    const char* display_name; /* e.g. "Lighting" */
    uint32_t version_major;   /* the plugin's own version */
    uint32_t version_minor;
    uint32_t version_patch;
    uint32_t scope;           /* ACETATE_SCOPE_* */
    uint32_t coverage;        /* ACETATE_COVERAGE_* */
    const char* const* masks; /* mask kinds it reads, e.g. {"water"}; may be NULL if none */
    uint32_t mask_count;
    const AcetateParamDesc* params;
    uint32_t param_count;
    const AcetatePresetDesc* presets;
    uint32_t preset_count;
    const char* source_digest; /* digest of the plugin's sources, embedded at build; may be "" */
} AcetateEffectDescriptor;

/* A point light of the scene, in scene pixels (origin top-left, y down), linear colour. */
typedef struct AcetateLight {
    float pos[2];
    float radius;
    float color[3];
    float intensity;
} AcetateLight;

/*
 * What an instance is built for. Owned by the host; valid only during build().
 * params holds the resolved values (default, then preset, then the scene's params), clamped,
 * in the order of the descriptor's params.
 */
typedef struct AcetateFloorInfo {
    uint32_t struct_size;
    uint32_t floor_index;   /* UINT32_MAX for a global instance */
    const char* floor_name; /* "" for a global instance */
    uint32_t canvas_width;
    uint32_t canvas_height;
    const AcetateLight* lights; /* the floor's lights; NULL when light_count is 0 */
    uint32_t light_count;
    const float* params;
    uint32_t param_count;
    const char* const* masks_present; /* mask kinds this floor has, of those the effect reads */
    uint32_t masks_present_count;
} AcetateFloorInfo;

/* An intermediate target: RGBA in the host's target format, ceil(canvas / divisor) in size. */
typedef struct AcetateTargetDesc {
    const char* name; /* [a-z][a-z0-9_]*, unique within the instance; not "previous"/"result" */
    uint32_t divisor; /* 1, 2, 4, 8, ... */
} AcetateTargetDesc;

/*
 * One pass. Its fragment shader sees (host-generated declarations, docs/plugin-guide.md):
 *   uniform block AcetateFrame: acetate_canvas (w, h, 1/w, 1/h), acetate_output (same for this
 *     pass's output), acetate_time (seconds), acetate_floor, and param_<name> per parameter;
 *   one sampler2D per input, bound in the order of `inputs`, named after the input with
 *     '.' replaced by '_': "previous", "mask.water" -> mask_water, "texture.ramp" ->
 *     texture_ramp, "bright" -> bright;
 *   floor_data[]: the floats given to set_floor_data (std430 storage buffer);
 *   out vec4 out_color.
 * The plugin's GLSL supplies everything after those declarations, including main().
 *
 * An ACETATE_PASS_INSTANCED_QUADS pass draws instance_count quads; quad i covers the scene rect
 * (x, y, width, height) = floor_data[instance_data_offset + 4 * i + 0..3], in scene pixels. Its
 * fragment shader also sees `in vec2 acetate_uv` (0..1 across the quad, y down) and
 * `flat in int acetate_instance` (i); it reads any further per-instance data from floor_data.
 * Only the quads' pixels are shaded, so it usually follows a pass that copies "previous" into
 * the same output, and blends with ACETATE_BLEND_ADD or ACETATE_BLEND_OVER.
 */
typedef struct AcetatePassDesc {
    uint32_t struct_size;
    const char* name;      /* unique within the instance, e.g. "down1" */
    uint32_t kind;         /* ACETATE_PASS_* */
    const char* glsl;      /* fragment source after the host's declarations, or NULL */
    const uint32_t* spirv; /* or a whole SPIR-V fragment module with the same interface */
    uint32_t spirv_word_count;
    const char* const* inputs;     /* "previous", "mask.<kind>", "texture.<name>" or a target */
    uint32_t input_count;          /* at most 8 */
    const char* output;            /* "result" (the effect's output) or a target name */
    uint32_t blend;                /* ACETATE_BLEND_*; ADD and OVER need an earlier REPLACE */
    uint32_t instance_count;       /* instanced quads: how many (1 .. 1048576); else 0 */
    uint32_t instance_data_offset; /* instanced quads: first float of the rects in floor_data */
} AcetatePassDesc;

/*
 * A texture the plugin prepares on the CPU for one instance (a lookup table, a distance field):
 * premultiplied RGBA floats, row-major, y down, uploaded at load in the target format. Passes
 * read it as the input "texture.<name>".
 */
typedef struct AcetateTextureDesc {
    const char* name;  /* [a-z][a-z0-9_]*, unique within the instance */
    uint32_t width;    /* 1 .. 16384 */
    uint32_t height;   /* 1 .. 16384 */
    const float* rgba; /* width * height * 4 floats, all finite; copied */
} AcetateTextureDesc;

/* Host-owned handle through which build() declares an instance's work. Opaque. */
typedef struct AcetateGraph AcetateGraph;

/*
 * Functions the host lends to build(). Every function copies what it is given; the plugin
 * keeps ownership of its arguments. Each returns ACETATE_OK, or ACETATE_ERROR_INVALID_ARGUMENT
 * with the reason recorded by the host (it names the plugin, pass and resource).
 */
typedef struct AcetateHostApi {
    uint32_t struct_size;
    /* Declares an intermediate target. Errors: bad name, duplicate, divisor not a power of 2. */
    AcetateStatus (*declare_target)(AcetateGraph* graph, const AcetateTargetDesc* target);
    /* Appends a pass; passes run in the order added. Errors: see AcetatePassDesc. */
    AcetateStatus (*add_pass)(AcetateGraph* graph, const AcetatePassDesc* pass);
    /* Sets this instance's floor_data (replacing earlier data). At most 1 Mi floats. */
    AcetateStatus (*set_floor_data)(AcetateGraph* graph, const float* data, uint32_t count);
    /* Writes a line to the host's standard error, prefixed with the instance label. */
    void (*log)(AcetateGraph* graph, const char* message);
    /* Adds a texture (see AcetateTextureDesc). Errors: bad or duplicate name, size, NULL data,
     * a value that is not finite. */
    AcetateStatus (*add_texture)(AcetateGraph* graph, const AcetateTextureDesc* texture);
} AcetateHostApi;

/*
 * The plugin's function table. Owned by the plugin; valid while the library is loaded.
 */
typedef struct AcetateEffectApi {
    uint32_t struct_size;                      /* sizeof(AcetateEffectApi) */
    const AcetateEffectDescriptor* descriptor; /* never NULL */
    /*
     * Declares one instance's targets, passes and floor data. Called at scene load, once per
     * floor using the effect (or once, for a global effect), never during a frame. Must be
     * deterministic and must not keep `host`, `graph` or `floor` after returning.
     * Returns ACETATE_OK, or any error status (the host then refuses the scene's load with the
     * plugin's last_error() text).
     */
    AcetateStatus (*build)(const AcetateHostApi* host, AcetateGraph* graph,
                           const AcetateFloorInfo* floor);
    /* The text of this thread's last failure, or NULL. Owned by the plugin. */
    const char* (*last_error)(void);
} AcetateEffectApi;

/*
 * The entry point. `host_abi_version` is ACETATE_ABI_VERSION of the host. On success, sets
 * *out_api to the plugin's table and returns ACETATE_OK. Returns ACETATE_ERROR_UNSUPPORTED_ABI
 * if the plugin cannot serve that version, ACETATE_ERROR_INVALID_ARGUMENT if out_api is NULL.
 * May be called more than once; returns the same table each time.
 */
typedef AcetateStatus (*AcetateEntryPoint)(uint32_t host_abi_version,
                                           const AcetateEffectApi** out_api);

#ifdef __cplusplus
}
#endif

#endif /* ACETATE_EFFECT_H */
