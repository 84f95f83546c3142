// BROKEN on purpose: correct only while the Vulkan validation layer is in its process. build()
// asks the dynamic loader whether the layer's library is loaded (no environment variable is
// needed for that); with it, the effect darkens the colour by 0.9, without it (as a user's
// host runs it) by 0.6. Both keep the contract, so no check on a single image sees it.
// Caught by: DETERMINISM, in determinism/without-layer only: that case's process never loaded
// the layer, and its output is compared with determinism/run-1's.
#include <dlfcn.h>

#include <acetate/effect.hpp>

class LayerAware final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.layer_aware";
        e.display_name = "Harness: correct only with the validation layer loaded";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        void* layer = dlopen("libVkLayer_khronos_validation.so", RTLD_LAZY | RTLD_NOLOAD);
        if (layer) dlclose(layer);  // NOLOAD took a reference: give it back
        const float data[] = {layer ? 0.9f : 0.6f};
        graph.floor_data(data);
        graph.pass({.name = "darken",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * floor_data[0], prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(LayerAware)
