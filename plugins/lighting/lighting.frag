// acetate.lighting: ambient light (day/night), the floor's point lights, a darkness level.
// Light multiplies the premultiplied colour, so every term is scaled by alpha: a transparent
// pixel stays (0, 0, 0, 0) (docs/design.md, L-alpha-zero: the lighting bug that started it
// all), and alpha is passed through untouched.
//
// floor_data: [light count, then per light: x, y, radius, intensity, r, g, b, unused].

float falloff(float distance_over_radius) {
    // Smooth: 1 at the light, 0 with zero slope at the radius.
    float t = clamp(1.0 - distance_over_radius * distance_over_radius, 0.0, 1.0);
    return t * t;
}

void main() {
    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 pos = gl_FragCoord.xy;  // full-resolution pass: scene pixels, y down
    float ambient = mix(param_night_ambient, param_day_ambient, param_day) * (1.0 - param_darkness);
    vec3 light = vec3(ambient);
    int count = min(int(floor_data[0]), int(param_max_lights));
    for (int i = 0; i < count; ++i) {
        int b = 1 + i * 8;
        float r = floor_data[b + 2];
        float d = length(pos - vec2(floor_data[b], floor_data[b + 1])) / r;
        if (d >= 1.0) continue;
        float flicker = 1.0 + param_flicker * 0.15 * sin(acetate_time * 7.0 + float(i) * 1.7);
        vec3 colour = vec3(floor_data[b + 4], floor_data[b + 5], floor_data[b + 6]);
        light += colour * (floor_data[b + 3] * falloff(d) * flicker * (1.0 - param_darkness));
    }
    out_color = vec4(c.rgb * light, c.a);
}
