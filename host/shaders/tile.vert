#version 450
// A tile quad: the image is scaled to its rect in scene pixels (origin top-left, y down), seen
// through the camera. Vulkan's framebuffer y also points down, so scene space maps to NDC
// without a flip. The texture coordinate is computed per pixel in tile.frag, not interpolated.
layout(push_constant) uniform Push {  // TilePushConstants (render/host_pipelines.hpp)
    vec4 tile_rect;       // x, y, width, height in scene pixels
    vec4 isolation_tint;  // read by tile.frag's isolation variants
    vec4 view;            // the camera: origin x, y (scene pixels), scale, 1/scale
    vec2 canvas_size;     // the output, in pixels
} pc;
void main() {
    vec2 corner = vec2(gl_VertexIndex & 1, (gl_VertexIndex >> 1) & 1);  // 4-vertex strip
    vec2 pos = (pc.tile_rect.xy + corner * pc.tile_rect.zw - pc.view.xy) * pc.view.z;
    gl_Position = vec4(pos / pc.canvas_size * 2.0 - 1.0, 0.0, 1.0);
}
