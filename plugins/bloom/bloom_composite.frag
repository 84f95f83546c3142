// acetate.bloom "composite": result = previous + intensity * bloom / LEVELS, where the input
// bloom is the first up level (the first down level when the chain has one level) and LEVELS
// and SCALE come from the pass's defines: LEVELS is how many levels that sum holds, each
// carrying the whole bright-pass energy, so dividing by LEVELS makes the added energy intensity
// x the bright-pass energy whatever the preset; SCALE is the first level's divisor (2 or 4).
// bloom is read with one bilinear tap on the anchored grid (fractions 0.25/0.75 at SCALE 2,
// odd eighths at SCALE 4: exact on any sampler with 3 or more bits of sub-texel precision).
//
// Alpha: the added light b = min(1, max(added rgb)) covers that much more of the pixel:
// a' = a + b (1 - a) never drops, and where a' rounds to 0 so does every added channel (each is
// <= b), so transparent pixels stay (0, 0, 0, 0) unless light really lands on them.

void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 uv = gl_FragCoord.xy / (SCALE * vec2(textureSize(bloom, 0)));
    vec3 add = texture(bloom, uv).rgb * (param_intensity / LEVELS);
    float b = min(1.0, max(add.r, max(add.g, add.b)));
    out_color = vec4(min(prev.rgb + add, vec3(65504.0)),  // half max: never Inf
                     prev.a + b * max(0.0, 1.0 - prev.a));
}
