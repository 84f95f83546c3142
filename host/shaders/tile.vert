#version 450
// A tile quad: the image is scaled to its rect in scene pixels (origin top-left, y down).
// Vulkan's framebuffer y also points down, so scene space maps to NDC without a flip.
layout(push_constant) uniform Push {
    vec4 rect;          // x, y, width, height in scene pixels
    vec4 tint;          // isolation-view tint (rgb), read by the isolation variants
    vec2 canvas;        // canvas size in pixels
    uint floor_index;   // slot in the violation counters
    uint mode;          // unused by the tile stages
} pc;
layout(location = 0) out vec2 uv;
void main() {
    vec2 corner = vec2(gl_VertexIndex & 1, (gl_VertexIndex >> 1) & 1);  // 4-vertex strip
    uv = corner;
    vec2 pos = pc.rect.xy + corner * pc.rect.zw;
    gl_Position = vec4(pos / pc.canvas * 2.0 - 1.0, 0.0, 1.0);
}
