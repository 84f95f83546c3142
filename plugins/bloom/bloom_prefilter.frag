// acetate.bloom "prefilter": bright-pass + the first, firefly-safe downsample by DIVISOR (2, 4 or
// 8, from the pass's defines: the chain's first level is half, quarter or eighth size).
// Reads src (previous, the composite), writes the first down level (ceil(canvas / DIVISOR)).
//
// Grid: output texel i covers input texels DIVISOR i .. DIVISOR (i+1) - 1 (anchored at the
// top-left, the way the host sizes targets: ceil(size / DIVISOR)). Positions are in input texels, so uv = pos / input size
// (textureSize), not gl_FragCoord * acetate_output.zw: on an odd input, 2 * ceil(w / 2) != w and
// normalising by the output size would stretch the grid, so the bloom would drift by up to half
// a texel per level. The four taps sit on texel corners (bilinear weights exactly 0.5): each is
// the mean of one 2x2 block: together a 4x4 box centred on the 2x2 block at DIVISOR 2 (blocks
// overlap, as in the down passes), exactly the block at DIVISOR 4 and 8 (4 and 16 taps, each
// input texel read once). A tap past the edge is clamped to the edge
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

// TAPS (the pass's defines) per axis: 2 at DIVISOR 2 and 4 (offsets -1, +1), 4 at DIVISOR 8
// (-3, -1, +1, +3).
const int N = TAPS;

void main() {
    vec2 inv = 1.0 / vec2(textureSize(src, 0));
    vec2 c = DIVISOR * gl_FragCoord.xy;  // centre of this texel's input block
    // Karis average: a tap holding a single very bright pixel weighs ~1/luma, so a firefly adds
    // at most ~1/3 of a unit to its neighbourhood instead of exploding into a disc.
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
            vec3 t = tap(c + vec2(float(2 * i + 1 - N), float(2 * j + 1 - N)), inv);
            float w = 1.0 / (1.0 + luma(t));
            sum += t * w;
            weights += w;
        }
    out_color = vec4(sum / weights, 0.0);
}
