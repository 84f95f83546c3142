// acetate.specular: GGX highlights from the floor's lights and sun, added in premultiplied
// space (scaled by the pixel's alpha; alpha passed through bit for bit).
//
// Defines from build(): POINT_LIGHTS (point lights considered, the first in scene order),
// SUN_INDEX (the sun's index in acetate_lights, -1 for none), HAS_ROUGHNESS_MASK,
// HAS_NORMAL_MASK (0 or 1: a floor without a mask never samples it), EXACT_VISIBILITY (1: the
// height-correlated Smith term, 0: its linear approximation), SPARKLE (1: micro-sparkle).
//
// Geometry, in scene pixels: x right, y down, z up out of the floor. The view is straight down
// the z axis, so V = (0, 0, 1) at every pixel. A point light is at (position, height); the sun
// is the unit vector `direction` towards it.
//
// Every limit is bounded (docs/plugins/specular.md derives the numbers):
// - perceptual roughness >= 0.089 before it is squared: alpha >= 0.007921, so the GGX peak
//   1 / (pi alpha^2) is at most 5073 and its intermediates at most 1 / alpha = 126.2 and
//   1 / alpha^2 = 15938, all finite in half precision;
// - 1 - NoH^2 as |n x h|^2, which keeps its digits where NoH is near 1;
// - NoV clamped to [1e-4, 1]; a light with NoL <= 0 adds nothing;
// - a normal or light vector shorter than 1e-10 (squared 1e-20) is never normalised: a flat
//   normal, or no light, takes its place;
// - each light's colour * intensity is capped at 65504 before use, so every product stays
//   finite in 32 bits; the added term is capped at 65504, and so is the sum with the input.

const float PI = 3.14159265358979;
const float MIN_PERCEPTUAL_ROUGHNESS = 0.089;
const float MIN_N_DOT_V = 1e-4;
const float HALF_MAX = 65504.0;
const float TINY_LENGTH2 = 1e-20;
const vec3 V = vec3(0.0, 0.0, 1.0);
const vec3 FLAT = vec3(0.0, 0.0, 1.0);

// GGX (Trowbridge-Reitz) normal distribution, for alpha = perceptual roughness squared.
// 1 - NoH^2 = |n x h|^2 for unit n and h: no cancellation near the peak.
float distribution(float alpha, float noh, vec3 n, vec3 h) {
    vec3 nxh = cross(n, h);
    float s = noh * alpha;
    // The denominator is at least alpha^2 (|n x h|^2 + NoH^2 = 1 and alpha <= 1): never 0.
    float k = alpha / (dot(nxh, nxh) + s * s);
    return k * k * (1.0 / PI);
}

// Smith visibility V = G2 / (4 NoL NoV), height-correlated. With NoV >= 1e-4 and
// alpha >= 0.007921 both denominators are at least 7.9e-7.
float visibility(float alpha, float nov, float nol) {
#if EXACT_VISIBILITY
    float a2 = alpha * alpha;
    float lambda_v = nol * sqrt((nov - a2 * nov) * nov + a2);
    float lambda_l = nov * sqrt((nol - a2 * nol) * nol + a2);
    return 0.5 / (lambda_v + lambda_l);
#else
    return 0.5 / mix(2.0 * nol * nov, nol + nov, alpha);
#endif
}

// Schlick's Fresnel with a scalar F0.
float fresnel(float f0, float voh) {
    float x = clamp(1.0 - voh, 0.0, 1.0);
    float x2 = x * x;
    return f0 + (1.0 - f0) * (x2 * x2 * x);
}

// D * V * F * NoL for unit n and l: the light reflected towards the viewer per unit radiance.
float lobe(vec3 n, vec3 l, float alpha, float nov) {
    float nol = min(dot(n, l), 1.0);
    if (!(nol > 0.0)) return 0.0;
    vec3 half_vector = V + l;  // l.z >= 0 (heights and elevations are >= 0), so |V + l| >= 1
    float len2 = dot(half_vector, half_vector);
    if (len2 < TINY_LENGTH2) return 0.0;
    vec3 h = half_vector * inversesqrt(len2);
    float noh = clamp(dot(n, h), 0.0, 1.0);
    float voh = clamp(h.z, 0.0, 1.0);
    return distribution(alpha, noh, n, h) * visibility(alpha, nov, nol) *
           fresnel(param_f0, voh) * nol;
}

vec3 radiance(AcetateLight l) {
    // colour * intensity may overflow a float to +Inf; min() of +Inf is defined.
    return min(l.color * l.intensity, vec3(HALF_MAX));
}

