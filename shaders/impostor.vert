#version 450
// Impostor vertex shader: one camera-facing quad (6 vertices, no index buffer) per instance of set 0
// binding 2 read as Impostor records (64 bytes, systems/render/crowd_renderer.hpp ImpostorInstance).
// The quad turns about the vertical axis to face the camera and spans the type's atlas cell in model
// units (push base_colour: x width, y bottom, z height), scaled by the instance's scale. The cell is the
// atlas direction nearest the camera's azimuth in the character's frame (local +Z forward) and the walk
// phase row (offsets.x directions, offsets.y phase rows; the last row is the standing pose, used when
// the phase is negative), in the band of views (offsets.w bands, systems/render/impostor_types.hpp) whose
// elevation is nearest the camera's above the pivot (the quad's centre, bottom + height / 2 above the origin;
// band 0 for a camera below it). Band 0's quad stands upright (foreshortened as the standing figure is); a band from
// above is drawn on a quad facing the camera, its cells (cells[1].x tall) stretched by impostor_band_stretch for the
// camera's elevation against the band's (depth ratio cells[1].y), so its silhouette is as tall as the figure's.
// The atlas is packed (systems/render/impostor_packing.hpp): one texel holds the colour and the normal of the same
// point, so its size is the baked image's width and half its height.
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
layout(std430, set = 1, binding = 0) readonly buffer Cells { vec4 cells[]; };  // [0]: texel grid, [1]: bands, then bounds

layout(location = 0) out vec2 v_uv;             // packed atlas texture coordinates
layout(location = 1) flat out vec4 v_colour;    // tint
layout(location = 2) flat out vec4 v_light_fade; // xyz: direction to the key light in the band's frame (x right,
                                                 // y up, z towards its bake camera: the atlas normals' frame), w: fade
layout(location = 3) flat out vec3 v_level;     // xy: the atlas's size in texels at mip z (the quad's level)
layout(location = 4) flat out vec2 v_up;        // world +Y in the band's frame (y, z): (cos a, sin a) of its elevation

const vec2 kCorners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

void main() {
    Impostor im = impostors[pc.offsets.z + uint(gl_InstanceIndex)];
    vec3 origin = im.position_scale.xyz;
    float scale = im.position_scale.w;
    vec4 grid = cells[0];
    vec3 pivot = origin + vec3(0.0, scale * (pc.base_colour.y + 0.5 * pc.base_colour.z), 0.0);
    vec3 d = pc.camera.xyz - pivot * pc.camera.w;  // the way to the eye (w 0: its direction, an eye at infinity)
    vec2 h = vec2(d.x, d.z);
    float level_distance = length(h);
    if (dot(h, h) < 1e-12) h = vec2(0.0, 1.0);
    h = normalize(h);
    vec3 toward = vec3(h.x, 0.0, h.y);
    vec3 right = vec3(h.y, 0.0, -h.x);  // cross(up, toward)
    // The band nearest the camera's elevation above the pivot: band e of n views from e x 90 / (n - 1) degrees.
    float bands = float(pc.offsets.w);
    float steps = max(bands - 1.0, 1.0);
    float seen = atan(d.y, level_distance);
    float band = clamp(floor(seen / 1.57079633 * steps + 0.5), 0.0, bands - 1.0);
    float baked = band * 1.57079633 / steps;
    vec2 cs = vec2(cos(baked), sin(baked));
    // The band's own frame (its bake camera's: the atlas normals' frame): vertical leant back by its elevation.
    vec3 band_up = cs.x * vec3(0.0, 1.0, 0.0) - cs.y * toward;
    vec3 band_facing = cs.x * toward + cs.y * vec3(0.0, 1.0, 0.0);
    // The quad: band 0 upright; a band from above facing the camera, stretched to the figure's height from there.
    vec3 up = vec3(0.0, 1.0, 0.0);
    float cell_height = pc.base_colour.z;
    if (band > 0.0) {
        vec4 banding = cells[1];
        seen = max(seen, 0.0);
        up = cos(seen) * vec3(0.0, 1.0, 0.0) - sin(seen) * toward;
        float k = banding.y;
        cell_height = banding.x * (cos(seen) + k * sin(seen)) / (cs.x + k * cs.y);
    }
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
    float row = band * rows + k;  // among every band's rows
    vec4 b = cells[2u + uint(row) * pc.offsets.x + uint(v)];
    if (b.z <= b.x) {  // empty cell: a degenerate quad
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    // Texels per pixel at the pivot's depth along the quad's vertical: atlas texels are (nearly) square in model
    // units and a quad faces the camera across, so only its height is foreshortened (band 0's upright quad by the
    // camera's elevation) and sets the lod. Its length on screen in pixels, whichever way it points there (a
    // camera looking down sees the vertical of a quad beside the view's centre across the screen): NDC x is
    // P11 / P00 times as many pixels as NDC y (the viewport's aspect; the rows of view_proj are the rigid view's
    // scaled by P00 and P11).
    vec4 c0 = pc.view_proj * vec4(pivot, 1.0);
    vec4 cy = pc.view_proj * vec4(pivot + up * (scale * cell_height), 1.0);
    float p00 = length(vec3(pc.view_proj[0][0], pc.view_proj[1][0], pc.view_proj[2][0]));
    float p11 = length(vec3(pc.view_proj[0][1], pc.view_proj[1][1], pc.view_proj[2][1]));
    vec2 span = cy.xy / cy.w - c0.xy / c0.w;
    float py = c0.w > 1e-6 && cy.w > 1e-6 ? length(vec2(span.x * p11 / p00, span.y)) * 0.5 * pc.base_colour.w : 1e6;  // cell height, px
    float rho = grid.y / max(py, 1e-3);
    float lod = clamp(log2(rho), 0.0, grid.z - 1.0);
    float level = floor(lod + 0.5);  // the nearest level, as a sampler's nearest-mip mode picks it
    // A texel of that level that passes the alpha test holds a covered texel of level 0 within its 2^level
    // footprint; one more texel for footprints that do not divide the cell evenly.
    vec2 pad = (exp2(level) + 1.0) / grid.xy;
    vec2 c = mix(max(b.xy - pad, 0.0), min(b.zw + pad, 1.0), kCorners[gl_VertexIndex]);
    vec3 world = pivot + scale * (right * ((c.x - 0.5) * pc.base_colour.x) + up * ((c.y - 0.5) * cell_height));
    v_uv = vec2((v + c.x) / dirs, (row + 1.0 - c.y) / (rows * bands));
    v_level = vec3(max(floor(vec2(grid.x * dirs, grid.y * rows * bands) / exp2(level)), 1.0), level);
    v_colour = im.colour;
    v_up = cs;
    // The band's frame (right, band_up, band_facing) is orthonormal, so lighting the atlas normal in it with the light
    // turned into it equals lighting the normal turned into the world (what shaders/lit_mesh.frag does).
    v_light_fade = vec4(dot(pc.light.xyz, right), dot(pc.light.xyz, band_up), dot(pc.light.xyz, band_facing), im.forward_phase.w);
    gl_Position = pc.view_proj * vec4(world, 1.0);
}
