#version 450
// Impostor vertex shader: one camera-facing quad (6 vertices, no index buffer) per instance of set 0
// binding 2 read as Impostor records (64 bytes, systems/render/crowd_renderer.hpp ImpostorInstance).
// The quad turns about the vertical axis to face the camera and spans the type's atlas cell in model
// units (push base_colour: x width, y bottom, z height), scaled by the instance's scale. The cell is the
// atlas direction nearest the camera's azimuth in the character's frame (local +Z forward) and the walk
// phase row (offsets.x directions, offsets.y phase rows; the last row is the standing pose, used when
// the phase is negative). The atlas is packed (systems/render/impostor_packing.hpp): one texel holds the
// colour and the normal of the same point, so its size is the baked image's width and half its height.
// The quad covers only the cell's silhouette (set 1 binding 0, systems/render/crowd_renderer.hpp
// impostor_cell_table), padded by a texel of the mip level the quad's screen size calls for (log2 of atlas
// texels per pixel, rounded: v_level), so that the coarser level's wider silhouette is not cut.

struct Impostor {
    vec4 position_scale;  // xyz: character origin (world), w: uniform scale
    vec4 forward_phase;   // xy: world xz of the character's local +Z, z: walk phase [0,1) or < 0 standing, w: fade
    vec4 colour;          // tint (multiplies the atlas albedo)
    uvec4 atlas;          // x: atlas id (the draw's), unused here
};
layout(std430, set = 0, binding = 2) readonly buffer Impostors { Impostor impostors[]; };

layout(push_constant) uniform Push {
    mat4 view_proj;
    vec4 light;
    vec4 camera;
    uvec4 offsets;      // x: directions, y: rows (phases + 1 standing), z: first instance, w: mode
    vec4 base_colour;   // x: quad width, y: quad bottom, z: quad height (model units), w: viewport height (px)
} pc;
layout(std430, set = 1, binding = 0) readonly buffer Cells { vec4 cells[]; };  // [0]: texel grid, then bounds

layout(location = 0) out vec2 v_uv;             // packed atlas texture coordinates
layout(location = 1) flat out vec4 v_colour;    // tint
layout(location = 2) flat out vec4 v_light_fade; // xyz: direction to the key light in the quad's frame (x right,
                                                 // y up, z towards the camera: the atlas normals' frame), w: fade
layout(location = 3) flat out vec3 v_level;     // xy: the atlas's size in texels at mip z (the quad's level)

const vec2 kCorners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

void main() {
    Impostor im = impostors[pc.offsets.z + uint(gl_InstanceIndex)];
    vec3 origin = im.position_scale.xyz;
    float scale = im.position_scale.w;
    vec3 d = pc.camera.xyz - origin;
    vec2 h = vec2(d.x, d.z);
    if (dot(h, h) < 1e-12) h = vec2(0.0, 1.0);
    h = normalize(h);
    vec3 toward = vec3(h.x, 0.0, h.y);
    vec3 right = vec3(h.y, 0.0, -h.x);  // cross(up, toward)
    // Camera azimuth in the character's frame: local x = (f.y, -f.x), local z = f (xz components).
    vec2 f = im.forward_phase.xy;
    float lx = h.x * f.y - h.y * f.x;
    float lz = h.x * f.x + h.y * f.y;
    float dirs = float(pc.offsets.x);
    float alpha = atan(lx, lz);  // (-pi, pi]
    float v = mod(floor(alpha / 6.28318531 * dirs + 0.5), dirs);
    float rows = float(pc.offsets.y);
    float phase = im.forward_phase.z;
    float k = phase < 0.0 ? rows - 1.0 : mod(floor(phase * (rows - 1.0) + 0.5), rows - 1.0);
    vec4 b = cells[1u + uint(k) * pc.offsets.x + uint(v)];
    if (b.z <= b.x) {  // empty cell: a degenerate quad
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    // Texels per pixel at the origin's depth, vertically: atlas texels are square in model units and a quad
    // faces the camera across, so only its height is foreshortened (by the camera's pitch) and sets the lod.
    vec4 grid = cells[0];
    vec3 centre = origin + vec3(0.0, scale * (pc.base_colour.y + 0.5 * pc.base_colour.z), 0.0);
    vec4 c0 = pc.view_proj * vec4(centre, 1.0);
    vec4 cy = pc.view_proj * vec4(centre + vec3(0.0, scale * pc.base_colour.z, 0.0), 1.0);
    float py = c0.w > 1e-6 && cy.w > 1e-6 ? abs(cy.y / cy.w - c0.y / c0.w) * 0.5 * pc.base_colour.w : 1e6;  // cell height, px
    float rho = grid.y / max(py, 1e-3);
    float lod = clamp(log2(rho), 0.0, grid.z - 1.0);
    float level = floor(lod + 0.5);  // the nearest level, as a sampler's nearest-mip mode picks it
    // A texel of that level that passes the alpha test holds a covered texel of level 0 within its 2^level
    // footprint; one more texel for footprints that do not divide the cell evenly.
    vec2 pad = (exp2(level) + 1.0) / grid.xy;
    vec2 c = mix(max(b.xy - pad, 0.0), min(b.zw + pad, 1.0), kCorners[gl_VertexIndex]);
    vec3 world = origin + scale * (right * (c.x - 0.5) * pc.base_colour.x + vec3(0.0, pc.base_colour.y + c.y * pc.base_colour.z, 0.0));
    v_uv = vec2((v + c.x) / dirs, (k + 1.0 - c.y) / rows);
    v_level = vec3(max(floor(vec2(grid.x * dirs, grid.y * rows) / exp2(level)), 1.0), level);
    v_colour = im.colour;
    // The quad's frame (right, up, toward) is orthonormal, so lighting the atlas normal in it with the light
    // turned into it equals lighting the normal turned into the world (what shaders/lit_mesh.frag does).
    v_light_fade = vec4(dot(pc.light.xyz, right), pc.light.y, dot(pc.light.xyz, toward), im.forward_phase.w);
    gl_Position = pc.view_proj * vec4(world, 1.0);
}
