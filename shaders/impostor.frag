#version 450
// Impostor fragment shader: alpha-tested atlas albedo (tested against push offsets.w >> 8 255ths of coverage: one half
// at full resolution, less in the far layers, impostor_alpha_test_bits; premultiplied by coverage, so mip levels
// averaged with the empty background are divided back) times the tint, read unfiltered (texelFetch) from
// the one mip level the vertex shader chose for the whole quad (on lavapipe a filtered texture() with its
// per-pixel level costs about twice as much: docs/PERFORMANCE.md), lit as shaders/lit_mesh.frag lights a
// mesh. One fetch reads colour and normal (the packed atlas: systems/render/impostor_packing.hpp); the
// normal is in its view's bake camera's frame (x right, y up, z towards that camera), and is lit there with the
// light the vertex shader turned into that frame (and the hemisphere by world +Y in it: a band seen from above
// looks down at the figure). Compiled with BLEND (the impostor_blend pipeline), where the vertex shader blends two
// views and/or two walk phases (v_blend's weights not 0), up to three cells are read, each alpha-tested and lit in its view's frame, and blended where they cover the
// pixel, the silhouettes cross-fading by a screen door (below). Unlit materials (KHR_materials_unlit) bake no
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
#ifdef BLEND
layout(location = 5) flat in vec4 v_blend;   // x, y: the second view's and phase's offset from v_uv; z, w: their weights
layout(location = 6) flat in vec3 v_light1;  // the light in the second view's frame
#endif
layout(location = 0) out vec4 out_colour;

const float kBayer[16] = float[](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

// The texel of the packed atlas at texture coordinates `uv` in the quad's level: colour (x) and normal (y).
uvec2 fetch(vec2 uv) {
    ivec2 size = ivec2(v_level.xy);
    return texelFetch(atlas, min(ivec2(uv * v_level.xy), size - 1), int(v_level.z)).xy;
}

// The colour shown for atlas colour `c` (coverage in alpha, > 0) and normal `e` lit with `light` (in the normal's
// frame): the albedo times the tint, lit in the share of the texel that is lit surface.
vec3 shade(vec4 c, vec4 e, vec3 light) {
    vec3 nb = e.a > 0.0 ? e.rgb / e.a * 2.0 - 1.0 : vec3(0.0, 0.0, 1.0);
    vec3 n = normalize(nb);
    vec3 albedo = c.rgb / c.a * v_colour.rgb;
    float ambient = pc.light.w;
    vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * (n.y * v_up.x + n.z * v_up.y));  // world N.y
    float diffuse = max(dot(n, light), 0.0);
    vec3 lit = albedo * (ambient * hemi + (1.0 - ambient) * lighting.key.rgb * diffuse);
    const float lit_share = e.a >= c.a - 1.5 / 255.0 ? 1.0 : e.a / c.a;
    return clamp(mix(albedo, lit, lit_share), 0.0, 1.0);
}

void main() {
    float fade = v_light_fade.w;
    if (fade < 1.0) {
        ivec2 p = ivec2(gl_FragCoord.xy) & 3;
        float t = (kBayer[p.y * 4 + p.x] + 0.5) / 16.0;
        if (fade >= 0.0 ? t >= fade : t < -fade) discard;
    }
#ifndef BLEND
    uvec2 packed = fetch(v_uv);
    vec4 c = unpackUnorm4x8(packed.x);
    if (c.a < float(pc.offsets.w >> 8u) / 255.0) discard;  // the alpha test's threshold (one half; less in the far layers)
    out_colour = vec4(shade(c, unpackUnorm4x8(packed.y), v_light_fade.xyz), v_colour.a);
#else
    // Up to three of the four cells (two views x two phases; a weight 0 leaves its cell out), each alpha-tested at one
    // half as the one cell is (a sharp silhouette of its own) and lit in its own view's frame. The pixel shows the weighted mean of
    // the pictures that cover it, where their share of the weights passes a screen door (the transposed Bayer
    // threshold, apart from the fade's): covered by all, always; by a picture of weight w alone, at a share w of the
    // pixels. Blending coverage and testing it at one half instead would keep each silhouette whole until half-way and
    // then swap it whole. A separate pipeline (lavapipe runs both sides of a branch a 4x4 block's pixels take
    // differently, and does not know v_blend is the same for all).
    ivec2 q = ivec2(gl_FragCoord.xy) & 3;
    float door = (kBayer[q.x * 4 + q.y] + 0.5) / 16.0;
    // The three cells of the (view, phase) weights' triangle: the square's corners (0, 0), (1, 0) or (0, 1), (1, 1) with
    // barycentric weights (1 - max, |wv - wk|, min), linear in the weights and the same either side of the diagonal.
    float wv = v_blend.z, wk = v_blend.w;
    bool views_first = wv >= wk;  // the triangle under the diagonal: the second view before the second phase
    vec2 corner_uv[3] = vec2[](vec2(0.0), views_first ? vec2(v_blend.x, 0.0) : vec2(0.0, v_blend.y), v_blend.xy);
    float corner_weight[3] = float[](1.0 - max(wv, wk), abs(wv - wk), min(wv, wk));
    vec3 corner_light[3] = vec3[](v_light_fade.xyz, views_first ? v_light1 : v_light_fade.xyz, v_light1);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 3; ++i) {
        float w = corner_weight[i];
        if (w <= 0.0) continue;
        uvec2 packed = fetch(v_uv + corner_uv[i]);
        vec4 c = unpackUnorm4x8(packed.x);
        if (c.a < 0.5) continue;
        sum += w * vec4(shade(c, unpackUnorm4x8(packed.y), corner_light[i]), 1.0);
    }
    if (sum.a <= door) discard;
    out_colour = vec4(sum.rgb / sum.a, v_colour.a);
#endif
}
