#pragma once
// Small helpers shared by the example art generators (make_example_art.cpp, specular_art.cpp).

#include <algorithm>
#include <cmath>

inline float clamp01(float v) {
    return std::clamp(v, 0.f, 1.f);
}
// GLSL's smoothstep(e0, e1, v).
inline float smooth(float e0, float e1, float v) {
    float t = clamp01((v - e0) / (e1 - e0));
    return t * t * (3 - 2 * t);
}
inline float fract(float v) {
    return v - std::floor(v);
}
