// com.example.colour_grade: grades the colour itself, then puts the coverage back.
//
// Inputs: previous. Parameters: param_lift, param_gamma, param_gain (vec3), param_saturation.
// Colours are premultiplied and linear.
void main() {
    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    // Nothing here (a == 0): no colour to grade, and rgb must stay 0.
    if (c.a <= 0.0) {
        out_color = vec4(0.0, 0.0, 0.0, c.a);
        return;
    }
    // Un-premultiply: lift must move a half-covered edge pixel as much as an opaque one.
    vec3 v = c.rgb / c.a;
    // Black goes to lift, white to gain. 65504, RGBA16F's largest value, keeps an HDR pixel
    // finite through pow() and the re-premultiplication.
    v = clamp(param_lift + (param_gain - param_lift) * v, 0.0, 65504.0);
    v = min(pow(v, 1.0 / param_gamma), vec3(65504.0));
    float luma = dot(v, vec3(0.2126, 0.7152, 0.0722));  // Rec. 709 weights, linear light
    v = clamp(mix(vec3(luma), v, param_saturation), 0.0, 65504.0);
    // Re-premultiply; alpha is written back bit for bit.
    out_color = vec4(v * c.a, c.a);
}
