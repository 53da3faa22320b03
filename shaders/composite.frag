#version 450
// Composite fragment shader: the layer (set 1 binding 1, drawn at half this target's resolution with
// transparent black where it is empty, so its filtered colour is premultiplied by coverage) read with
// bilinear filtering at this pixel's centre and alpha-tested at half coverage: the silhouette follows the
// interpolated coverage (smooth, not in 2 x 2 blocks) and what is kept is opaque, its colour divided back.
// (Blending the filtered coverage instead left thin limbs, one layer texel wide, half transparent.)

layout(push_constant) uniform Push {
    mat4 view_proj;
    vec4 light;
    vec4 camera;        // xy: 0.5 / the layer's size in texels
    uvec4 offsets;
    vec4 base_colour;
} pc;

layout(set = 1, binding = 1) uniform sampler2D layer;
layout(location = 0) out vec4 out_colour;

void main() {
    vec4 c = texture(layer, gl_FragCoord.xy * pc.camera.xy);
    if (c.a < 0.5) discard;
    out_colour = vec4(c.rgb / c.a, 1.0);
}
