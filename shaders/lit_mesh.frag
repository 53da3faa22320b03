#version 450
#extension GL_GOOGLE_include_directive : require
// Lit mesh fragment shader: albedo * (ambient * occlusion * hemisphere(N) + (1 - ambient) * key * max(dot(N, L), 0))
// + emissive, where hemisphere(N) = mix(ground, sky, 0.5 + 0.5 N.y) (set 0 binding 4) and albedo = instance colour *
// material base colour (* the base colour texture at the vertex UVs in textured mode, offsets.w & 2). N is turned
// to face the camera (two-sided lighting, so meshes with either winding light the same). In box mode (offsets.w & 1)
// N is the flat face normal from screen-space derivatives of the world position. With offsets.w & 4 the
// world normal itself is written, encoded as 0.5 + 0.5 N (impostor atlas bakes; zero for an unlit material). With
// offsets.w bit 15 (an unlit material) the albedo is written as it is.
// Material maps (gpu::LitMode, set 1 bindings 2..4, read at the vertex UVs): with offsets.w & 8 N is turned by the
// normal map, a glTF tangent-space normal (x along +u, y towards v = 0, z along N) in the tangent frame of the
// screen-space derivatives of the world position and the UVs (so any deformation of the skin keeps its frame;
// mirrored UVs flip the frame's handedness, as MikkTSpace's sign does); with & 16 the ambient term is scaled by the
// occlusion map's red channel; with & 32 the emissive texture is added (at UV (0, 0) when untextured: one texel).
// With offsets.w & 128 the light is glTF's metallic-roughness model (shaders/pbr.glsl), metalness and roughness
// from set 1 binding 5 (blue, green; one texel when untextured), instead of the diffuse one above.
// Built again with DITHER (the dithered pipelines, gpu::LitPipelines): a screen-door fade keeps only the
// pixels whose 4x4 Bayer value is below (offsets.w >> 8) & 31 (0..16, gpu::lit_dither_bits), the complement of an
// impostor faded at -m (shaders/impostor.frag) for the same m, or with bit 13 the complement of those (the left
// mesh of a mesh <-> mesh cross-fade); the pipelines without it never discard. The DITHER build also alpha-tests
// (bit 14 of offsets.w, the cutoff in bits 16..31: gpu::lit_alpha_bits), for materials drawn with alpha masks.
// Each build again with MATERIAL_MAPS (the maps, metallic-roughness, and vertex colours: an interpolated colour) and
// with MATERIAL_PBR (metallic-roughness alone, every draw of it having the bit): the pipelines of materials with
// those LitMode bits (gpu::LitVariant); without either the colour is flat and none of that code is there, since
// lavapipe runs a branch's code under a mask whether or not a pixel takes it (docs/PERFORMANCE.md).

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
#ifdef MATERIAL_MAPS
layout(set = 1, binding = 2) uniform sampler2D normal_texture;
layout(set = 1, binding = 3) uniform sampler2D occlusion_texture;
layout(set = 1, binding = 4) uniform sampler2D emissive_texture;
#endif
#if defined(MATERIAL_MAPS) || defined(MATERIAL_PBR)
layout(set = 1, binding = 5) uniform sampler2D metallic_roughness_texture;

#include "pbr.glsl"
#endif

layout(location = 0) in vec4 v_normal_u;   // xyz: normal, w: texture u
layout(location = 1) in vec4 v_world_v;    // xyz: world position, w: texture v
#ifdef MATERIAL_MAPS
layout(location = 2) in vec4 v_colour;       // interpolated: vertex colours
#else
layout(location = 2) flat in vec4 v_colour;  // one colour a draw and instance
#endif
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
    const vec2 uv = vec2(v_normal_u.w, v_world_v.w);
    vec3 n = (pc.offsets.w & 1u) != 0u ? normalize(cross(dFdx(world), dFdy(world))) : normalize(v_normal_u.xyz);
    if (dot(n, pc.camera.xyz - world * pc.camera.w) < 0.0) n = -n;
