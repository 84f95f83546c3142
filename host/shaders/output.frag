#version 450
// Accumulation -> output image, or one of the debug views (docs/design.md, L-debug-views).
layout(push_constant) uniform Push {  // OutputPushConstants (render/host_pipelines.hpp)
    vec4 background;  // straight-alpha linear background colour
    uint view;        // OutputView (render/output_view.hpp)
} pc;
layout(set = 0, binding = 0) uniform sampler2D accumulation;
layout(set = 0, binding = 1) uniform sampler2D active_floor;  // the active floor's own target
layout(location = 0) out vec4 color;

const uint kNormal = 0u, kFloorAlpha = 1u, kAccumAlpha = 2u, kFloorRgb = 3u, kViolations = 4u,
           kIsolation = 5u;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 acc = texelFetch(accumulation, p, 0);
    vec4 flr = texelFetch(active_floor, p, 0);
    if (pc.view == kFloorAlpha) {
        color = vec4(vec3(flr.a), 1.0);
    } else if (pc.view == kAccumAlpha) {
        color = vec4(vec3(acc.a), 1.0);
    } else if (pc.view == kFloorRgb) {
        color = vec4(flr.rgb, 1.0);
    } else if (pc.view == kViolations) {
        bool bad = (flr.a <= 0.0 && any(notEqual(flr.rgb, vec3(0.0)))) || any(isnan(flr)) ||
                   any(isinf(flr));
        float luma = dot(flr.rgb, vec3(0.2126, 0.7152, 0.0722));
        color = bad ? vec4(1.0, 0.0, 0.0, 1.0) : vec4(vec3(0.25 * clamp(luma, 0.0, 1.0)), 1.0);
    } else {
        // Premultiplied over the canvas background (docs/design.md, L-one-alpha).
        vec4 bg = vec4(pc.background.rgb * pc.background.a, pc.background.a);
        color = acc + bg * (1.0 - acc.a);
    }
}
