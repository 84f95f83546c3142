#version 450
// Draws a premultiplied tile texel. Texels with alpha 0 are discarded so that the stencil
// (written by the pipeline where fragments survive) marks exactly the tile's coverage.
layout(push_constant) uniform Push {
    vec4 rect;
    vec4 tint;
    vec2 canvas;
    uint floor_index;
    uint tint_mode;
} pc;
layout(set = 0, binding = 0) uniform sampler2D tile;
layout(set = 0, binding = 2) buffer Violations { uint count[]; } violations;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;

bool violates_premultiplied(vec4 c) {
    return (c.a <= 0.0 && any(notEqual(c.rgb, vec3(0.0)))) || any(isnan(c)) || any(isinf(c));
}

void main() {
    vec4 c = texture(tile, uv);
    if (violates_premultiplied(c)) atomicAdd(violations.count[pc.floor_index], 1u);
    if (c.a <= 0.0) discard;
    if (pc.tint_mode == 1u) {
        // Isolation view: keep the tile's shape and shading, replace its hue with the floor's.
        float luma = dot(c.rgb / c.a, vec3(0.2126, 0.7152, 0.0722));
        c.rgb = pc.tint.rgb * c.a * (0.35 + 0.65 * clamp(luma, 0.0, 1.0));
    }
    color = c;
}
