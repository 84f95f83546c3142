// BROKEN on purpose: a plugin must not grow its host's memory. build() allocates a 256 KiB
// scratch table for each instance, fills it (so its pages are resident) and never frees it:
// the author thought of it as a per-library cache but allocates it per build, that is per
// instance and per load. Its one pass scales colour by 0.9 and keeps alpha. Caught by: the
// MEMORY check only, in isolation/state, which loads the same two-floor scene again and again
// (two builds, 512 KiB, per load).
#include <acetate/effect.hpp>
#include <cstdlib>
#include <cstring>

class BuildLeak final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.build_leak";
        e.display_name = "Harness: leaks 256 KiB per build";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        constexpr size_t kScratch = 256 << 10;
        void* scratch = std::malloc(kScratch);  // never freed
        if (scratch) std::memset(scratch, 0x5a, kScratch);
        graph.pass({.name = "dim",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * 0.9, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(BuildLeak)
