/*
 * acetate/effect.h -- the Acetate effect plugin ABI, version 1.2.
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
 * later minor version adds fields only at the end of structs that carry struct_size, and adds
 * new structs (each with struct_size first) where a 1.0 struct had none. Every reader checks
 * struct_size before it reads a field added after 1.0: the host does so for what a plugin
 * passes, and the C++ layer (acetate/effect.hpp) for what the host passes. A plugin built
 * against 1.0 therefore loads and renders unchanged in a 1.1 host.
 *
 * What 1.1 added, each marked "1.1" where it is declared: the descriptor's abi_minor and
 * param_exts (vector and colour parameters, hidden parameters); lights with height and a sun
 * (AcetateLightInfo); the floor's coverage bounds, floor count and vector parameter values;
 * masks readable at build (read_mask); target formats (declare_target_info); declared reach
 * (set_reach); periodic phases computed in double precision (declare_phase); per-pass input
 * names and defines; struct_size-first forms of the target and texture descriptions.
 *
 * What 1.2 added: a camera. A host may render a region of the scene at a scale (an interactive
 * program pans and zooms): "previous", "result", every target and every mask a pass reads are
 * then in render pixels, the camera's output, not scene pixels. build() is told the scale and
 * the render size it builds for (AcetateFloorInfo's 1.2 fields) and runs again when they
 * change; every pass sees the camera in the push-constant block AcetateView and converts with
 * acetate_scene_position() and acetate_render_position() (docs/plugin-guide.md, "Cameras").
 * Lengths a plugin gives the host stay in scene pixels: lights, floor data rects of instanced
 * quads, the declared reach, coverage bounds, read_mask's image. A host renders a plugin built
 * against 1.0 or 1.1 only at the whole canvas and scale 1 (it refuses another camera, naming
 * the plugin), where every 1.2 field has the value that makes it read as before. A descriptor
 * may declare how far a render at another scale may stray (scale_tolerance).
 *
 * One way to do each thing. Where 1.1 added a fuller form of a 1.0 function, new code uses the
 * fuller one and the older stays only for plugins built before it: declare_target_info, not
 * declare_target; add_texture_format, not add_texture or add_texture_info; AcetateLightInfo
 * (floor->light_infos), not AcetateLight. acetate/effect.hpp calls the fuller form whenever
 * the host has it, and the older only on a host without it.
 *
 * Call order, threads and lifetime, as the host keeps them:
 *  1. Load. The host opens the library (its static constructors run) only after the load
 *     policy accepted its bytes, then calls the entry point, then reads the descriptor and
 *     copies it. The entry point may be called more than once; it returns the same table.
 *  2. build(). At scene load, once per instance (each floor using the effect, or once for a
 *     global effect), in the floors' order; again when a program changes a live parameter or
 *     preset, or reloads the scene. Never while a frame renders: a frame runs only the passes
 *     build() declared, and none of the plugin's code. The host lends `host`, `graph` and
 *     `floor` for the call only. One host object calls build() from one thread at a time (the
 *     thread that loads), but a program may run several hosts, which may call the same
 *     library's build() at once from several threads: build() keeps no unsynchronised global
 *     state.
 *  3. last_error(). Right after a call that failed, on the thread that made it.
 *  4. Unload. When nothing holds the library any more (the last scene using it is gone, the
 *     host is destroyed, or a rebuilt file replaced it on a reload) the host closes it and its
 *     static destructors run. A library is never called after that.
 * Every call into the plugin is watched (docs/contract.md, rule 7): it must leave the process as
 * it found it (floating-point environment, signals, environment, descriptors, threads, working
 * folder, umask, locale).
 */
#ifndef ACETATE_EFFECT_H
#define ACETATE_EFFECT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The ABI major version this header describes: what the host passes to the entry point.
 * Fixed by ABI. */
#define ACETATE_ABI_VERSION 1u
/* The minor version (1.2): additions only. The descriptor's abi_minor says which minor a
 * plugin was built against; a host refuses a plugin newer than itself. */
#define ACETATE_ABI_MINOR 2u
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
/* 1.1: vector parameters. min_value and max_value bound every component; the default of each
 * component is in the parameter's AcetateParamExt (default_value must equal its first). A
 * scene gives them as JSON arrays; presets cannot set them. */
