#version 450
// Impostor fragment shader: alpha-tested atlas albedo (premultiplied by coverage, so mip levels
// averaged with the empty background are divided back) times the tint, read unfiltered (texelFetch) from
// the one mip level the vertex shader chose for the whole quad (on lavapipe a filtered texture() with its
// per-pixel level costs about twice as much: docs/PERFORMANCE.md), lit as shaders/lit_mesh.frag lights a
// mesh, with the normal decoded from the atlas's bottom half (stored in the bake camera's
// frame: x right, y up, z towards the camera) and turned into the quad's world frame. Fade (a
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
layout(set = 1, binding = 1) uniform sampler2D atlas;

layout(location = 0) in vec2 v_uv;
layout(location = 1) flat in vec4 v_colour;
layout(location = 2) flat in vec4 v_right_fade;
layout(location = 3) flat in vec3 v_toward;
layout(location = 4) flat in vec3 v_level;   // xy: the atlas's size in texels at mip z (chosen per quad)
layout(location = 0) out vec4 out_colour;

const float kBayer[16] = float[](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

void main() {
    float fade = v_right_fade.w;
    if (fade < 1.0) {
        ivec2 p = ivec2(gl_FragCoord.xy) & 3;
        float t = (kBayer[p.y * 4 + p.x] + 0.5) / 16.0;
        if (fade >= 0.0 ? t >= fade : t < -fade) discard;
    }
    ivec2 texel = ivec2(v_uv * v_level.xy);
    int level = int(v_level.z);
    vec4 c = texelFetch(atlas, texel, level);
    if (c.a < 0.5) discard;
    vec4 e = texelFetch(atlas, texel + ivec2(0, int(v_level.y) / 2), level);
    vec3 nb = e.a > 0.0 ? e.rgb / e.a * 2.0 - 1.0 : vec3(0.0, 0.0, 1.0);
    vec3 n = normalize(v_right_fade.xyz * nb.x + vec3(0.0, nb.y, 0.0) + v_toward * nb.z);
    vec3 albedo = c.rgb / c.a * v_colour.rgb;
    float ambient = pc.light.w;
    vec3 hemi = mix(lighting.ground.rgb, lighting.sky.rgb, 0.5 + 0.5 * n.y);
    float diffuse = max(dot(n, pc.light.xyz), 0.0);
    vec3 lit = albedo * (ambient * hemi + (1.0 - ambient) * lighting.key.rgb * diffuse);
    out_colour = vec4(clamp(lit, 0.0, 1.0), v_colour.a);
}
