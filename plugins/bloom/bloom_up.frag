// acetate.bloom "upK": upK = tent(coarser) + level, where the input coarser is the coarser
// level (up(K+1), or downN for the coarsest step) and level is downK, at this pass's size.
// 9-tap tent (weights 1 2 1 / 2 4 2 / 1 2 1, / 16), taps param_radius texels of coarser apart,
// around this texel's centre on the anchored grid (i + 0.5) / 2. With radius 1 every tap lands
// at a bilinear fraction of 0.25 or 0.75, exact on any sampler. The tent sums to 1 and bilinear
// taps at half-texel spacing form a partition of unity, so the upsample preserves the mean too.
// With ONE_TAP (the pass's defines: the finest upsample of a cheaper preset) the tent is one
// bilinear tap at the centre, still a partition of unity.

vec3 at(vec2 pos, vec2 inv) { return texture(coarser, pos * inv).rgb; }

void main() {
    vec2 inv = 1.0 / vec2(textureSize(coarser, 0));
    vec2 c = 0.5 * gl_FragCoord.xy;
#ifdef ONE_TAP
    vec3 s = at(c, inv);  // the bilinear tap alone: a cheaper, blockier finest level
#else
    float r = param_radius;
    vec3 s = (4.0 * at(c, inv)
              + 2.0 * (at(c + vec2(-r, 0.0), inv) + at(c + vec2(r, 0.0), inv)
                       + at(c + vec2(0.0, -r), inv) + at(c + vec2(0.0, r), inv))
              + at(c + vec2(-r, -r), inv) + at(c + vec2(r, -r), inv)
              + at(c + vec2(-r, r), inv) + at(c + vec2(r, r), inv)) * (1.0 / 16.0);
#endif
    out_color = vec4(s + texelFetch(level, ivec2(gl_FragCoord.xy), 0).rgb, 0.0);
}
