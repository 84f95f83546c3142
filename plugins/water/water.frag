// acetate.water: one pass over the floor. Outside the water it copies; on the water, in order:
//   1. the bed, refracted: taps offset along the wave slope, the offset shrinking to zero at
//      the shore, each texel read only if it is water and not transparent
//   2. caustics multiply the bed, before anything darkens it, so they read as light whatever
//      ran before; the pattern's mean is 1 and its factor is bounded (no division anywhere)
//   3. the water column: the bed times a transmittance blended by depth, then murk, lit by
//      the floor's lights and sun
//   4. foam in a band along the shore, lit by the floor's lights and sun
//   5. glints: a GGX highlight of each light and the sun on the wave normal
// Every colour term is the premultiplied bed or is multiplied by the pixel's alpha, so rgb
// stays 0 where alpha is 0; alpha passes through untouched; and what the water adds never
// pushes a channel past 65504, the largest half float.
//
// Defines from build(): TAPS, CAUSTIC_OCTAVES, MAX_LIGHTS, HAS_OUTDOORS, ANIMATE (1.0 or 0.0),
// FIELD_DIVISOR and FIELD_ORIGIN (the shore texture's cell size and first cell), WATER_BOX (the
// scene-pixel box of every pixel with water), LAYER0_SCALE .. LAYER2_SCALE, FOAM_SCALE.

const float kHalfMax = 65504.0;
const float kPi = 3.14159265358979;
const float kWaveTexels = 256.0;
const float kWaterF0 = 0.02;  // Fresnel reflectance of water at normal incidence
// The GGX peak is 1 / (pi a^4) at a = perceptual roughness; clamping a at 0.089 keeps it
// near 5000, finite in half precision (the clamp Filament uses for mediump).
const float kMinPerceptualRoughness = 0.089;
const float kGlintCap = 16.0;  // the most one pixel's highlights add, before alpha and strength
const float kMaxSlope = 0.35;  // the surface's steepest tilt at waves = 1 (about 19 degrees)
// Wave layers 1 and 2 run across layer 0 at 1.1 and -0.7 radians (columns of the rotations).
const mat2 kTurn1 = mat2(0.4535961, 0.8912074, -0.8912074, 0.4535961);
const mat2 kTurn2 = mat2(0.7648422, -0.6442177, 0.6442177, 0.7648422);

float water_cover(ivec2 p) {
    vec4 m = texelFetch(mask_water, p, 0);
    return clamp(m.r, 0.0, 1.0) * clamp(m.a, 0.0, 1.0);
}

// Scene pixels from pos to the shore (0 on land), filtered between cells.
float shore_distance(vec2 pos) {
    vec2 cell = pos / FIELD_DIVISOR - FIELD_ORIGIN;
    // Explicit level 0: this runs after early returns, where implicit derivatives are undefined.
    return max(textureLod(texture_shore, cell * acetate_size_texture_shore.zw, 0.0).r, 0.0);
}

// One wave layer: slope (xy, in the layer's frame), height (z), caustic density (w). The layer
// moves `direction` (whole tiles) per period of its phase, so it wraps without a jump.
vec4 wave_layer(vec2 layer_pos, float scale, vec2 direction, float phase) {
    vec2 tile = fract(layer_pos / scale + direction * (phase * ANIMATE));
    return textureLod(texture_waves, (tile * kWaveTexels + 0.5) / (kWaveTexels + 1.0), 0.0);
}

struct Surface {
    vec2 slope;     // scene frame, length at most 1
    float caustic;  // mean 1, in [0, 4]
};

Surface surface_at(vec2 pos) {
    vec4 a = wave_layer(pos, LAYER0_SCALE, vec2(1.0, 0.0), phase_wave0);
    vec4 b = wave_layer(kTurn1 * pos, LAYER1_SCALE, vec2(0.0, 1.0), phase_wave1);
    Surface s;
    // A layer's slope turns back into the scene frame with the transpose of its rotation.
    s.slope = 0.6 * a.xy + 0.4 * (transpose(kTurn1) * b.xy);
#if CAUSTIC_OCTAVES == 1
    s.caustic = a.w;
#elif CAUSTIC_OCTAVES == 2
    // A weighted geometric mean: the first layer's network, broken up by the second's. Each
    // factor is in [0, 4], so the product is too.
    s.caustic = pow(max(a.w, 0.0), 0.65) * pow(max(b.w, 0.0), 0.35);
#else
    vec4 c = wave_layer(kTurn2 * pos, LAYER2_SCALE, vec2(1.0, 1.0), phase_wave2);
    s.caustic = pow(max(a.w, 0.0), 0.5) * pow(max(b.w, 0.0), 0.3) * pow(max(c.w, 0.0), 0.2);
#endif
    return s;
}

