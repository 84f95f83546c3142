// acetate.fire, pass "glow": the floor lit by its fire. previous -> result over the floor's
// reach. The glow map (texture.glow, one R16F cell per 4 scene pixels) is the emitters blurred
// against a fixed reference (emitters.hpp); it flickers with two phases of 0.37 s and 0.53 s,
// which line up again only every 19.61 s. Light multiplies the premultiplied colour, so transparent pixels stay (0, 0, 0, 0)
// and alpha is passed through; where the map is 0 (beyond the blur's 3 sigma, plus about a
// cell for filtering and the emitters' snap to cells) the pixel is copied exactly.

void main() {
    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 uv = acetate_scene_position(gl_FragCoord.xy) * 0.25 * acetate_size_texture_glow.zw;
    float g = textureLod(texture_glow, uv, 0.0).r;
    float flicker = 0.85 + 0.15 * sin(6.2831853 * phase_flicker_a) * sin(6.2831853 * phase_flicker_b);
    vec3 lit = c.rgb + c.rgb * param_glow_color * (param_glow * g * flicker);
    out_color = vec4(min(lit, max(c.rgb, vec3(65504.0))), c.a);
}