#define ACETATE_PARAM_VEC2 3u /* e.g. an offset in scene pixels */
#define ACETATE_PARAM_VEC3 4u
#define ACETATE_PARAM_COLOR 5u /* linear RGB */

/* 1.1: AcetateParamExt flags. */
/* Set only by presets (a quality knob such as a tap count): a scene may not set it, and the
 * harness does not sweep it as a user parameter. */
#define ACETATE_PARAM_HIDDEN 1u

/* 1.1: target formats (AcetateTargetInfo). FLOOR is the format of the floor's own images,
 * "previous" and "result" (RGBA16F unless the host renders in RGBA32F). */
#define ACETATE_FORMAT_FLOOR 0u
#define ACETATE_FORMAT_R16F 1u
#define ACETATE_FORMAT_RG16F 2u
#define ACETATE_FORMAT_RGBA16F 3u
#define ACETATE_FORMAT_R32F 4u
#define ACETATE_FORMAT_RG32F 5u
#define ACETATE_FORMAT_RGBA32F 6u

/* 1.1: light kinds (AcetateLightInfo). */
#define ACETATE_LIGHT_POINT 0u
#define ACETATE_LIGHT_SUN 1u /* directional: one per floor at most */

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

/*
 * 1.1: what ABI 1.0's AcetateParamDesc cannot say about a parameter. The descriptor's
 * param_exts, when not NULL, holds param_count pointers; params[i]'s extension is
 * param_exts[i] (NULL: none, as in 1.0).
 */
typedef struct AcetateParamExt {
    uint32_t struct_size;    /* sizeof(AcetateParamExt) as the plugin was built */
    uint32_t flags;          /* ACETATE_PARAM_HIDDEN, ... */
    float default_vector[4]; /* VEC2, VEC3, COLOR: the default of each component */
} AcetateParamExt;

/* One value of a quality preset. */
typedef struct AcetatePresetValue {
    const char* param; /* a parameter name of this effect */
    float value;
} AcetatePresetValue;

/* A preset: a name (1 to 32 of a-z, 0-9, '-', '_', starting with a letter: "low", "medium",
 * "high", "ultra", or any other, such as "draft"), mapping to parameter values. Declare
 * presets cheapest first. */
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
    /* ---- 1.1 (read only when struct_size covers them) ---- */
    uint32_t abi_minor;                       /* ACETATE_ABI_MINOR the plugin was built against */
    const AcetateParamExt* const* param_exts; /* NULL, or param_count pointers (each may be NULL) */
    /* ---- 1.2 (read only when struct_size covers it; 0 for a descriptor that ends before) ---- */
    /* How far a render at another scale may stray from the render at scale 1, as a fraction of
     * the largest value there. At scale 1/2 each pixel, channel by channel, must lie within the
     * range the scale-1 render takes over the scene pixels it covers and one around them,
     * widened by this fraction of that range's largest magnitude (the harness's camera-scale
     * relation, docs/harness.md). 0 for an effect whose output is a function of the scene
     * position and the pixels there; one that gathers around a pixel (refraction) or draws
     * shapes smaller than a pixel (sparks) needs more. Finite, 0 to 4. */
    float scale_tolerance;
} AcetateEffectDescriptor;

/* A point light of the scene, in scene pixels (origin top-left, y down), linear colour.
 * ABI 1.0's view of a light; 1.1 plugins read AcetateLightInfo, which also has the height. */
typedef struct AcetateLight {
    float pos[2];
    float radius;
    float color[3];
    float intensity;
} AcetateLight;

/*
 * 1.1: a light as ABI 1.1 describes it. Scene space: x right, y down (scene pixels), z up out of
 * the floor towards the viewer.
 */