// The bed seen through the surface: TAPS taps on a disk around pos + offset, each a bilinear
// read whose four texels count only if they are on the canvas, water, and at least half as
// opaque as this pixel. Weights are renormalised over what counted.
// pos and the offsets are scene pixels; each tap is placed in the scene and only then turned
// into render pixels, so under a camera a tap lands where it lands in the whole frame (at a
// whole-pixel origin, on the same texels with the same weights).
vec3 refracted_bed(vec2 pos, vec4 c, vec2 offset, float dist) {
    float len = length(offset);
    if (len <= 0.0) return c.rgb;  // still water: the bed as it is
    // Every tap stays 1.5 px inside the water's edge: the offset shrinks to fit, to 0 at the
    // shore. reach > room >= 0 below, so the division is by a positive number.
    float spread = TAPS == 1 ? 0.0 : 0.5 * len;
    float reach = len + spread;
    float room = max(dist - 1.5, 0.0);
    float fit = reach > room ? room / reach : 1.0;
    offset *= fit;
    spread *= fit;
    vec3 rgb = vec3(0.0);
    float alpha = 0.0;
    ivec2 canvas = ivec2(acetate_canvas.xy);
    for (int i = 0; i < TAPS; ++i) {
        float r = spread * sqrt((float(i) + 0.5) / float(TAPS));  // a Vogel disk
        float theta = float(i) * 2.3999632;
        vec2 f = acetate_render_position(pos + offset + r * vec2(cos(theta), sin(theta))) - 0.5;
        ivec2 base = ivec2(floor(f));
        vec2 t = f - vec2(base);
        for (int k = 0; k < 4; ++k) {
            ivec2 corner = ivec2(k & 1, k >> 1);
            vec2 wxy = mix(1.0 - t, t, vec2(corner));
            float w = wxy.x * wxy.y;
            ivec2 q = base + corner;
            // A weight under 1/4096 is left out: nothing a half float shows, and the sum of
            // what counts then stays far from the subnormals (alpha >= c.a / 8192 below).
            if (w < 1.0 / 4096.0 || any(lessThan(q, ivec2(0))) ||
                any(greaterThanEqual(q, canvas)))
                continue;
            if (water_cover(q) <= 0.5) continue;
            vec4 s = texelFetch(previous, q, 0);
            if (s.a < 0.5 * c.a) continue;
            rgb += w * s.rgb;
            alpha += w * s.a;
        }
    }
    // Brought to this pixel's alpha. alpha >= c.a / 8192 > 0 whenever a texel counted (weight
    // >= 1/4096, a >= c.a / 2), so c.a / alpha <= 8192; with none, the pixel keeps its bed.
    return alpha > 0.0 ? rgb * (c.a / alpha) : c.rgb;
}

