#pragma once
// The glow shader expanding_glow.cpp declares honestly (coverage-expanding) and
// undeclared_expansion.cpp does not: out = max(prev, strength * average of the 4 neighbours at
// +-2 pixels), componentwise. Alpha never drops; rgb stays 0 wherever a is 0.

inline constexpr const char* kGlowShader = R"(
// "previous" is canvas-sized; clamp so no fetch falls outside it.
vec4 tap(ivec2 p) {
    ivec2 last = ivec2(acetate_canvas.xy) - 1;
    return texelFetch(previous, clamp(p, ivec2(0), last), 0);
}
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(previous, p, 0);
    vec4 around = 0.25 * (tap(p + ivec2(2, 0)) + tap(p - ivec2(2, 0)) +
                          tap(p + ivec2(0, 2)) + tap(p - ivec2(0, 2)));
    out_color = max(prev, param_strength * around);
}
)";
