#pragma once
// A CPU replica of acetate.fire's particles, written from docs/plugins/fire.md: the same integer
// hash and the same float steps up to each particle's age and random draws (so those are
// bit-identical to the shader's), then each particle's centre and radius in double. The fire
// tests predict from it where every particle is at a given time.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace acetate::test::fire_model {

inline std::array<uint32_t, 4> pcg4d(std::array<uint32_t, 4> v) {
    for (uint32_t& x : v) x = x * 1664525u + 1013904223u;
    auto mix = [&] {
        v[0] += v[1] * v[3];
        v[1] += v[2] * v[0];
        v[2] += v[0] * v[1];
        v[3] += v[1] * v[2];
    };
    mix();
    for (uint32_t& x : v) x ^= x >> 16u;
    mix();
    return v;
}

inline float unit(uint32_t h) {
    return float(h >> 8u) * (1.0f / 16777216.0f);
}

// The host's phase for a period: fract(time / period) in double, stored as a float below 1.
inline float phase(double time, double period) {
    const double turns = time / period;
    return std::min(float(turns - std::floor(turns)), 0x1.fffffep-1f);
}

struct Params {
    float flame_height = 26, flame_size = 5, ember_speed = 45, smoke_height = 90, smoke_size = 7;
    std::array<float, 2> wind{8, 0};
    uint32_t seed = 1;
    float spread = 6;  // the emitter spacing
};

struct Emitter {
    double x, y, strength, wind_factor;
    uint32_t index;
};

struct Particle {
    int kind;  // 0 smoke, 1 flame, 2 ember
    double x, y, radius;
    double envelope;  // 0..1: how present the particle is in its life now
};

inline constexpr double kClockPeriod = 2048;
inline constexpr float kRate[3] = {0.3125f, 1.25f, 0.625f};  // 1 / (3.2, 0.8, 1.6) s
inline constexpr double kLife[3] = {3.2, 0.8, 1.6};
inline constexpr double kGravity = 60;

inline double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

inline Particle particle_at(double time, const Emitter& e, int kind, uint32_t slot,
                            const Params& p) {
    const uint32_t id = uint32_t(kind) * 256u + slot;
    const float offset = unit(pcg4d({p.seed, e.index, id, 0u})[0]);
    const float clock = phase(time, kClockPeriod) * float(kClockPeriod);  // exact: a power of 2
    const float scaled = clock * kRate[kind];  // the shader's `precise`: rounded, then added
    const float u = scaled + offset;
    const float cycle = std::floor(u);
    const double age = u - cycle;
    const uint32_t cycles = uint32_t(std::lround(kClockPeriod * kRate[kind]));  // lives per period
    const auto h = pcg4d({p.seed, e.index, id, uint32_t(cycle) % cycles + 1u});
    const double r[4] = {unit(h[0]), unit(h[1]), unit(h[2]), unit(h[3])};
    const double life = kLife[kind];
    const double jx = (r[0] - 0.5) * p.spread, jy = (r[1] - 0.5) * 0.5 * p.spread;
    const double dx = p.wind[0] * e.wind_factor * age * life;
    const double dy = p.wind[1] * e.wind_factor * age * life;
    Particle out{kind, 0, 0, 0, 0};
    if (kind == 1) {
        const double rise = p.flame_height * e.strength * (0.6 + 0.4 * r[2]) * age;
        const double sway = std::sin(6.2831853 * (1.5 * age + r[3])) * 0.3 * p.flame_size * age;
        out.x = e.x + jx + sway + dx;
        out.y = e.y + jy - rise + dy;
        out.radius = p.flame_size * std::sqrt(e.strength) * (1 - 0.6 * age);
        out.envelope = smoothstep(0, 0.12, age) * (1 - smoothstep(0.55, 1, age));
    } else if (kind == 2) {
        const double vx = (r[0] - 0.5) * p.ember_speed, vy = -(0.5 + 0.5 * r[1]) * p.ember_speed;
        const double t = age * life;
        out.x = e.x + vx * t + dx;
        out.y = e.y + vy * t + 0.5 * kGravity * t * t + dy;
        out.radius = 1.2;
        out.envelope = smoothstep(0, 0.05, age) * (1 - smoothstep(0.6, 1, age));
    } else {
        const double rise = p.smoke_height * (0.7 + 0.3 * r[2]) * age;
        out.x = e.x + jx + 1.5 * dx;
        out.y = e.y + jy - 0.8 * p.flame_height * e.strength - rise + 1.5 * dy;
        out.radius = p.smoke_size * (1 + 2 * age);
        out.envelope = age < 0.2 ? age / 0.2 : (1 - age) / 0.8;
    }
    return out;
}

// Every particle of one emitter, in the plugin's counts per kind (smoke, flame, ember).
inline std::vector<Particle> particles_at(double time, const Emitter& e,
                                          const std::array<int, 3>& counts, const Params& p) {
    std::vector<Particle> out;
    for (int kind = 0; kind < 3; ++kind)
        for (int slot = 0; slot < counts[kind]; ++slot)
            out.push_back(particle_at(time, e, kind, uint32_t(slot), p));
    return out;
}

}  // namespace acetate::test::fire_model
