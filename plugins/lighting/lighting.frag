// acetate.lighting: ambient light (day/night), the floor's point lights, a darkness level.
// Light multiplies the premultiplied colour, so every term is scaled by alpha: a transparent
// pixel stays (0, 0, 0, 0) (docs/design.md, L-alpha-zero: the lighting bug that started it
// all), and alpha is passed through untouched.
//
// Lights: the host's acetate_lights[] (point lights in scene order, then the floor's sun).
// Only point lights count. The sun is ignored: on a flat floor without normals a directional
// light would only add a constant, which is what the ambient level already is. A point light's
// height is ignored too: its falloff is by distance on the floor, as before lights had a
// height, so scenes render exactly as they did.

float falloff(float distance_over_radius) {
    // Smooth: 1 at the light, 0 with zero slope at the radius.
    float t = clamp(1.0 - distance_over_radius * distance_over_radius, 0.0, 1.0);
    return t * t;
}

void main() {
    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 pos = acetate_scene_position(gl_FragCoord.xy);  // scene pixels, y down, as the lights
    float ambient = mix(param_night_ambient, param_day_ambient, param_day) * (1.0 - param_darkness);
    vec3 light = vec3(ambient);
    // Points come first, so the preset's cap counts point lights, as it always has; i is the
    // point's index, which keeps each light's flicker phase.
    int count = min(acetate_light_count, int(param_max_lights));
    for (int i = 0; i < count; ++i) {
        AcetateLight l = acetate_lights[i];
        if (l.kind != ACETATE_LIGHT_POINT) continue;
        float d = length(pos - l.position) / l.radius;
        if (d >= 1.0) continue;
        float flicker = 1.0 + param_flicker * 0.15 * sin(acetate_time * 7.0 + float(i) * 1.7);
        light += l.color * (l.intensity * falloff(d) * flicker * (1.0 - param_darkness));
    }
    // Capped at 65504, the largest half float, so a bright light never stores Inf in rgba16f
    // targets; a channel already above it (rgba32f) is never lowered by the cap.
    out_color = vec4(min(c.rgb * light, max(c.rgb, vec3(65504.0))), c.a);
}