// A counter-based hash of three integers (a PCG-style permutation of uvec3): the same bits on
// every device for the same key, unlike fract(sin(x) * big).
uvec3 permute(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

void main() {
    ivec2 at = ivec2(gl_FragCoord.xy);
    vec4 c = texelFetch(previous, at, 0);

    // Intensity: the specular mask's luminance (Rec. 709 weights) times its alpha, in [0, 1].
    vec4 ms = texelFetch(mask_specular, at, 0);
    float strength = clamp(dot(ms.rgb, vec3(0.2126, 0.7152, 0.0722)) * ms.a, 0.0, 1.0);

    // Roughness: the roughness mask's red where its alpha is 1, the parameter where it is 0.
    float perceptual = param_roughness;
#if HAS_ROUGHNESS_MASK
    vec4 mr = texelFetch(mask_roughness, at, 0);
    perceptual = mix(perceptual, clamp(mr.r, 0.0, 1.0), clamp(mr.a, 0.0, 1.0));
#endif
    perceptual = clamp(perceptual, MIN_PERCEPTUAL_ROUGHNESS, 1.0);
    float alpha = perceptual * perceptual;

    // Normal: rgb in [0, 1] -> [-1, 1]; green points up the image unless flip_y, and scene y
    // points down. Blended towards flat by the mask's alpha (0 where no tile carries one).
    vec3 n = FLAT;
#if HAS_NORMAL_MASK
    vec4 mn = texelFetch(mask_normal, at, 0);
    vec3 t = mn.rgb * 2.0 - 1.0;
    t.y = param_flip_y > 0.5 ? t.y : -t.y;
    vec3 blended = mix(FLAT, t, clamp(mn.a, 0.0, 1.0));
    float n2 = dot(blended, blended);
    if (n2 >= TINY_LENGTH2) n = blended * inversesqrt(n2);
#endif
    float nov = clamp(n.z, MIN_N_DOT_V, 1.0);

    vec3 p = vec3(acetate_scene_position(gl_FragCoord.xy), 0.0);  // scene pixels, as the lights
    vec3 sum = vec3(0.0);
    for (int i = 0; i < POINT_LIGHTS; ++i) {
        AcetateLight l = acetate_lights[i];
        vec3 d = vec3(l.position, l.height) - p;
        float d2 = dot(d, d);
        if (d2 < TINY_LENGTH2) continue;  // the light at this pixel, on the floor: no direction
        float dist = sqrt(d2);
        // Falloff over the light's radius, by 3D distance: (1 - (d/r)^2)^2, 0 from d = r on.
        float q = dist / l.radius;
        float f = clamp(1.0 - q * q, 0.0, 1.0);
        if (f <= 0.0) continue;
        sum += radiance(l) * (f * f * lobe(n, d / dist, alpha, nov));
    }
#if SUN_INDEX >= 0
    AcetateLight sun = acetate_lights[SUN_INDEX];
    sum += radiance(sun) * lobe(n, sun.direction, alpha, nov);
#endif
    // Each lobe is at most D 5073 * (V NoL <= 0.5 / alpha = 63.1) * F 1 = 3.2e5, so the sum of
    // 65 lights at radiance 65504 stays below 1.4e12, and all that follows below 1e14.
    vec3 spec = sum * (strength * param_intensity);

#if SPARKLE
    // Micro-sparkle: per scene pixel and time step, a factor 1 + s (9 u^8 - 1) with u uniform
    // in [0, 1): its mean is 1, so sparkle redistributes the highlight without brightening it.
    // The step comes from the whole seconds and their fraction, exact at 1e5 s.
    int rate = int(param_sparkle_rate);
    int tick = int(acetate_time_whole) * rate + min(int(acetate_time_fraction * float(rate)),
                                                    rate - 1);
    // Hashed by scene pixel, so a camera's region sparkles as the whole canvas does there.
    ivec2 scene_pixel = ivec2(floor(acetate_scene_position(gl_FragCoord.xy)));
    uint bits = permute(uvec3(uvec2(scene_pixel), uint(tick))).x;
    float u = float(bits >> 8u) * (1.0 / 16777216.0);
    float u2 = u * u;
    float u4 = u2 * u2;
    spec *= 1.0 + param_sparkle * (9.0 * u4 * u4 - 1.0);
#endif

    // Capped, scaled by alpha (0 at a == 0), and never pushing the input past 65504.
    spec = min(spec, vec3(HALF_MAX));
    vec3 added = min(clamp(c.a, 0.0, 1.0) * spec, max(vec3(HALF_MAX) - c.rgb, vec3(0.0)));
    out_color = vec4(c.rgb + added, c.a);
}
