#version 450
// Effect passes of kind ACETATE_PASS_INSTANCED_QUADS: quad i covers the scene rect
// floor_data[offset + 4i .. +3] = (x, y, width, height), offset in acetate_misc.z.
// The frame block at binding 11, read as storage like the GLSL passes read it (see
// EffectPipelines::kFrameStorageBinding); binding 0 holds the same bytes as a uniform block.
layout(set = 0, binding = 11, std140) readonly buffer AcetateFrame {
    vec4 acetate_canvas;
    vec4 acetate_output;
    vec4 acetate_misc;
};
layout(set = 0, binding = 9, std430) readonly buffer AcetateFloorData { float floor_data[]; };
// The camera (EffectViewPushConstants): origin x, y in scene pixels, scale, 1/scale.
layout(push_constant) uniform AcetateView {
    vec4 acetate_view;
    vec4 acetate_scene_canvas;
};
layout(location = 0) out vec2 acetate_uv;
layout(location = 1) flat out int acetate_instance;

void main() {
    int base = int(acetate_misc.z) + 4 * gl_InstanceIndex;
    vec4 rect = vec4(floor_data[base], floor_data[base + 1], floor_data[base + 2],
                     floor_data[base + 3]);
    vec2 corner = vec2(gl_VertexIndex & 1, (gl_VertexIndex >> 1) & 1);  // 4-vertex strip
    acetate_uv = corner;
    acetate_instance = gl_InstanceIndex;
    // Scene pixels to render pixels (the camera), then to NDC; acetate_canvas is the render
    // size, and the viewport covers the pass's output, whatever its divisor.
    vec2 render = (rect.xy + corner * rect.zw - acetate_view.xy) * acetate_view.z;
    gl_Position = vec4(render * acetate_canvas.zw * 2.0 - 1.0, 0.0, 1.0);
}
