#version 450
// Impostor fragment shader: alpha-tested atlas albedo (premultiplied by coverage, so mip levels
// averaged with the empty background are divided back) times the tint, read unfiltered (texelFetch) from
// the one mip level the vertex shader chose for the whole quad (on lavapipe a filtered texture() with its
// per-pixel level costs about twice as much: docs/PERFORMANCE.md), lit as shaders/lit_mesh.frag lights a
// mesh. One fetch reads colour and normal (the packed atlas: systems/render/impostor_packing.hpp); the
// normal is in its band's bake camera's frame (x right, y up, z towards that camera), and is lit there with the
// light the vertex shader turned into that frame (and the hemisphere by world +Y in it: a band seen from above
// looks down at the figure). Unlit materials (KHR_materials_unlit) bake no
// normal (zero, alpha 0: shaders/lit_mesh.frag), so the normal's alpha over the colour's is the share of lit
// surface in the texel, exact through the bake's averaging and the mip chain: the albedo is shown as it is in
// that proportion. Within 1.5/255 of 1 (the two halves' independent 8-bit rounding) the texel is all lit. Fade (a
// screen-door dither over a 4x4 Bayer matrix): fade f > 0 shows the pixels whose threshold is below f,
// f < 0 the complement of -f's pixels (the other side of a cross-fade with a mesh dithered at -f).

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
layout(set = 1, binding = 1) uniform usampler2D atlas;  // x: colour, y: normal, 4 x 8 bits each

layout(location = 0) in vec2 v_uv;
layout(location = 1) flat in vec4 v_colour;
layout(location = 2) flat in vec4 v_light_fade;  // xyz: light direction in the band's frame, w: fade
layout(location = 3) flat in vec3 v_level;   // xy: the atlas's size in texels at mip z (chosen per quad)
layout(location = 4) flat in vec2 v_up;      // world +Y in the band's frame (y, z components)
layout(location = 0) out vec4 out_colour;

const float kBayer[16] = float[](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

void main() {
    float fade = v_light_fade.w;
    if (fade < 1.0) {
        ivec2 p = ivec2(gl_FragCoord.xy) & 3;
        float t = (kBayer[p.y * 4 + p.x] + 0.5) / 16.0;
        if (fade >= 0.0 ? t >= fade : t < -fade) discard;
    }
    ivec2 size = ivec2(v_level.xy);
    uvec2 packed = texelFetch(atlas, min(ivec2(v_uv * v_level.xy), size - 1), int(v_level.z)).xy;
    vec4 c = unpackUnorm4x8(packed.x);
    if (c.a < 0.5) discard;
    vec4 e = unpackUnorm4x8(packed.y);
    vec3 nb = e.a > 0.0 ? e.rgb / e.a * 2.0 - 1.0 : vec3(0.0, 0.0, 1.0);
    vec3 n = normalize(nb);
    vec3 albedo = c.rgb / c.a * v_colour.rgb;
    float ambient = pc.light.w;
    vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * (n.y * v_up.x + n.z * v_up.y));  // world N.y
    float diffuse = max(dot(n, v_light_fade.xyz), 0.0);
    vec3 lit = albedo * (ambient * hemi + (1.0 - ambient) * lighting.key.rgb * diffuse);
    const float lit_share = e.a >= c.a - 1.5 / 255.0 ? 1.0 : e.a / c.a;
    out_colour = vec4(clamp(mix(albedo, lit, lit_share), 0.0, 1.0), v_colour.a);
}
