#version 450
// Draws a premultiplied tile texel. Texels with alpha 0 are discarded so that the stencil
// (written by the pipeline where fragments survive) marks exactly the tile's coverage, and no
// colour without coverage ever enters a floor (tile texels breaking that are counted at load).
layout(push_constant) uniform Push {
    vec4 rect;
    vec4 tint;
    vec2 canvas;
    uint floor_index;
    uint mode;          // bit 0: isolation tint; bit 1: the tile maps 1:1 onto whole pixels
} pc;
layout(set = 0, binding = 0) uniform sampler2D tile;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;

void main() {
    // A tile drawn at its own size on whole pixels needs no filtering: fetching the texel is
    // exact, where the interpolated uv would let the filter blend in neighbours by rounding.
    vec4 c = (pc.mode & 2u) != 0u ? texelFetch(tile, ivec2(gl_FragCoord.xy - pc.rect.xy), 0)
                                  : texture(tile, uv);
    if (c.a <= 0.0) discard;
    if ((pc.mode & 1u) != 0u) {
        // Isolation view: keep the tile's shape and shading, replace its hue with the floor's.
        float luma = dot(c.rgb / c.a, vec3(0.2126, 0.7152, 0.0722));
        c.rgb = pc.tint.rgb * c.a * (0.35 + 0.65 * clamp(luma, 0.0, 1.0));
    }
    color = c;
}