// The floor's lights and sun on a surface of normal n seen from straight above: Lambert
// irradiance (for the foam) and the GGX highlight (Trowbridge-Reitz distribution,
// height-correlated Smith visibility, Schlick Fresnel; the forms of Filament's brdf.fs).
void light_surface(vec2 pos, vec3 n, out vec3 diffuse, out vec3 specular) {
    diffuse = vec3(0.0);
    specular = vec3(0.0);
    float a = max(param_roughness, kMinPerceptualRoughness);
    a *= a;
    float a2 = a * a;
    float NoV = max(n.z, 1e-4);  // the view is (0, 0, 1); n.z >= 0.58 even at waves = 4
    int points = 0;
    for (int i = 0; i < acetate_light_count; ++i) {
        AcetateLight l = acetate_lights[i];
        vec3 to_light;
        vec3 radiance;
        if (l.kind == ACETATE_LIGHT_SUN) {
            to_light = l.direction;
            radiance = min(l.color * l.intensity, vec3(kHalfMax));
        } else {
            if (points >= MAX_LIGHTS) continue;
            ++points;
            if (l.radius <= 0.0) continue;
            vec3 d = vec3(l.position - pos, l.height);
            float len = length(d);
            float r = len / l.radius;
            if (r >= 1.0) continue;
            float window = 1.0 - r * r;  // the lighting effect's falloff, over 3D distance
            // Capped like the sun, so no sum below reaches infinity (64 lights * 65504).
            radiance = min(l.color * l.intensity, vec3(kHalfMax)) * (window * window);
            // A light at the pixel at height 0 is taken as straight above, never normalised.
            to_light = len > 1e-4 ? d / len : vec3(0.0, 0.0, 1.0);
        }
        float NoL = dot(n, to_light);
        if (NoL <= 0.0) continue;
        NoL = min(NoL, 1.0);
        diffuse += radiance * NoL;
        vec3 h = to_light + vec3(0.0, 0.0, 1.0);
        float hl = length(h);
        if (hl < 1e-4) continue;
        h /= hl;
        float NoH = clamp(dot(n, h), 0.0, 1.0);
        // 1 - NoH^2 as |n x h|^2: no cancellation when NoH is near 1.
        vec3 nxh = cross(n, h);
        float k = a / (dot(nxh, nxh) + (NoH * a) * (NoH * a));
        float D = k * k / kPi;
        float lambda_v = NoL * sqrt((NoV - a2 * NoV) * NoV + a2);
        float lambda_l = NoV * sqrt((NoL - a2 * NoL) * NoL + a2);
        float V = 0.5 / (lambda_v + lambda_l);  // both > 0: NoL > 0, NoV > 0, a2 > 0
        float F = kWaterF0 + (1.0 - kWaterF0) * pow(1.0 - clamp(h.z, 0.0, 1.0), 5.0);
        specular += radiance * (D * V * F * NoL);
    }
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 pos = acetate_scene_position(gl_FragCoord.xy);  // scene pixels, y down
    vec4 c = texelFetch(previous, p, 0);
    if (c.a <= 0.0 || any(lessThan(pos, WATER_BOX.xy)) || any(greaterThanEqual(pos, WATER_BOX.zw))) {
        out_color = c;
        return;
    }
    float cover = water_cover(p);
    if (cover <= 0.0) {
        out_color = c;
        return;
    }
    float dist = shore_distance(pos);
#if HAS_OUTDOORS
    vec4 o = texelFetch(mask_outdoors, p, 0);
    float outdoor = clamp(o.r, 0.0, 1.0) * clamp(o.a, 0.0, 1.0);
#else
    float outdoor = 1.0;
#endif
    float amplitude = param_waves * mix(param_indoor_waves, 1.0, outdoor);
    Surface s = surface_at(pos);

    // 1-2. The bed, refracted, with the caustics the waves focus onto it.
    vec3 bed = refracted_bed(pos, c, s.slope * (param_refraction * amplitude), dist);
    float depth = mix(1.0 - exp(-dist / param_depth_range), cover, param_depth_from_mask);
    float caustic_gain = param_caustics * min(amplitude, 1.0) * (1.0 - 0.6 * depth);
    bed *= mix(1.0, s.caustic, caustic_gain);

    // 3. The water column: the bed through a depth-blended transmittance, then the light the
    // murk scatters back (lit like the foam) hiding it with depth.
    vec3 n = normalize(vec3(-kMaxSlope * amplitude * s.slope, 1.0));
    vec3 diffuse, specular;
    light_surface(pos, n, diffuse, specular);
    vec3 light = min(param_ambient + diffuse, vec3(kHalfMax));  // finite: no 0 * inf below
    vec3 color = bed * mix(param_shallow_color, param_deep_color, depth);
    color = mix(color, param_murk_color * light * c.a, param_murk * depth);

    // 4-5. Foam and glints, lit by this floor's lights and sun.
    float foam = 0.0;
    if (param_foam > 0.0 && param_foam_width > 0.0) {
        float band = 1.0 - smoothstep(0.0, param_foam_width, dist);
        float noise = 0.5 + 0.5 * wave_layer(pos, FOAM_SCALE, vec2(-1.0, 1.0), phase_foam).z;
        foam = param_foam * band * mix(1.0, smoothstep(0.25, 0.75, noise), param_foam_breakup);
    }
    color = mix(color, param_foam_color * light * c.a, foam);
    color += min(specular, vec3(kGlintCap)) * (param_glints * c.a);

    vec3 rgb = mix(c.rgb, color, cover);
    out_color = vec4(min(rgb, max(c.rgb, vec3(kHalfMax))), c.a);
}
