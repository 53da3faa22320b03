#version 450
// Lit mesh vertex shader with vertex pulling: positions and normals come from storage buffers so one
// indexed, instanced draw covers every character that shares a topology (one instance per character).
// Vertex i of instance k reads element vertex_base + k * vertex_stride + i (vertex_stride 0 = shared mesh).
// Box mode (offsets.w == 1): one indexed, non-instanced draw for N unit boxes, with an index buffer of
// box * 8 + corner; vertex i is corner i % 8 of box i / 8, its position computed from the corner bits
// (bit 0: x, bit 1: y, bit 2: z; 0 = -0.5, 1 = +0.5) and no normal (the fragment shader derives flat face
// normals). Lavapipe shades vertices on one thread and runs instances one by one, so 8 arithmetic corners
// per box in one draw is far cheaper than N instances of a 24-vertex mesh.
// Textured mode (offsets.w == 2): the vertex's texture coordinate is element gl_VertexIndex of the material
// set's UV buffer (set 1, shared by every instance of the topology).

layout(std430, set = 0, binding = 0) readonly buffer Positions { float positions[]; };
layout(std430, set = 0, binding = 1) readonly buffer Normals { float normals[]; };
struct Instance {
    mat4 model;
    vec4 colour;
};
layout(std430, set = 0, binding = 2) readonly buffer Instances { Instance instances[]; };
layout(std430, set = 1, binding = 0) readonly buffer Uvs { vec2 uvs[]; };

layout(push_constant) uniform Push {
    mat4 view_proj;     // clip-space (Vulkan convention) from world
    vec4 light;         // xyz: unit direction towards the light (world), w: ambient in [0,1]
    vec4 camera;        // xyz: camera position (world)
    uvec4 offsets;      // x: vertex_base, y: vertex_stride, z: instance_base, w: 0 mesh, 1 boxes, 2 textured mesh
    vec4 base_colour;   // the draw's material colour
} pc;

layout(location = 0) out vec3 v_normal;
layout(location = 1) out vec3 v_world;
layout(location = 2) out vec4 v_colour;
layout(location = 3) out vec2 v_uv;

void main() {
    uint inst;
    vec3 p;
    vec3 n;
    if (pc.offsets.w == 1u) {
        inst = pc.offsets.z + uint(gl_VertexIndex) / 8u;
        uint c = uint(gl_VertexIndex) % 8u;
        p = vec3(float(c & 1u), float((c >> 1u) & 1u), float((c >> 2u) & 1u)) - 0.5;
        n = vec3(0.0);
    } else {
        inst = pc.offsets.z + uint(gl_InstanceIndex);
        uint v = pc.offsets.x + uint(gl_InstanceIndex) * pc.offsets.y + uint(gl_VertexIndex);
        p = vec3(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
        n = vec3(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
    }
    mat4 m = instances[inst].model;
    // Cofactor matrix = det * inverse-transpose: transforms normals correctly under non-uniform scale
    // (proxy boxes); the sign of det is irrelevant because the fragment shader faces normals to the camera.
    mat3 a = mat3(m);
    mat3 cof = mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1]));
    vec4 world = m * vec4(p, 1.0);
    v_normal = cof * n;
    v_world = world.xyz;
    v_colour = instances[inst].colour * pc.base_colour;
    v_uv = pc.offsets.w == 2u ? uvs[gl_VertexIndex] : vec2(0.0);
    gl_Position = pc.view_proj * world;
}
