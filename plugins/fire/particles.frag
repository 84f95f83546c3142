// acetate.fire, pass "particles": one particle per instanced quad, premultiplied OVER onto
// result. Each quad is the box its particle can reach over any life (fire.cpp, reach_box), so
// this shader only decides what the particle looks like at this pixel now.
//
// A particle is a pure function of (seed, emitter, slot, time), with no state between frames:
//   offset  = unit(pcg4d(seed, emitter, kind * 256 + slot, 0))        when in its life it starts
//   u       = clock * rate + offset     (rate = 1 / lifetime; `precise`: no fused multiply-add)
//   cycle   = floor(u), age = u - cycle (0 at birth, 1 at death)
//   r       = unit(pcg4d(seed, emitter, kind * 256 + slot, cycle % cycles + 1))  this life's draws
// clock = phase_clock * CLOCK_PERIOD, a phase the host reduces in double; every lifetime
// divides CLOCK_PERIOD (cycles = CLOCK_PERIOD / lifetime lives per period), so at the clock's
// wrap u drops by exactly `cycles` and, counted modulo it, nothing jumps. Integer hashing and the
// exact conversion unit(h) = (h >> 8) / 2^24 make offset, cycle, age and r bit-identical on the
// CPU (tests/fire_model.hpp); never fract(sin(x) * big), whose precision Vulkan leaves open.
//
// Kinds (floor_data[PARAMS_OFFSET + 8 i ..]: emitter x, y, strength, wind factor, kind, slot,
// emitter index): 0 smoke, 1 flame, 2 ember. Each term below has the bound fire.cpp uses for
// the quad. Flames and embers emit light: their rgb may exceed alpha (HDR, allowed), but both
// carry the same factors and a pixel whose alpha is under 1/4096 is dropped whole, so rgb is 0
// wherever alpha is 0 (even after rounding to half), and OVER keeps alpha in [0, 1] and never
// below what the floor had.

uvec4 pcg4d(uvec4 v) {  // Jarzynski and Olano's 4D PCG hash: integer only, the same everywhere
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

vec4 unit4(uvec4 h) {  // [0, 1), exact: 24 bits fit a float's mantissa
    return vec4(h >> 8u) * (1.0 / 16777216.0);
}

// Blackbody colour at `kelvin`: Planck's law at 610, 550 and 465 nm, scaled so red is 1, times
// (kelvin / 1900)^4 for brightness (Stefan-Boltzmann), so a cooling particle dims and reddens.
vec3 blackbody(float kelvin) {
    vec3 lambda = vec3(0.610, 0.550, 0.465);  // micrometres
    vec3 lambda5 = lambda * lambda * lambda * lambda * lambda;
    vec3 planck = 1.0 / (lambda5 * (exp(14388.0 / (lambda * kelvin)) - 1.0));
    float t = kelvin / 1900.0;
    return planck / planck.r * (t * t * t * t);
}

// A disc of radius 1 with a soft edge from `inner` outwards: exactly 0 from 1 on.
float disc(float d, float inner) {
    return 1.0 - smoothstep(inner, 1.0, d);
}

void main() {
    int base = PARAMS_OFFSET + 8 * acetate_instance;
    vec2 emitter = vec2(floor_data[base], floor_data[base + 1]);
    float strength = floor_data[base + 2];
    float wind_factor = floor_data[base + 3];
    int kind = int(floor_data[base + 4]);
    uint id = uint(kind) * 256u + uint(floor_data[base + 5]);
    uint index = uint(floor_data[base + 6]);
    uint seed = uint(param_seed);

    float rate = kind == 0 ? SMOKE_RATE : kind == 1 ? FLAME_RATE : EMBER_RATE;
    float life = kind == 0 ? SMOKE_LIFE : kind == 1 ? FLAME_LIFE : EMBER_LIFE;
    float offset = unit4(pcg4d(uvec4(seed, index, id, 0u))).x;
    precise float clock = phase_clock * CLOCK_PERIOD;
    precise float u = clock * rate + offset;
    float cycle = floor(u);
    float age = u - cycle;
    // The cycle counts modulo the lives per clock period, so at the clock's wrap (u drops by
    // exactly that many) a particle keeps its draws mid-life.
    uint cycles = uint(kind == 0 ? SMOKE_CYCLES : kind == 1 ? FLAME_CYCLES : EMBER_CYCLES);
    vec4 r = unit4(pcg4d(uvec4(seed, index, id, uint(cycle) % cycles + 1u)));

    vec2 pos = acetate_scene_position(gl_FragCoord.xy);  // scene pixels, as the emitters
    vec2 jitter = vec2(r.x - 0.5, (r.y - 0.5) * 0.5) * SPREAD;  // |x| <= SPREAD/2, |y| <= SPREAD/4
    vec2 drift = param_wind * (wind_factor * age * life);       // between 0 and wind * life
    vec4 src = vec4(0.0);
    if (kind == 1) {  // flame: rises, sways, shrinks and cools
        float rise = param_flame_height * strength * (0.6 + 0.4 * r.z) * age;
        float sway = sin(6.2831853 * (1.5 * age + r.w)) * 0.3 * param_flame_size * age;
        vec2 at = emitter + jitter + vec2(sway, -rise) + drift;
        float radius = param_flame_size * sqrt(strength) * (1.0 - 0.6 * age);
        float envelope = smoothstep(0.0, 0.12, age) * (1.0 - smoothstep(0.55, 1.0, age));
        float shape = envelope * disc(length(pos - at) / radius, 0.4);
        vec3 light = blackbody(param_temperature * (1.0 - 0.45 * age)) * param_intensity;
        src = vec4(light * shape, 0.4 * shape);  // a flame hides little of what is behind
    } else if (kind == 2) {  // ember: thrown up, pulled down by gravity, cooling
        float speed = param_ember_speed;
        vec2 velocity = vec2((r.x - 0.5) * speed, -(0.5 + 0.5 * r.y) * speed);
        float t = age * life;
        vec2 at = emitter + velocity * t + vec2(0.0, 0.5 * GRAVITY * t * t) + drift;
        float envelope = smoothstep(0.0, 0.05, age) * (1.0 - smoothstep(0.6, 1.0, age));
        float shape = envelope * disc(length(pos - at) / 1.2, 0.3);
        vec3 light = blackbody(param_temperature * (1.05 - 0.55 * age)) * (2.0 * param_embers);
        src = vec4(light * shape, shape);
    } else {  // smoke: leaves the flames' top, rises slowly, grows, drifts further, fades
        vec2 start = emitter + jitter - vec2(0.0, 0.8 * param_flame_height * strength);
        float rise = param_smoke_height * (0.7 + 0.3 * r.z) * age;
        vec2 at = start - vec2(0.0, rise) + 1.5 * drift;
        float radius = param_smoke_size * (1.0 + 2.0 * age);
        float envelope = age < 0.2 ? age / 0.2 : (1.0 - age) / 0.8;  // 0, 1 at 0.2, 0
        float a = param_smoke * envelope * disc(length(pos - at) / radius, 0.2);
        src = vec4(vec3(0.22, 0.21, 0.20) * a, a);
    }
    // A light-emitting pixel's colour can be some 2000 times its alpha (a flame at 3500 K and
    // intensity 64): at a disc's very edge the
    // alpha would round to 0 in a half-float target while the colour did not. Such faint edges
    // (alpha under 1/4096, far below what a display shows) are left out, so a pixel that holds
    // colour always holds a normal half-float alpha too.
    out_color = src.a < 1.0 / 4096.0 ? vec4(0.0) : src;
}
