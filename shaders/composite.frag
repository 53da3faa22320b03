#version 450
// Composite fragment shader: the layer (set 0: binding 0 its colour, drawn at half this target's resolution
// with transparent black where it is empty, so its filtered colour is premultiplied by coverage; binding 1 its
// depth) read with bilinear filtering at this pixel's centre and alpha-tested at half coverage: the silhouette
// follows the interpolated coverage (smooth, not in 2 x 2 blocks) and what is kept is opaque, its colour
// divided back. (Blending the filtered coverage instead left thin limbs, one layer texel wide, half
// transparent.) Its depth is the nearest of the four layer texels the filter read, so the far crowd is
// depth-tested against everything drawn at full resolution as if it were drawn there.

layout(push_constant) uniform Push {
    mat4 view_proj;
    vec4 light;
    vec4 camera;        // xy: 0.5 / the layer's size in texels
    uvec4 offsets;
    vec4 base_colour;
} pc;

layout(set = 0, binding = 0) uniform sampler2D layer;
layout(set = 0, binding = 1) uniform sampler2D layer_depth;
layout(location = 0) out vec4 out_colour;

void main() {
    vec2 uv = gl_FragCoord.xy * pc.camera.xy;
    vec4 c = texture(layer, uv);
    if (c.a < 0.5) discard;
    vec4 d = textureGather(layer_depth, uv, 0);
    gl_FragDepth = min(min(d.x, d.y), min(d.z, d.w));
    out_colour = vec4(c.rgb / c.a, 1.0);
}
