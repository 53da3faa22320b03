#version 450
// Lit mesh fragment shader: albedo * (ambient * hemisphere(N) + (1 - ambient) * key * max(dot(N, L), 0)), where
// hemisphere(N) = mix(ground, sky, 0.5 + 0.5 N.y) (set 0 binding 4) and albedo = instance colour * material
// base colour (* the base colour texture at the vertex UVs in textured mode, offsets.w == 2). N is turned to
// face the camera (two-sided lighting, so meshes with either winding light the same). In box mode
// (offsets.w == 1) N is the flat face normal from screen-space derivatives of the world position.

layout(push_constant) uniform Push {
    mat4 view_proj;
    vec4 light;
    vec4 camera;
    uvec4 offsets;
    vec4 base_colour;
} pc;

layout(std430, set = 0, binding = 4) readonly buffer Lighting {
    vec4 sky;
    vec4 ground;
    vec4 key;
} lighting;
layout(set = 1, binding = 1) uniform sampler2D base_colour_texture;

layout(location = 0) in vec3 v_normal;
layout(location = 1) in vec3 v_world;
layout(location = 2) in vec4 v_colour;
layout(location = 3) in vec2 v_uv;
layout(location = 0) out vec4 out_colour;

void main() {
    vec3 n = pc.offsets.w == 1u ? normalize(cross(dFdx(v_world), dFdy(v_world))) : normalize(v_normal);
    if (dot(n, pc.camera.xyz - v_world) < 0.0) n = -n;
    vec4 albedo = v_colour;
    if (pc.offsets.w == 2u) albedo *= texture(base_colour_texture, v_uv);
    float ambient = pc.light.w;
    vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * n.y);
    float diffuse = max(dot(n, pc.light.xyz), 0.0);
    vec3 lit = albedo.rgb * (ambient * hemi + (1.0 - ambient) * lighting.key.rgb * diffuse);
    out_colour = vec4(clamp(lit, 0.0, 1.0), albedo.a);
}
