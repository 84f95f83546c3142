#version 450
// Draws a premultiplied tile texel, in one variant per stage: host_pipelines.cpp inserts the
// defines below after the #version line. No variant branches on a push constant: lavapipe runs
// both sides of such a branch for every pixel, texture reads included (docs/performance.md).
//   KEEP_COVERAGE  (tile -> floor target) texels with alpha <= 0 are discarded, so the stencil
//                  the pipeline writes where fragments survive marks exactly the tile's coverage.
//                  Without it (tile -> accumulation) they are drawn as (0,0,0,0) instead, which
//                  the over blend leaves the destination unchanged with: the same pixels as a
//                  discard, for less.
//   ISOLATION      the isolation view's tint.
// Either way no colour without coverage enters a floor (tile texels breaking that are counted
// at load).
layout(push_constant) uniform Push {  // TilePushConstants (render/host_pipelines.hpp)
    vec4 tile_rect;       // x, y, width, height in scene pixels
    vec4 isolation_tint;  // the floor's tint (rgb)
    vec4 view;            // the camera: origin x, y (scene pixels), scale, 1/scale
    vec2 canvas_size;
} pc;
layout(set = 0, binding = 0) uniform sampler2D tile;
layout(location = 0) out vec4 color;

void main() {
    // The texture coordinate from the scene position this pixel shows, not interpolated from
    // the quad's corners: a camera at a whole-pixel origin then reads every tile with the same
    // numbers as the whole frame, bit for bit (the corners' NDC would differ in rounding).
    vec2 uv = (pc.view.xy + gl_FragCoord.xy * pc.view.w - pc.tile_rect.xy) / pc.tile_rect.zw;
    // The sampler makes this exact for a tile drawn at its own size on whole pixels: it is
    // nearest then, and a pixel centre maps to a texel centre (HostPipelines::tile_sampler).
    vec4 c = texture(tile, uv);
#ifdef KEEP_COVERAGE
    if (c.a <= 0.0) discard;
#endif
#ifdef ISOLATION
    // Isolation view: keep the tile's shape and shading, replace its hue with the floor's.
    float luma = dot(c.rgb / c.a, vec3(0.2126, 0.7152, 0.0722));
    c.rgb = pc.isolation_tint.rgb * c.a * (0.35 + 0.65 * clamp(luma, 0.0, 1.0));
#endif
#ifdef KEEP_COVERAGE
    color = c;
#else
    color = c.a <= 0.0 ? vec4(0.0) : c;
#endif
}
