#version 450
// A tile quad: the image is scaled to its rect in scene pixels (origin top-left, y down).
// Vulkan's framebuffer y also points down, so scene space maps to NDC without a flip.
layout(push_constant) uniform Push {  // TilePushConstants (render/host_pipelines.hpp)
    vec4 tile_rect;       // x, y, width, height in scene pixels
    vec4 isolation_tint;  // read by tile.frag's isolation variants
    vec2 canvas_size;     // in pixels
} pc;
layout(location = 0) out vec2 uv;
void main() {
    vec2 corner = vec2(gl_VertexIndex & 1, (gl_VertexIndex >> 1) & 1);  // 4-vertex strip
    uv = corner;
    vec2 pos = pc.tile_rect.xy + corner * pc.tile_rect.zw;
    gl_Position = vec4(pos / pc.canvas_size * 2.0 - 1.0, 0.0, 1.0);
}
