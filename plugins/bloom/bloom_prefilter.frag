// acetate.bloom "prefilter": bright-pass + the first, firefly-safe 2x downsample.
// Reads src (previous, the composite), writes down1 (ceil(canvas / 2)).
//
// Grid: output texel i covers input texels 2i and 2i+1 (anchored at the top-left, the way the
// host sizes targets: ceil(size / 2)). Positions are in input texels, so uv = pos / input size
// (textureSize), not gl_FragCoord * acetate_output.zw: on an odd input, 2 * ceil(w / 2) != w and
// normalising by the output size would stretch the grid, so the bloom would drift by up to half
// a texel per level. The four taps sit on texel corners (bilinear weights exactly 0.5): each is
// the mean of one 2x2 block, together a 4x4 box. A tap past the edge is clamped to the edge
// texel by the sampler, which is the same as clamping it to the last valid texel centre: the
// partial last texel of an odd-sized level averages only the valid column/row, replicated.

const float CAP = 65504.0 / 16.0;  // bright-pass ceiling: 8 levels summed stay below half max

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Quadratic soft knee on max(r, g, b) (Unity's curve): hue is kept, a saturated colour is not
// under-counted as luminance would. Contribution = max(soft, br - t); scale = contribution / br.
vec3 bright(vec3 c) {
    c = max(c, vec3(0.0));  // a negative channel would make the Karis weight blow up
    float t = param_threshold;
    float k = t * param_knee;
    float br = max(c.r, max(c.g, c.b));
    float soft = clamp(br - t + k, 0.0, 2.0 * k);
    soft = k > 0.0 ? soft * soft / (4.0 * k) : 0.0;
    float scale = br > 0.0 ? max(soft, br - t) / br : 0.0;  // in [0, 1]
    float m = br * scale;
    return c * (scale * (CAP / max(m, CAP)));  // cap: no overflow down the chain
}

vec3 tap(vec2 pos, vec2 inv) { return bright(texture(src, pos * inv).rgb); }

void main() {
    vec2 inv = 1.0 / vec2(textureSize(src, 0));
    vec2 c = 2.0 * gl_FragCoord.xy;  // centre of this texel's 2x2 input block
    vec3 a = tap(c + vec2(-1.0, -1.0), inv);
    vec3 b = tap(c + vec2(1.0, -1.0), inv);
    vec3 d = tap(c + vec2(-1.0, 1.0), inv);
    vec3 e = tap(c + vec2(1.0, 1.0), inv);
    // Karis average: a tap holding a single very bright pixel weighs ~1/luma, so a firefly adds
    // at most ~1/3 of a unit to its neighbourhood instead of exploding into a disc.
    float wa = 1.0 / (1.0 + luma(a)), wb = 1.0 / (1.0 + luma(b));
    float wd = 1.0 / (1.0 + luma(d)), we = 1.0 / (1.0 + luma(e));
    out_color = vec4((a * wa + b * wb + d * wd + e * we) / (wa + wb + wd + we), 0.0);
}
