// BROKEN on purpose: many frames in one load. A 1x1 target `clock` carries (time, frames seen)
// from frame to frame: a pass that discards everything is its first writer (so last frame's
// value survives; the host clears nothing), and a frame counts as new when acetate_time
// changes, so the renders within one frame (each floor, the composite) count once. After an
// 8-frame warm-up the effect "settles" with sqrt(8 - frames), a sign slip (it meant
// frames - 8): NaN from the 9th frame on, over the whole floor. Until then colour is scaled by
// 0.9 and alpha kept, whatever the count, so the state changes no image before the 9th frame.
// The first read guards against the poison and uninitialised memory: only a texel carrying the
// exact magic (0.3125, 0.6875) in blue and alpha is a clock. Caught by: FINITE in frames/many
// (10 frames at strictness 1) only; no other case renders more than 6 frames (distinct
// times) in one load.
#include <acetate/effect.hpp>

class FrameCount final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.frame_count";
        e.display_name = "Harness: settles after eight frames";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.target("clock", 4096);  // 1x1 for any canvas
        graph.target("clock_next", 4096);
        graph.pass({.name = "keep",
                    .glsl = "void main() { discard; }  // keeps last frame's clock\n",
                    .output = "clock"});
        graph.pass({.name = "tick",
                    .glsl = R"(
void main() {
    vec4 last = texelFetch(clock, ivec2(0), 0);
    bool valid = last.b == 0.3125 && last.a == 0.6875;  // NaN or any poison: no clock yet
    float now = unpackHalf2x16(packHalf2x16(vec2(acetate_time, 0.0))).x;  // as stored
    float frames = valid ? last.g : 0.0;
    if (!valid || last.r != now) frames += 1.0;
    out_color = vec4(now, frames, 0.3125, 0.6875);
}
)",
                    .inputs = {"clock"},
                    .output = "clock_next"});
        graph.pass({.name = "store",
                    .glsl = "void main() { out_color = texelFetch(clock_next, ivec2(0), 0); }\n",
                    .inputs = {"clock_next"},
                    .output = "clock"});
        graph.pass({.name = "apply",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float frames = texelFetch(clock_next, ivec2(0), 0).g;
    float shade = 0.9;
    if (frames > 8.0) shade -= 0.05 * sqrt(8.0 - frames);  // meant frames - 8.0
    out_color = vec4(prev.rgb * shade, prev.a);
}
)",
                    .inputs = {"previous", "clock_next"}});
    }
};
ACETATE_REGISTER_EFFECT(FrameCount)
