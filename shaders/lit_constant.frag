#version 450
// Constant-colour fragment shader for profiling (RendererOptions::constant_fragments): writes the
// albedo unlit, reading one flat input instead of three, no texture and no lighting. Drawing with it
// separates the fragment cost from the vertex and binning cost of the lit pipeline (docs/PERFORMANCE.md).

// The per-pixel vertex shader's other outputs, declared so the interfaces match (validation warns of outputs no
// input consumes) and never read: the driver drops unread inputs when it links the stages.
layout(location = 0) in vec4 v_normal_u;
layout(location = 1) in vec4 v_world_v;
layout(location = 2) flat in vec4 v_colour;
layout(location = 0) out vec4 out_colour;

void main() {
    out_colour = v_colour;
}
