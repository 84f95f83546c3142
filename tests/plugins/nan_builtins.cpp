// Feeds min, max, clamp and smoothstep what GLSL leaves to the driver (checked_memory_test.cpp):
//   r = clamp(NaN, 0, 1), with the NaN made at run time from the texel (log of a negative
//       number), so glslang cannot fold it;
//   g = smoothstep(1, 0, previous.r): edge0 >= edge1, undefined in GLSL;
//   b = a correct use of every other form (vector, vector-with-scalar, int and uint), which
//       must come out the same with CompositorOptions::checked_builtins and without;
//   a = previous.a.
#include <acetate/effect.hpp>

class NanBuiltins final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.nan_builtins";
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "builtins",
                    .glsl = R"(
void main() {
    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float nan_at_run_time = log(-1.0 - c.a);
    ivec2 i = clamp(ivec2(gl_FragCoord.xy), 1, 3);
    i = max(min(i, ivec2(2)), 0);
    uvec3 u = clamp(max(uvec3(i.xyy), 1u), uvec3(0u), uvec3(5u));
    vec3 v = clamp(c.rgb * 3.0, 0.0, 1.0) + max(c.rgb, vec3(0.2)) + min(c.rgb, 0.3);
    v = smoothstep(0.0, 4.0, v) + smoothstep(vec3(0.0), vec3(2.0), v);
    float b = clamp(dot(v, vec3(0.25)), 0.0, 1.0) * min(c.a, 1.0) +
              float(u.x + u.y + u.z) * max(0.01, c.b * 0.1) + smoothstep(0.0, 1.0, c.g);
    out_color = vec4(clamp(nan_at_run_time, 0.0, 1.0), smoothstep(1.0, 0.0, c.r), b, c.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(NanBuiltins)
