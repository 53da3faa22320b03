#version 450
// Lit mesh fragment shader: colour * (ambient + (1 - ambient) * max(dot(N, L), 0)), with N turned to face
// the camera (two-sided lighting, so meshes with either winding light the same). In box mode (offsets.w == 1)
// N is the flat face normal from screen-space derivatives of the world position.

layout(push_constant) uniform Push {
    mat4 view_proj;
    vec4 light;
    vec4 camera;
    uvec4 offsets;
} pc;

layout(location = 0) in vec3 v_normal;
layout(location = 1) in vec3 v_world;
layout(location = 2) in vec4 v_colour;
layout(location = 0) out vec4 out_colour;

void main() {
    vec3 n = pc.offsets.w == 1u ? normalize(cross(dFdx(v_world), dFdy(v_world))) : normalize(v_normal);
    if (dot(n, pc.camera.xyz - v_world) < 0.0) n = -n;
    float ambient = pc.light.w;
    float diffuse = max(dot(n, pc.light.xyz), 0.0);
    out_colour = vec4(v_colour.rgb * (ambient + (1.0 - ambient) * diffuse), v_colour.a);
}
