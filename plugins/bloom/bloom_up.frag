// acetate.bloom "upK": upK = tent(coarser) + level, where the input coarser is the coarser
// level (up(K+1), or downN for the coarsest step) and level is downK, at this pass's size.
// 9-tap tent (weights 1 2 1 / 2 4 2 / 1 2 1, / 16), taps param_radius texels of coarser apart,
// around this texel's centre on the anchored grid (i + 0.5) / 2. With radius 1 every tap lands
// at a bilinear fraction of 0.25 or 0.75, exact on any sampler. The tent sums to 1 and bilinear
// taps at half-texel spacing form a partition of unity, so the upsample preserves the mean too.

vec3 at(vec2 pos, vec2 inv) { return texture(coarser, pos * inv).rgb; }

void main() {
    vec2 inv = 1.0 / vec2(textureSize(coarser, 0));
    vec2 c = 0.5 * gl_FragCoord.xy;
    float r = param_radius;
    vec3 s = 4.0 * at(c, inv)
           + 2.0 * (at(c + vec2(-r, 0.0), inv) + at(c + vec2(r, 0.0), inv)
                  + at(c + vec2(0.0, -r), inv) + at(c + vec2(0.0, r), inv))
           + at(c + vec2(-r, -r), inv) + at(c + vec2(r, -r), inv)
           + at(c + vec2(-r, r), inv) + at(c + vec2(r, r), inv);
    out_color = vec4(s * (1.0 / 16.0) + texelFetch(level, ivec2(gl_FragCoord.xy), 0).rgb, 0.0);
}
