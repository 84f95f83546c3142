#version 450
// A floor's scene-space mask as the camera sees it (compositor_camera.cpp): each render pixel
// reads the mask at the scene position it shows, filtered between texels, 0 off the canvas.
// With a whole-pixel origin at scale 1 every pixel centre falls on a texel centre and the
// sampler is nearest, so the copy is exact. Masks are data, not colour: no blend, no premultiplication.
layout(push_constant) uniform Push {  // MaskViewPushConstants (render/host_pipelines.hpp)
    vec4 view;    // origin x, y (scene pixels), scale, 1/scale
    vec4 canvas;  // the scene's canvas: width, height, 1/width, 1/height
} pc;
layout(set = 0, binding = 0) uniform sampler2D mask;
layout(location = 0) out vec4 color;

void main() {
    vec2 scene = pc.view.xy + gl_FragCoord.xy * pc.view.w;
    if (any(lessThan(scene, vec2(0.0))) || any(greaterThanEqual(scene, pc.canvas.xy))) {
        color = vec4(0.0);
        return;
    }
    color = texture(mask, scene * pc.canvas.zw);
}