typedef struct AcetateLightInfo {
    uint32_t struct_size; /* sizeof(AcetateLightInfo) as the host was built */
    uint32_t kind;        /* ACETATE_LIGHT_* */
    float pos[2];         /* POINT: position on the floor, scene pixels */
    float height;         /* POINT: height above the floor, scene pixels, >= 0 */
    float radius;         /* POINT: reach, scene pixels, > 0 */
    float direction[3];   /* SUN: unit vector from the floor towards the sun (x, y, z) */
    float color[3];       /* linear */
    float intensity;      /* >= 0 */
} AcetateLightInfo;

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
    /* ---- 1.1 (check struct_size before reading) ---- */
    /* The floor's point lights in scene order, then its sun if it has one. Each element's own
     * struct_size says how much of it the host filled. NULL when light_info_count is 0. */
    const AcetateLightInfo* const* light_infos;
    uint32_t light_info_count;
    /* The pixels the floor's tiles cover: x0, y0, x1, y1 with x1, y1 exclusive (scene pixels);
     * all 0 for a floor without tiles; the whole canvas for a global instance. */
    int32_t coverage_bounds[4];
    uint32_t floor_count; /* floors in the scene */
    /* 4 floats per parameter, in the order of params: a vector parameter's components (x, y,
     * z), a scalar's value in x; the rest 0. */
    const float* param_vectors;
    /* ---- 1.2 (check struct_size before reading) ---- */
    uint32_t host_abi_minor; /* the ABI minor the host implements (2 for a 1.2 host) */
    /* Render pixels per scene pixel this instance is built for (> 0; 1 without a camera): a
     * blur of 8 scene pixels is 8 * render_scale render pixels. build() runs again when the
     * program changes the camera's scale. */
    float render_scale;
    /* The size of "previous" and "result" (the camera's output; the canvas without one). A
     * target of divisor d is ceil(render_width / d) x ceil(render_height / d). */
    uint32_t render_width;
    uint32_t render_height;
} AcetateFloorInfo;

/* An intermediate target: RGBA in the host's target format, ceil(render size / divisor) in size
 * (the render size is the canvas unless a camera says otherwise, see render_width). */
typedef struct AcetateTargetDesc {
    const char* name; /* [a-z][a-z0-9_]*, unique within the instance; not "previous"/"result" */
    uint32_t divisor; /* 1, 2, 4, 8, ... */
} AcetateTargetDesc;

/* 1.1: an intermediate target with a format. */
typedef struct AcetateTargetInfo {
    uint32_t struct_size; /* sizeof(AcetateTargetInfo) as the plugin was built */
    const char* name;     /* as AcetateTargetDesc */
    uint32_t divisor;     /* as AcetateTargetDesc */
    uint32_t format;      /* ACETATE_FORMAT_*; a pass may blend (ADD, OVER) only onto 16- and
                             32-bit float formats the device can blend */
} AcetateTargetInfo;

/*
 * 1.1: a mask as build() reads it (read_mask): the floor's masks of one kind composited into one
 * scene-space image (scene pixels whatever the camera; a pass reading "mask.<kind>" reads it in
 * render pixels, like "previous"), canvas-sized RGBA floats as the mask files hold them (data:
 * not colour-decoded, not premultiplied), row-major, y down. Owned by the
 * host, read-only, valid only until build() returns. A floor without the kind reads an all-zero
 * image of the same size.
 */
typedef struct AcetateMaskImage {
    uint32_t struct_size; /* set by the plugin: sizeof(AcetateMaskImage) as it was built */
    uint32_t width;
    uint32_t height;
    uint32_t channels; /* 4 */
    const float* data; /* width * height * channels floats */
} AcetateMaskImage;

