// acetate.bloom "downK": 2x downsample of src (down(K-1)) with a 4x4 box made of four bilinear
// taps on texel corners (weights exactly 0.5), on the same anchored grid as the prefilter.
// Normalised: a constant stays constant, and with even sizes every input texel gives away
// exactly its energy (edge clamping included), so the mean is preserved.

void main() {
    vec2 inv = 1.0 / vec2(textureSize(src, 0));
    vec2 c = 2.0 * gl_FragCoord.xy;
    vec3 s = texture(src, (c + vec2(-1.0, -1.0)) * inv).rgb + texture(src, (c + vec2(1.0, -1.0)) * inv).rgb
           + texture(src, (c + vec2(-1.0, 1.0)) * inv).rgb + texture(src, (c + vec2(1.0, 1.0)) * inv).rgb;
    out_color = vec4(0.25 * s, 0.0);
}
