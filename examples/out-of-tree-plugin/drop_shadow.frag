// com.example.drop_shadow, composite: the floor over its shadow.
//
// Inputs: previous (the floor so far) and shadow (half size: the floor's alpha, blurred).
// Parameters: param_colour (vec3), param_opacity, param_offset (vec2, scene pixels).
// Colours are premultiplied and linear.
void main() {
    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    // The shadow here is the blurred alpha of the floor `offset` pixels back.
    vec2 from = (gl_FragCoord.xy - param_offset) * acetate_canvas.zw;
    float a = param_opacity * texture(shadow, from).a;
    // The shadow premultiplied (rgb = colour * a), with the floor over it. Alpha only grows
    // (c.a + a * (1 - c.a) >= c.a), and rgb is 0 wherever the output's alpha is 0.
    out_color = c + vec4(param_colour * a, a) * (1.0 - c.a);
}
