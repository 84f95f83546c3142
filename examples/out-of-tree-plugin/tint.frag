// com.example.tint: multiplies colour by a tint, leaving alpha exactly as it was.
//
// The host declares, before this text: `previous` (sampler2D, this floor so far), the
// AcetateFrame uniform block with param_strength (float) and param_tint (vec3), and
// `out vec4 out_color`. Colours are premultiplied and linear.
void main() {
    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    // Each factor lies in [0, 1], so rgb stays 0 where a == 0 and never exceeds a.
    vec3 factor = mix(vec3(1.0), param_tint, param_strength);
    out_color = vec4(c.rgb * factor, c.a);
}