#ifdef MATERIAL_MAPS
    if ((pc.offsets.w & 8u) != 0u) {  // normal map (gpu::kLitNormalMap)
        // dp = T du + B dv over the pixel's footprint: T = dp/du, B = dp/dv from the two screen derivatives.
        const vec3 dpx = dFdx(world), dpy = dFdy(world);
        const vec2 dux = dFdx(uv), duy = dFdy(uv);
        const float det = dux.x * duy.y - duy.x * dux.y;
        if (abs(det) > 1e-20) {
            const vec3 t_raw = (duy.y * dpx - dux.y * dpy) / det;
            const vec3 b_raw = (dux.x * dpy - duy.x * dpx) / det;
            const vec3 t = t_raw - n * dot(n, t_raw);
            if (dot(t, t) > 1e-20) {
                const vec3 tn = normalize(t);
                // The map's +y points towards v = 0, against dp/dv; its sign gives the frame's handedness.
                const vec3 b = cross(n, tn) * (dot(cross(n, tn), b_raw) > 0.0 ? -1.0 : 1.0);
                const vec3 m = texture(normal_texture, uv).xyz * 2.0 - 1.0;
                const vec3 mapped = mat3(tn, b, n) * m;
                if (dot(mapped, mapped) > 1e-12) n = normalize(mapped);
            }
        }
    }
#endif
    vec4 albedo = v_colour;
    if ((pc.offsets.w & 2u) != 0u) albedo *= texture(base_colour_texture, uv);
#ifdef DITHER
    // Alpha test (gpu::lit_alpha_bits): bit 14 on, the cutoff in bits 16..31.
    if ((pc.offsets.w & 0x4000u) != 0u && albedo.a < float(pc.offsets.w >> 16) / 65535.0) discard;
#endif
    if ((pc.offsets.w & 4u) != 0u) {  // normal output (impostor bakes): 0.5 + 0.5 N, the draw's coverage in alpha
        // An unlit material writes nothing lit (zero, alpha 0): once the bake averages samples and mip levels, the
        // atlas's normal alpha over its colour alpha is the share of lit surface (shaders/impostor.frag).
        out_colour = (pc.offsets.w & 0x8000u) != 0u ? vec4(0.0) : vec4(0.5 + 0.5 * n, albedo.a);
        return;
    }
    if ((pc.offsets.w & 0x8000u) != 0u) {  // an unlit material (gpu::kLitUnlit, KHR_materials_unlit): its albedo as it is
        out_colour = vec4(clamp(albedo.rgb, 0.0, 1.0), albedo.a);
        return;
    }
    float ambient = pc.light.w;
#ifdef MATERIAL_MAPS
    if ((pc.offsets.w & 16u) != 0u) ambient *= texture(occlusion_texture, uv).r;  // occlusion map (gpu::kLitOcclusion)
    vec3 lit;
    if ((pc.offsets.w & 128u) != 0u) {  // glTF metallic-roughness (gpu::kLitMetallicRoughness)
        const vec2 mr = texture(metallic_roughness_texture, uv).bg;
        lit = pbr_light(albedo.rgb, mr.x, mr.y, n, normalize(pc.camera.xyz - world * pc.camera.w), pc.light.xyz, ambient, 1.0 - pc.light.w, lighting.key.rgb,
                        lighting.sky.rgb, lighting.ground.rgb);
    } else {
        vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * n.y);
        float diffuse = max(dot(n, pc.light.xyz), 0.0);
        lit = albedo.rgb * (ambient * hemi + (1.0 - pc.light.w) * lighting.key.rgb * diffuse);
    }
    if ((pc.offsets.w & 32u) != 0u) lit += texture(emissive_texture, uv).rgb;  // emissive (gpu::kLitEmissive)
#elif defined(MATERIAL_PBR)
    // Metallic-roughness alone (gpu::LitVariant::MetallicRoughness: the bit is set for every draw of this build).
    const vec2 mr = texture(metallic_roughness_texture, uv).bg;
    vec3 lit = pbr_light(albedo.rgb, mr.x, mr.y, n, normalize(pc.camera.xyz - world * pc.camera.w), pc.light.xyz, ambient, 1.0 - ambient,
                         lighting.key.rgb, lighting.sky.rgb, lighting.ground.rgb);
#else
    vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * n.y);
    float diffuse = max(dot(n, pc.light.xyz), 0.0);
    vec3 lit = albedo.rgb * (ambient * hemi + (1.0 - ambient) * lighting.key.rgb * diffuse);
#endif
    out_colour = vec4(clamp(lit, 0.0, 1.0), albedo.a);
}
