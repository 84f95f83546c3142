#pragma once
// The glow shader expanding_glow.cpp declares honestly (coverage-expanding) and
// undeclared_expansion.cpp does not: out = max(prev, strength * average of the 4 neighbours at
// +-2 scene pixels), componentwise. Alpha never drops; rgb stays 0 wherever a is 0. The taps are
// 2 * acetate_view_scale texels away (filtered), so the glow is as wide through any camera.

inline constexpr const char* kGlowShader = R"(
// Bilinear by hand from texelFetch, clamped to the edge texels: a tap at a texel's centre reads
// that texel exactly, whatever the output's size (a sampler's normalised coordinate would not).
vec4 tap(vec2 scene_offset) {
    vec2 at = gl_FragCoord.xy + scene_offset * acetate_view_scale - 0.5;
    ivec2 last = ivec2(acetate_canvas.xy) - 1, p = ivec2(floor(at));
    vec2 f = at - floor(at);
    vec4 t00 = texelFetch(previous, clamp(p, ivec2(0), last), 0);
    vec4 t10 = texelFetch(previous, clamp(p + ivec2(1, 0), ivec2(0), last), 0);
    vec4 t01 = texelFetch(previous, clamp(p + ivec2(0, 1), ivec2(0), last), 0);
    vec4 t11 = texelFetch(previous, clamp(p + ivec2(1, 1), ivec2(0), last), 0);
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
}
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec4 around = 0.25 * (tap(vec2(2, 0)) + tap(vec2(-2, 0)) + tap(vec2(0, 2)) + tap(vec2(0, -2)));
    out_color = max(prev, param_strength * around);
}
)";
