#pragma once
// The CPU model acetate.specular is tested against (specular_test.cpp), in double precision,
// written from the textbook formulas and the documented limits (docs/plugins/specular.md), not
// from the shader; and the tolerances that compare it with the GPU, each with its reason.

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "scene/image_io.hpp"
#include "scene/scene.hpp"

namespace acetate::test::specular {

using Vec3 = std::array<double, 3>;
constexpr double kHalfMax = 65504.0;
constexpr double kPi = 3.14159265358979323846;

// ---- Tolerances ----------------------------------------------------------------------------
// Storing a float into an RGBA16F target rounds to nearest or toward zero (Vulkan allows
// either): under one ulp, at most 2^-10 of the value.
constexpr double kHalfConversion = 1.0 / 1024;
// Below 2^-14 the half ulp is 2^-24 absolute.
constexpr double kHalfSubnormalUlp = 1.0 / 16777216;
// The shader's 32-bit arithmetic on the added term: each operation is within a few ulps
// (2^-24) except where the GGX peak amplifies the absolute error of |n x h|^2: at most
// 2.4e-7 / alpha relative, 3.0e-5 at the smallest alpha (0.007921). Under 2^-14 = 6.1e-5.
constexpr double kShaderArithmetic = 1.0 / 16384;

inline float half_of(double v) {
    return float(Imath::half(float(v)));
}
inline double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 normalized(const Vec3& v) {
    const double len = std::sqrt(dot(v, v));
    return {v[0] / len, v[1] / len, v[2] / len};
}

struct Params {
    double intensity = 1, f0 = 0.04, roughness = 0.4;
    bool flip_y = false;
    bool exact = true;       // exact_visibility (presets high, ultra, and the default)
    size_t max_points = 32;  // max_lights (the default; presets 4, 16, 32, 64)
    nlohmann::json json() const {
        return {{"intensity", intensity}, {"f0", f0}, {"roughness", roughness}, {"flip_y", flip_y}};
    }
};

// One floor as the effect sees it: canvas-sized colour and mask composites (half floats).
struct Inputs {
    ImageRGBA colour, specular, roughness, normal;
    bool has_roughness = false, has_normal = false;
    Inputs(uint32_t w, uint32_t h) : colour(w, h), specular(w, h), roughness(w, h), normal(w, h) {}
};

// The model: the specular term (before alpha) at pixel (x, y), in double.
inline Vec3 specular_term(const Inputs& in, uint32_t x, uint32_t y, const FloorDesc& floor,
                          const Params& p) {
    const float* ms = in.specular.at(x, y);
    const double strength =
        std::clamp((0.2126 * ms[0] + 0.7152 * ms[1] + 0.0722 * ms[2]) * ms[3], 0.0, 1.0);
    double rough = p.roughness;
    if (in.has_roughness) {
        const float* m = in.roughness.at(x, y);
        const double w = std::clamp(double(m[3]), 0.0, 1.0);
        rough = rough * (1 - w) + std::clamp(double(m[0]), 0.0, 1.0) * w;
    }
    rough = std::clamp(rough, 0.089, 1.0);  // the documented floor on perceptual roughness
    const double a = rough * rough, a2 = a * a;
    Vec3 n{0, 0, 1};
    if (in.has_normal) {
        const float* m = in.normal.at(x, y);
        const double w = std::clamp(double(m[3]), 0.0, 1.0);
        // Green points up the image (towards -y) unless flip_y.
        const Vec3 t{2.0 * m[0] - 1, (p.flip_y ? 1 : -1) * (2.0 * m[1] - 1), 2.0 * m[2] - 1};
        const Vec3 b{t[0] * w, t[1] * w, (1 - w) + t[2] * w};
        if (dot(b, b) >= 1e-20) n = normalized(b);
    }
    const double nov = std::clamp(n[2], 1e-4, 1.0);
    // Reflected radiance per unit incoming radiance, towards V = (0, 0, 1), times NoL.
    auto reflect = [&](const Vec3& l) {
        const double nol = std::min(dot(n, l), 1.0);
        if (nol <= 0) return 0.0;
        const Vec3 h = normalized({l[0], l[1], l[2] + 1});
        const double noh = std::clamp(dot(n, h), 0.0, 1.0), voh = std::clamp(h[2], 0.0, 1.0);
        const double q = noh * noh * (a2 - 1) + 1;
        const double d = a2 / (kPi * q * q);
        double vis;
        if (p.exact) {
            auto lambda = [&](double c) {
                return (std::sqrt(1 + a2 * (1 - c * c) / (c * c)) - 1) / 2;
            };
            vis = 1 / (1 + lambda(nov) + lambda(nol)) / (4 * nol * nov);
        } else {
            vis = 0.5 / ((1 - a) * 2 * nol * nov + a * (nol + nov));  // Hammon's approximation
        }
        const double f = p.f0 + (1 - p.f0) * std::pow(1 - voh, 5);
        return d * vis * f * nol;
    };
    Vec3 sum{0, 0, 0};
    auto add = [&](const std::array<float, 3>& colour, float intensity, double weight) {
        for (int c = 0; c < 3; ++c)
            sum[c] += std::min(double(colour[c]) * intensity, kHalfMax) * weight;
    };
    for (size_t i = 0; i < floor.lights.size() && i < p.max_points; ++i) {
        const LightDesc& l = floor.lights[i];
        const Vec3 d{l.pos[0] - (x + 0.5), l.pos[1] - (y + 0.5), double(l.height)};
        const double dist = std::sqrt(dot(d, d));
        if (dist * dist < 1e-20) continue;
        const double f = std::max(0.0, 1 - (dist / l.radius) * (dist / l.radius));
        if (f > 0)
            add(l.color, l.intensity, f * f * reflect({d[0] / dist, d[1] / dist, d[2] / dist}));
    }
    if (floor.sun) {
        const auto s = floor.sun->direction();
        add(floor.sun->color, floor.sun->intensity, reflect({s[0], s[1], s[2]}));
    }
    for (double& v : sum) v = std::min(v * strength * p.intensity, kHalfMax);
    return sum;
}

struct Expected {
    Vec3 rgb, added;
};
inline Expected expected_at(const Inputs& in, uint32_t x, uint32_t y, const FloorDesc& floor,
                            const Params& p) {
    const float* c = in.colour.at(x, y);
    const Vec3 s = specular_term(in, x, y, floor, p);
    Expected e;
    for (int k = 0; k < 3; ++k) {
        e.added[k] =
            std::min(std::clamp(double(c[3]), 0.0, 1.0) * s[k], std::max(kHalfMax - c[k], 0.0));
        e.rgb[k] = c[k] + e.added[k];
    }
    return e;
}

inline double tolerance(double value, double added) {
    return kHalfConversion * std::fabs(value) + kShaderArithmetic * added + kHalfSubnormalUlp;
}

// An image of one value per pixel from f(x, y) -> rgba, rounded to half floats.
template <class F>
inline ImageRGBA image(uint32_t w, uint32_t h, F f) {
    ImageRGBA out(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const std::array<double, 4> v = f(x, y);
            for (int c = 0; c < 4; ++c) out.at(x, y)[c] = half_of(v[c]);
        }
    return out;
}
// A normal mask holding the unit normal n (scene axes: x right, y down, z up), green up.
inline ImageRGBA normal_mask(uint32_t w, uint32_t h, Vec3 n) {
    n = normalized(n);
    return image(w, h, [&](uint32_t, uint32_t) {
        return std::array<double, 4>{0.5 + 0.5 * n[0], 0.5 - 0.5 * n[1], 0.5 + 0.5 * n[2], 1};
    });
}
inline ImageRGBA grey(uint32_t w, uint32_t h, double value, double alpha = 1) {
    return image(w, h, [&](uint32_t, uint32_t) {
        return std::array<double, 4>{value * alpha, value * alpha, value * alpha, alpha};
    });
}
inline ImageRGBA mask(uint32_t w, uint32_t h, double value) {
    return image(w, h, [&](uint32_t, uint32_t) {
        return std::array<double, 4>{value, value, value, 1};
    });
}

}  // namespace acetate::test::specular