/*
 * One pass. Its fragment shader sees (host-generated declarations, docs/plugin-guide.md):
 *   uniform block AcetateFrame: acetate_canvas (w, h, 1/w, 1/h), acetate_output (same for this
 *     pass's output), acetate_time (seconds), acetate_floor, and param_<name> per parameter;
 *   one sampler2D per input, bound in the order of `inputs`, named after the input with
 *     '.' replaced by '_': "previous", "mask.water" -> mask_water, "texture.ramp" ->
 *     texture_ramp, "bright" -> bright (1.1: or as input_names says);
 *   floor_data[]: the floats given to set_floor_data (std430 storage buffer);
 *   out vec4 out_color.
 * 1.1 adds (docs/plugin-guide.md has the whole list): acetate_size_<input> (vec4: the input's
 * width, height and their reciprocals), the lights block acetate_lights[] with
 * acetate_light_count, acetate_time_whole and acetate_time_fraction, phase_<name> per declared
 * phase, param_<name> as a vec2/vec3 for vector parameters, and the pass's defines.
 * The plugin's GLSL supplies everything after those declarations, including main().
 *
 * An ACETATE_PASS_INSTANCED_QUADS pass draws instance_count quads; quad i covers the scene rect
 * (x, y, width, height) = floor_data[instance_data_offset + 4 * i + 0..3], in scene pixels. Its
 * fragment shader also sees `in vec2 acetate_uv` (0..1 across the quad, y down) and
 * `flat in int acetate_instance` (i); it reads any further per-instance data from floor_data.
 * Only the quads' pixels are shaded, so it usually follows a pass that copies "previous" into
 * the same output, and blends with ACETATE_BLEND_ADD or ACETATE_BLEND_OVER.
 *
 * 1.2: the camera. Every pass (vertex and fragment stage) also sees the push-constant block
 *   AcetateView { vec4 acetate_view; vec4 acetate_scene_canvas; }
 * acetate_view = (origin x, origin y, scale, 1 / scale): render pixel p (gl_FragCoord.xy of a
 * full-size pass) shows scene position origin + p / scale; acetate_scene_canvas = the scene's
 * canvas (w, h, 1/w, 1/h). The preamble defines acetate_scene_position(vec2 render_pixel) and
 * acetate_render_position(vec2 scene_position) on them. Without a camera acetate_view is
 * (0, 0, 1, 1). A whole SPIR-V module declares the block with the same layout.
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
    /* ---- 1.1 (the host reads them only when struct_size covers them) ---- */
    /* NULL, or input_count GLSL names, one per input (NULL entries keep the default name): one
     * shader can serve passes that read different targets. */
    const char* const* input_names;
    /* NULL, or lines of "#define NAME VALUE" placed before the GLSL; compiler messages still
     * give line numbers in the plugin's own text. */
    const char* defines;
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

/* 1.1: AcetateTextureDesc with struct_size first, and a format: a one- or two-channel texture
 * (a distance field, a direction) takes a quarter or half the memory of RGBA. */
typedef struct AcetateTextureInfo {
    uint32_t struct_size; /* sizeof(AcetateTextureInfo) as the plugin was built */
    const char* name;
    uint32_t width;
    uint32_t height;
    /* width * height texels of as many floats as the format has channels (1 for R16F and
     * R32F, 2 for RG16F and RG32F, else 4), all finite; copied. */
    const float* rgba;
    /* ACETATE_FORMAT_*, as for targets; FLOOR (0): RGBA in the floor's format. Read only by
     * add_texture_format (add_texture_info takes RGBA in the floor's format, as it did before
     * this field existed). The format must be one the device can render to and sample
     * linearly, as for a target. */
    uint32_t format;
} AcetateTextureInfo;

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
    /* ---- 1.1: check struct_size before calling (acetate/effect.hpp does) ---- */
    /* declare_target with a format. Errors: as declare_target, an unknown format, or one the
     * device cannot render to and sample. */
    AcetateStatus (*declare_target_info)(AcetateGraph* graph, const AcetateTargetInfo* target);
    /* add_texture with struct_size. */
    AcetateStatus (*add_texture_info)(AcetateGraph* graph, const AcetateTextureInfo* texture);
    /* Fills *mask with the floor's mask of `kind` (see AcetateMaskImage). Errors: a kind the
     * descriptor does not list in masks, mask NULL or its struct_size too small. */
    AcetateStatus (*read_mask)(AcetateGraph* graph, const char* kind, AcetateMaskImage* mask);
    /* A coverage-expanding effect's reach: how many pixels past its floor's coverage bounds it
     * may change (1.2: scene pixels; the host scales it by the camera). The host then shades
     * "result" only within the bounds grown by the reach (without it, the whole canvas). Errors: a
     * preserving effect, more than 16384. */
    AcetateStatus (*set_reach)(AcetateGraph* graph, uint32_t pixels);
    /* Declares phase_<name> in GLSL: fract(time / period_seconds), computed each frame in
     * double precision, so an animation with that period is as smooth at 10^5 s as at 1 s.
     * Errors: bad or duplicate name, a period not finite or not > 0, more than 64 phases. */
    AcetateStatus (*declare_phase)(AcetateGraph* graph, const char* name, double period_seconds);
    /* add_texture_info reading `format` too (1, 2 or 4 floats per texel as the format has
     * channels). A host whose table ends before this entry does not read formats: check the
     * table's struct_size before calling. Errors: those of add_texture, a struct_size ending
     * before `format`, an unknown format or one the device cannot use. */
    AcetateStatus (*add_texture_format)(AcetateGraph* graph, const AcetateTextureInfo* texture);
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
