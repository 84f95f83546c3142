// com.example.drop_shadow, blur_x and blur_y: one direction of a Gaussian blur of src's alpha.
//
// Both passes run this text. What differs, the pass gives:
//   src        its input, named by Pass::input_names: "previous" (the floor), then "across"
//   DIRECTION  vec2(1, 0) or vec2(0, 1), from Pass::defines
// param_radius is the blur radius in scene pixels; param_taps, the most samples on each side, is
// a hidden parameter the presets set. The output is a half-size target.
void main() {
    // This texel's centre, normalised: the same point of the scene in src, whatever src's size.
    vec2 uv = gl_FragCoord.xy * acetate_output.zw;
    // The radius in src's texels (acetate_size_src: its width, height and their reciprocals).
    // Taps closer than a texel would read the same texels again, so use no more than that.
    float radius = dot(DIRECTION, param_radius * acetate_size_src.xy * acetate_canvas.zw);
    int n = min(int(param_taps), int(ceil(radius)));
    vec2 step = n > 0 ? DIRECTION * acetate_size_src.zw * (radius / float(n)) : vec2(0.0);
    float sum = 0.0;
    float weights = 0.0;
    for (int i = -n; i <= n; ++i) {
        float x = n > 0 ? float(i) / float(n) : 0.0;  // -1 .. 1 across the radius
        float w = exp(-2.0 * x * x);                   // sigma = radius / 2
        sum += w * texture(src, uv + float(i) * step).a;
        weights += w;
    }
    // Only alpha matters downstream; it stays in [0, 1] (a weighted mean of alphas).
    out_color = vec4(0.0, 0.0, 0.0, sum / weights);
}
