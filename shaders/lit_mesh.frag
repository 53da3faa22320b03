#version 450
// Lit mesh fragment shader: albedo * (ambient * hemisphere(N) + (1 - ambient) * key * max(dot(N, L), 0)), where
// hemisphere(N) = mix(ground, sky, 0.5 + 0.5 N.y) (set 0 binding 4) and albedo = instance colour * material
// base colour (* the base colour texture at the vertex UVs in textured mode, offsets.w & 2). N is turned
// to face the camera (two-sided lighting, so meshes with either winding light the same). In box mode (offsets.w & 1)
// N is the flat face normal from screen-space derivatives of the world position. With offsets.w & 4 the
// world normal itself is written, encoded as 0.5 + 0.5 N (impostor atlas bakes). With offsets.w bit 15 (an unlit
// material) the albedo is written as it is.
// Built again with DITHER (the dithered pipelines, gpu::LitPipelines): a screen-door fade keeps only the
// pixels whose 4x4 Bayer value is below (offsets.w >> 8) & 31 (0..16, gpu::lit_dither_bits), the complement of an
// impostor faded at -m (shaders/impostor.frag) for the same m, or with bit 13 the complement of those (the left
// mesh of a mesh <-> mesh cross-fade); the pipelines without it never discard. The DITHER build also alpha-tests
// (bit 14 of offsets.w, the cutoff in bits 16..31: gpu::lit_alpha_bits), for materials drawn with alpha masks.

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

layout(location = 0) in vec4 v_normal_u;   // xyz: normal, w: texture u
layout(location = 1) in vec4 v_world_v;    // xyz: world position, w: texture v
layout(location = 2) flat in vec4 v_colour;
layout(location = 0) out vec4 out_colour;

#ifdef DITHER
const uint kBayer[16] = uint[](0u, 8u, 2u, 10u, 12u, 4u, 14u, 6u, 3u, 11u, 1u, 9u, 15u, 7u, 13u, 5u);
#endif

void main() {
#ifdef DITHER
    ivec2 q = ivec2(gl_FragCoord.xy) & 3;
    // Kept: Bayer value below the count in bits 8..12; bit 13 keeps the complement (the other mesh of a cross-fade).
    if ((kBayer[q.y * 4 + q.x] < ((pc.offsets.w >> 8) & 31u)) == ((pc.offsets.w & 0x2000u) != 0u)) discard;
#endif
    const vec3 world = v_world_v.xyz;
    vec3 n = (pc.offsets.w & 1u) != 0u ? normalize(cross(dFdx(world), dFdy(world))) : normalize(v_normal_u.xyz);
    if (dot(n, pc.camera.xyz - world) < 0.0) n = -n;
    vec4 albedo = v_colour;
    if ((pc.offsets.w & 2u) != 0u) albedo *= texture(base_colour_texture, vec2(v_normal_u.w, v_world_v.w));
#ifdef DITHER
    // Alpha test (gpu::lit_alpha_bits): bit 14 on, the cutoff in bits 16..31.
    if ((pc.offsets.w & 0x4000u) != 0u && albedo.a < float(pc.offsets.w >> 16) / 65535.0) discard;
#endif
    if ((pc.offsets.w & 4u) != 0u) {  // normal output (impostor bakes): 0.5 + 0.5 N, the draw's coverage in alpha
        out_colour = vec4(0.5 + 0.5 * n, albedo.a);
        return;
    }
    if ((pc.offsets.w & 0x8000u) != 0u) {  // an unlit material (gpu::kLitUnlit, KHR_materials_unlit): its albedo as it is
        out_colour = vec4(clamp(albedo.rgb, 0.0, 1.0), albedo.a);
        return;
    }
    float ambient = pc.light.w;
    vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * n.y);
    float diffuse = max(dot(n, pc.light.xyz), 0.0);
    vec3 lit = albedo.rgb * (ambient * hemi + (1.0 - ambient) * lighting.key.rgb * diffuse);
    out_colour = vec4(clamp(lit, 0.0, 1.0), albedo.a);
}
