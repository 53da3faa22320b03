#version 450
// Vertex-lit fragment shader: the light shaders/lit_mesh.vert (built with VERTEX_LIT) computed at the vertices,
// interpolated, times the base colour texture in textured mode (offsets.w & 2), clamped to [0, 1] as
// shaders/lit_mesh.frag does. Two interpolants instead of three and no lighting per pixel: for characters
// small on screen, where lavapipe's cost per triangle dominates (docs/PERFORMANCE.md). Built again with
// DITHER: the screen-door fade of shaders/lit_mesh.frag (pixels whose 4x4 Bayer value is below offsets.w >> 8,
// or with bit 13 the others). Of the material maps only the emissive one is drawn here (offsets.w & 32, added after
// the light); normal and occlusion maps need the per-pixel normal and ambient term.
// The emissive map's code is only in the MATERIAL_MAPS build (gpu::LitVariant::Maps).

layout(push_constant) uniform Push {
    mat4 view_proj;
    vec4 light;
    vec4 camera;
    uvec4 offsets;
    vec4 base_colour;
} pc;

layout(set = 1, binding = 1) uniform sampler2D base_colour_texture;
#ifdef MATERIAL_MAPS
layout(set = 1, binding = 4) uniform sampler2D emissive_texture;
#endif

layout(location = 0) in vec4 v_lit;
layout(location = 1) in vec2 v_uv;
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
    vec4 lit = v_lit;
    if ((pc.offsets.w & 2u) != 0u) lit *= texture(base_colour_texture, v_uv);
#ifdef DITHER
    // Alpha test (gpu::lit_alpha_bits), as shaders/lit_mesh.frag.
    if ((pc.offsets.w & 0x4000u) != 0u && lit.a < float(pc.offsets.w >> 16) / 65535.0) discard;
#endif
#ifdef MATERIAL_MAPS
    if ((pc.offsets.w & 32u) != 0u) lit.rgb += texture(emissive_texture, v_uv).rgb;  // emissive (gpu::kLitEmissive)
#endif
    out_colour = vec4(clamp(lit.rgb, 0.0, 1.0), lit.a);
}
