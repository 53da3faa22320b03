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
// views, two walk phases and/or two bands of views (the weights not 0), up to four cells are read (a second band's where
// the eye's ray meets its quad), each alpha-tested and lit in its view's frame, and blended where they cover the
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
#ifdef BLEND  // shaders/impostor.vert: v_uv is the point in the first band's cell (0 to 1 across it)
layout(location = 5) in vec3 v_cell1;        // the point in the second band's cell, times z
layout(location = 6) flat in vec4 v_base;    // x: the first view's left edge; y, z: the first phase's top edge in each band
layout(location = 7) flat in vec4 v_step;    // x, y: the second view's and phase's offset; z, w: a cell's size
layout(location = 8) flat in vec4 v_weights; // the tetrahedron's four corners' weights
layout(location = 9) flat in uvec2 v_corners; // its second and third corners (axis bits: 1 view, 2 phase, 4 band)
layout(location = 10) flat in vec2 v_up1;    // world +Y in the second band's frame
layout(location = 11) flat in vec3 v_light1; // the light in the frame of the second view, first band
layout(location = 12) flat in vec3 v_light2; // first view, second band
layout(location = 13) flat in vec3 v_light3; // second view, second band
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
vec3 shade(vec4 c, vec4 e, vec3 light, vec2 up) {
    vec3 nb = e.a > 0.0 ? e.rgb / e.a * 2.0 - 1.0 : vec3(0.0, 0.0, 1.0);
    vec3 n = normalize(nb);
    vec3 albedo = c.rgb / c.a * v_colour.rgb;
    float ambient = pc.light.w;
    vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * (n.y * up.x + n.z * up.y));  // world N.y
    float diffuse = max(dot(n, light), 0.0);
    vec3 lit = albedo * (ambient * hemi + (1.0 - ambient) * lighting.key.rgb * diffuse);
    const float lit_share = e.a >= c.a - 1.5 / 255.0 ? 1.0 : e.a / c.a;
    return clamp(mix(albedo, lit, lit_share), 0.0, 1.0);
}

#ifdef BLEND
// The packed texel this pixel reads at the (view, phase, band) corner `a` (axis bits: 1 the second view, 2 the second
// phase, 4 the second band, whose cell is read where the eye's ray meets its quad); false where the pixel lies past
// that corner's cell (not covered there).
bool corner_texel(uint a, out uvec2 packed) {
    packed = uvec2(0u);
    bool second_band = (a & 4u) != 0u;
    vec2 c = second_band ? v_cell1.xy / v_cell1.z : v_uv;
    if (any(lessThan(c, vec2(0.0))) || any(greaterThan(c, vec2(1.0)))) return false;
    vec2 uv = vec2(v_base.x + c.x * v_step.z + ((a & 1u) != 0u ? v_step.x : 0.0),
                   (second_band ? v_base.z : v_base.y) - c.y * v_step.w + ((a & 2u) != 0u ? v_step.y : 0.0));
    packed = fetch(uv);
    return true;
}

// The colour corner `a`'s picture shows at this pixel, lit with the light and the world up in its view's and band's
// frame, where that picture covers the pixel (alpha-tested at one half, a sharp silhouette of its own); false
// elsewhere.
bool corner_colour(uint a, out vec3 shown) {
    shown = vec3(0.0);
    uvec2 packed;
    if (!corner_texel(a, packed)) return false;
    vec4 colour = unpackUnorm4x8(packed.x);
    if (colour.a < 0.5) return false;
    uint k = (a & 1u) | ((a & 4u) >> 1u);  // (view, band): 00, 10, 01, 11
    vec3 light = k == 0u ? v_light_fade.xyz : k == 1u ? v_light1 : k == 2u ? v_light2 : v_light3;
    shown = shade(colour, unpackUnorm4x8(packed.y), light, (a & 4u) != 0u ? v_up1 : v_up);
    return true;
}
#endif

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
    out_colour = vec4(shade(c, unpackUnorm4x8(packed.y), v_light_fade.xyz, v_up), v_colour.a);
#else
    // Up to four of the eight cells (two views x two phases x two bands; a weight 0 leaves its cell out), each
    // alpha-tested at one half as the one cell is (a sharp silhouette of its own) and lit in its own view's frame. The
    // pixel shows the weighted mean of the pictures that cover it, where their share of the weights passes a screen
    // door (the transposed Bayer threshold, apart from the fade's): covered by all, always; by a picture of weight w
    // alone, at a share w of the pixels. Blending coverage and testing it at one half instead would keep each
    // silhouette whole until half-way and then swap it whole. A separate pipeline (lavapipe runs both sides of a
    // branch a 4x4 block's pixels take differently, and does not know the weights are the same for all).
    ivec2 q = ivec2(gl_FragCoord.xy) & 3;
    float door = (kBayer[q.x * 4 + q.y] + 0.5) / 16.0;
    // The four corners of the weights' tetrahedron (shaders/impostor.vert): (0, 0, 0), then the axes in the order of
    // their weights.
    uint corner[4] = uint[](0u, v_corners.x, v_corners.y, 7u);
#ifdef PICK
    // One picture a pixel (the impostor_pick pipeline: one atlas read, as the nearest's): the corner whose share of
    // the cumulative weights holds the pixel's door threshold. Where both pictures cover a pixel it shows one of them
    // (a 4 x 4 dither of the two whose mean is the blend's); where one alone covers it, at a share of the pixels equal
    // to its weight, as the blend does.
    float below = v_weights.x, next = v_weights.x + v_weights.y, last = next + v_weights.z;
    vec3 shown;
    if (!corner_colour(corner[door < below ? 0 : door < next ? 1 : door < last ? 2 : 3], shown)) discard;
    out_colour = vec4(shown, v_colour.a);
#else
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 4; ++i) {
        float w = v_weights[i];
        vec3 shown;
        if (w <= 0.0 || !corner_colour(corner[i], shown)) continue;
        sum += w * vec4(shown, 1.0);
    }
    if (sum.a <= door) discard;
    out_colour = vec4(sum.rgb / sum.a, v_colour.a);
#endif
#endif
}
