#version 450
// Composite vertex shader: one quad over the screen rectangle push base_colour gives (x0, y0, x1, y1 in
// Vulkan NDC); the fragment shader writes each pixel's depth from the layer (gpu::LitPipelines::composite;
// the far layer of systems/render/far_layer.hpp).

layout(push_constant) uniform Push {
    mat4 view_proj;
    vec4 light;
    vec4 camera;        // xy: 0.5 / the layer's size in texels (the fragment shader's scale)
    uvec4 offsets;
    vec4 base_colour;   // the rectangle, NDC: x0, y0, x1, y1
} pc;

const vec2 kCorners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

void main() {
    vec2 c = mix(pc.base_colour.xy, pc.base_colour.zw, kCorners[gl_VertexIndex]);
    gl_Position = vec4(c, 1.0, 1.0);
}
