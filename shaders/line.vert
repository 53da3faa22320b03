#version 450
// Unlit line vertex shader with vertex pulling: each vertex is {vec4 position (w = 1), vec4 colour}.

struct LineVertex {
    vec4 position;
    vec4 colour;
};
layout(std430, set = 0, binding = 3) readonly buffer Lines { LineVertex line_vertices[]; };

layout(push_constant) uniform Push {
    mat4 view_proj;
    vec4 light;
    vec4 camera;
    uvec4 offsets;      // x: first line vertex
} pc;

layout(location = 0) out vec4 v_colour;

void main() {
    LineVertex lv = line_vertices[pc.offsets.x + uint(gl_VertexIndex)];
    v_colour = lv.colour;
    gl_Position = pc.view_proj * vec4(lv.position.xyz, 1.0);
}
