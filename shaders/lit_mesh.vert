#version 450
#extension GL_GOOGLE_include_directive : require
// Lit mesh vertex shader with vertex pulling: positions and normals come from storage buffers. The mode bits
// of offsets.w (gpu::LitMode) choose how a vertex finds its data:
// - mesh (0): one indexed, instanced draw covers every character that shares a topology (one instance per
//   character); vertex i of instance k reads element vertex_base + k * vertex_stride + i.
// - boxes (1): one indexed, non-instanced draw for N unit boxes, with an index buffer of box * 8 + corner;
//   vertex i is corner i % 8 of box i / 8, its position computed from the corner bits (bit 0: x, bit 1: y,
//   bit 2: z; 0 = -0.5, 1 = +0.5) and no normal (the fragment shader derives flat face normals).
// - textured (2): the vertex's texture coordinate is element gl_VertexIndex of the material set's
//   UV buffer (set 1, shared by every character of the topology).
// - vertex colours (64): the colour is multiplied by element gl_VertexIndex of set 1 binding 6, likewise shared.
// Compiled with and without VERTEX_LIT. Without VERTEX_LIT (for shaders/lit_mesh.frag, lit per pixel) the outputs are packed into
// three interpolants, since lavapipe stores and sets up every interpolant of every binned triangle: normal
// and u, world position and v, and the colour (interpolated, for vertex colours). With VERTEX_LIT (for
// shaders/lit_vertex.frag) the lighting of shaders/lit_mesh.frag is evaluated here, at the vertex (Gouraud), and
// the outputs are the lit colour and the UVs: on lavapipe each fragment then costs a multiply. With metallic-roughness
// (128) the vertex's light is shaders/pbr.glsl's for the colour before the base colour texture, metalness and
// roughness read at the vertex (mip 0); the fragment shader then multiplies the whole light, the specular included,
// by the texture (an approximation for the small, far characters these levels draw).
// Each build again with MATERIAL_MAPS (vertex colours, the colour interpolated; with VERTEX_LIT also
// metallic-roughness) and, with VERTEX_LIT, MATERIAL_PBR (metallic-roughness alone): without them the colour is flat
// and that code is left out (gpu::LitVariant; shaders/lit_mesh.frag says why).

layout(std430, set = 0, binding = 0) readonly buffer Positions { float positions[]; };
layout(std430, set = 0, binding = 1) readonly buffer Normals { float normals[]; };
struct Instance {
    mat4 model;
    vec4 colour;
};
layout(std430, set = 0, binding = 2) readonly buffer Instances { Instance instances[]; };
layout(std430, set = 0, binding = 4) readonly buffer Lighting {
    vec4 sky;
    vec4 ground;
    vec4 key;
} lighting;
layout(std430, set = 1, binding = 0) readonly buffer Uvs { vec2 uvs[]; };
#ifdef MATERIAL_MAPS
layout(std430, set = 1, binding = 6) readonly buffer Colours { vec4 vertex_colours[]; };
#endif
#if defined(VERTEX_LIT) && (defined(MATERIAL_MAPS) || defined(MATERIAL_PBR))
layout(set = 1, binding = 5) uniform sampler2D metallic_roughness_texture;
#include "pbr.glsl"
#endif

layout(push_constant) uniform Push {
    mat4 view_proj;     // clip-space (Vulkan convention) from world
    vec4 light;         // xyz: unit direction towards the light (world), w: ambient in [0,1]
    vec4 camera;        // xyz: camera position (world)
    uvec4 offsets;      // x: vertex_base, y: vertex_stride, z: instance_base, w: mode bits (1 boxes, 2 textured)
    vec4 base_colour;   // the draw's material colour
} pc;

#ifdef VERTEX_LIT
layout(location = 0) out vec4 v_lit;        // rgb: colour * light (clamped after the texture), a: alpha
layout(location = 1) out vec2 v_uv;         // texture coordinates
#else
layout(location = 0) out vec4 v_normal_u;   // xyz: normal (cofactor-transformed, not unit), w: texture u
layout(location = 1) out vec4 v_world_v;    // xyz: world position, w: texture v
#ifdef MATERIAL_MAPS
layout(location = 2) out vec4 v_colour;       // instance colour * material base colour * vertex colour
#else
layout(location = 2) flat out vec4 v_colour;  // instance colour * material base colour
#endif
#endif

void main() {
    const uint mode = pc.offsets.w;
    uint inst;
    vec3 p;
    vec3 n;
    if ((mode & 1u) != 0u) {
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
    // (proxy boxes); the sign of det is irrelevant because the normal is turned to face the camera.
    mat3 a = mat3(m);
    mat3 cof = mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1]));
    vec4 world = m * vec4(p, 1.0);
    vec2 uv = (mode & 2u) != 0u ? uvs[gl_VertexIndex] : vec2(0.0);
    vec4 colour = instances[inst].colour * pc.base_colour;
#ifdef MATERIAL_MAPS
    if ((mode & 64u) != 0u) colour *= vertex_colours[gl_VertexIndex];  // vertex colours (gpu::kLitVertexColour)
#endif
#ifdef VERTEX_LIT
    // The fragment shader's light, here (two-sided: the normal is turned to face the camera).
    vec3 nn = normalize(cof * n);
    if (dot(nn, pc.camera.xyz - world.xyz * pc.camera.w) < 0.0) nn = -nn;
    float ambient = pc.light.w;
    vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * nn.y);
    float diffuse = max(dot(nn, pc.light.xyz), 0.0);
    v_lit = vec4(colour.rgb * (ambient * hemi + (1.0 - ambient) * lighting.key.rgb * diffuse), colour.a);
#if defined(MATERIAL_MAPS) || defined(MATERIAL_PBR)
    // With MATERIAL_PBR alone every draw has the bit (gpu::LitVariant::MetallicRoughness): the test is constant there.
    if ((mode & 128u) != 0u) {  // glTF metallic-roughness (gpu::kLitMetallicRoughness)
        const vec2 mr = textureLod(metallic_roughness_texture, uv, 0.0).bg;
        v_lit.rgb = pbr_light(colour.rgb, mr.x, mr.y, nn, normalize(pc.camera.xyz - world.xyz * pc.camera.w), pc.light.xyz, ambient, 1.0 - ambient,
                              lighting.key.rgb, lighting.sky.rgb, lighting.ground.rgb);
    }
#endif
    if ((pc.offsets.w & 0x8000u) != 0u) v_lit = colour;  // an unlit material (gpu::kLitUnlit): its albedo as it is
    v_uv = uv;
#else
    v_normal_u = vec4(cof * n, uv.x);
    v_world_v = vec4(world.xyz, uv.y);
    v_colour = colour;
#endif
    gl_Position = pc.view_proj * world;
}
