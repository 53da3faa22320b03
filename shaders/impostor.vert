#version 450
// Impostor vertex shader: one camera-facing quad (6 vertices, no index buffer) per instance of set 0
// binding 2 read as Impostor records (64 bytes, systems/render/crowd_renderer.hpp ImpostorInstance).
// The quad turns about the vertical axis to face the camera and spans the type's atlas cell in model
// units (push base_colour: x width, y bottom, z height), scaled by the instance's scale. It shows the atlas
// directions about the camera's azimuth in the character's frame (local +Z forward) and the walk phase rows about
// the character's phase (offsets.x directions, offsets.y phase rows, a cycle; the last row is the standing pose,
// used when the phase is negative), in the band of views (offsets.w & 255 bands, systems/render/impostor_types.hpp)
// whose elevation is nearest the camera's above the pivot (the quad's centre, bottom + height / 2 above the origin;
// band 0 for a camera below it): the nearest of each, or compiled with BLEND (the impostor_blend pipeline) the two of
// each either side, blended by where the camera's azimuth and elevation and the phase lie between them (four of the
// eight cells, the weights' tetrahedron: shaders/impostor.frag), fading in from quads offsets.w >> 8 px tall (the
// nearest) to twice that. The blend draws the lower band's quad and reads the upper band's cells where the eye's
// ray through each point meets the upper band's quad (across()). Band 0's quad stands upright (foreshortened
// as the standing figure is); a band from above is drawn on a quad facing the camera, its cells (cells[1].x tall)
// stretched by impostor_band_stretch for the camera's elevation against the band's (depth ratio cells[1].y), so its
// silhouette is as tall as the figure's.
// The atlas is packed (systems/render/impostor_packing.hpp): one texel holds the colour and the normal of the same
// point, so its size is the baked image's width and half its height.
// The quad covers only the shown cells' silhouettes (set 1 binding 0, systems/render/crowd_renderer.hpp
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
    uvec4 offsets;      // x: directions, y: rows (phases + 1 standing), z: first instance, w: bands | upper << 8, upper
                        // with BLEND the blend's fade-in size (px), else the fragment shader's alpha test (255ths)
                        // (impostor_mode_bits, systems/render/impostor_types.hpp)
    vec4 base_colour;   // x: quad width, y: quad bottom, z: quad height (model units), w: viewport height (px)
} pc;
layout(std430, set = 1, binding = 0) readonly buffer Cells { vec4 cells[]; };  // [0]: texel grid, [1]: bands, then bounds

layout(location = 0) out vec2 v_uv;             // packed atlas texture coordinates
layout(location = 1) flat out vec4 v_colour;    // tint
layout(location = 2) flat out vec4 v_light_fade; // xyz: direction to the key light in the band's frame (x right,
                                                 // y up, z towards its bake camera: the atlas normals' frame), w: fade
layout(location = 3) flat out vec3 v_level;     // xy: the atlas's size in texels at mip z (the quad's level)
layout(location = 4) flat out vec2 v_up;        // world +Y in the band's frame (y, z): (cos a, sin a) of its elevation
#ifdef BLEND
// With BLEND, v_uv is the point's coordinates in the first band's cell (0 to 1 across it), and:
layout(location = 5) out vec3 v_cell1;          // the point's coordinates in the second band's cell (xy), times z
                                                 // (across(): divided by z, exact over the quad)
layout(location = 6) flat out vec4 v_base;      // x: the first view's left edge (texture u), y, z: the first phase's
                                                 // top edge in the first and second band (texture v)
layout(location = 7) flat out vec4 v_step;      // x, y: the second view's and phase's offset (texture u, v); z, w: a
                                                 // cell's size (texture u, v)
layout(location = 8) flat out vec4 v_weights;   // the weights of the tetrahedron's four corners
layout(location = 9) flat out uvec2 v_corners; // its second and third corners (axis bits: 1 view, 2 phase, 4 band)
layout(location = 10) flat out vec2 v_up1;      // as v_up, in the second band's frame
layout(location = 11) flat out vec3 v_light1;   // the light in the frame of the second view, first band
layout(location = 12) flat out vec3 v_light2;   // first view, second band
layout(location = 13) flat out vec3 v_light3;   // second view, second band
#endif

const vec2 kCorners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

// The key light in the frame of the view baked from `view` directions of `dirs` in the character's frame (local x
// `local_x`, local z `f`, world xz), in band `cs` (cos, sin of its elevation): that view's normals' frame (right,
// band_up, band_facing of its bake camera). The frame is orthonormal, so lighting the atlas normal with the light
// turned into it equals lighting the normal turned into the world (what shaders/lit_mesh.frag does).
vec3 light_in_view(float view, float dirs, vec2 local_x, vec2 f, vec2 cs) {
    float a = view * 6.28318531 / dirs;
    vec2 hv = normalize(sin(a) * local_x + cos(a) * f);
    vec3 toward = vec3(hv.x, 0.0, hv.y);
    vec3 band_up = cs.x * vec3(0.0, 1.0, 0.0) - cs.y * toward;
    vec3 band_facing = cs.x * toward + cs.y * vec3(0.0, 1.0, 0.0);
    return vec3(dot(pc.light.xyz, vec3(hv.y, 0.0, -hv.x)), dot(pc.light.xyz, band_up), dot(pc.light.xyz, band_facing));
}

#ifdef BLEND
// How far a blend weight w between two baked pictures is kept (sharpness s in [0, 1]): s 1 keeps w, s 0 snaps to the
// nearer picture (w >= 0.5: the second), between them a linear ramp of width s about one half.
float sharpen(float w, float s) {
    return s > 0.0 ? clamp((w - 0.5) / s + 0.5, 0.0, 1.0) : step(0.5, w);
}

// Grows `box` (cell-space bounds x0, y0, x1, y1; empty while x1 <= x0) to hold the cell bounds `b` (empty likewise).
void include_cell(inout vec4 box, vec4 b) {
    if (b.z > b.x) box = box.z > box.x ? vec4(min(box.xy, b.xy), max(box.zw, b.zw)) : b;
}
#endif

// Band `b`'s quad seen from elevation `seen` (radians, >= 0 for a band from above): its vertical on the quad `up`
// (band 0 upright; a band from above facing the camera, whose level direction towards the eye is `toward`) and
// its height in model units (a band from above stretched to the figure's height from `seen`, impostor_band_stretch).
void band_quad(float b, float steps, float seen, vec3 toward, out vec3 up, out float height) {
    up = vec3(0.0, 1.0, 0.0);
    height = pc.base_colour.z;
    if (b > 0.0) {
        vec4 banding = cells[1];
        float baked = b * 1.57079633 / steps;
        float s = max(seen, 0.0);
        up = cos(s) * vec3(0.0, 1.0, 0.0) - sin(s) * toward;
        height = banding.x * (cos(s) + banding.y * sin(s)) / (cos(baked) + banding.y * sin(baked));
    }
}

#ifdef BLEND
// Where the eye's ray through cell point `c` of one band's quad (its vertical `up_from`, height `h_from`) meets the
// plane of another's (`up_to`, `h_to`): that point's cell coordinates on the other quad (xy), and z the reciprocal of
// the ray's parameter there (the eye at 0, the first point at 1; 1 for an eye at infinity). Both quads are centred
// on the pivot and share its horizontal line `right` (so the map from one to the other is a projective one:
// (xy z, z) is linear over the first quad, which its perspective-correct interpolation keeps exact).
vec3 across(vec2 c, vec3 pivot, vec3 right, float scale, vec3 up_from, float h_from, vec3 up_to, float h_to) {
    float w = pc.base_colour.x;
    vec3 p = pivot + scale * (right * ((c.x - 0.5) * w) + up_from * ((c.y - 0.5) * h_from));
    vec3 n = cross(right, up_to);  // the other plane's normal
    vec3 ray = pc.camera.w > 0.0 ? p - pc.camera.xyz : -pc.camera.xyz;  // from the eye through p
    float along = dot(ray, n);
    float mu = abs(along) > 1e-9 ? -dot(p - pivot, n) / along : 0.0;
    vec3 q = p + mu * ray - pivot;
    float inverse = pc.camera.w > 0.0 ? 1.0 / max(1.0 + mu, 1e-6) : 1.0;
    return vec3(dot(q, right) / (scale * w) + 0.5, dot(q, up_to) / (scale * h_to) + 0.5, inverse);
}

// Grows `box` by the cell bounds `b` of another band's quad (as across() maps them onto the drawn quad).
void include_band_cell(inout vec4 box, vec4 b, vec3 pivot, vec3 right, float scale, vec3 up_from, float h_from, vec3 up_to,
                       float h_to) {
    if (b.z <= b.x) return;
    vec2 p0 = across(b.xy, pivot, right, scale, up_from, h_from, up_to, h_to).xy;
    vec2 p1 = across(b.zy, pivot, right, scale, up_from, h_from, up_to, h_to).xy;
    vec2 p2 = across(b.xw, pivot, right, scale, up_from, h_from, up_to, h_to).xy;
    vec2 p3 = across(b.zw, pivot, right, scale, up_from, h_from, up_to, h_to).xy;
    include_cell(box, vec4(min(min(p0, p1), min(p2, p3)), max(max(p0, p1), max(p2, p3))));
}

// Grows the bounds of the cells read, `first` (the first band's) or `second`, by the cell of corner `a` (axis bits: 1
// the second view v1, 2 the second phase, 4 the second band; rows: the cells' atlas rows for (band, phase) 00, 01,
// 10, 11) where its weight `w` is above 0.
void include_corner(uint a, float w, vec4 rows, float v0, float v1, inout vec4 first, inout vec4 second) {
    if (w <= 0.0) return;
    float row = (a & 4u) != 0u ? ((a & 2u) != 0u ? rows.w : rows.z) : ((a & 2u) != 0u ? rows.y : rows.x);
    vec4 bounds = cells[2u + uint(row) * pc.offsets.x + uint((a & 1u) != 0u ? v1 : v0)];
    if ((a & 4u) != 0u)
        include_cell(second, bounds);
    else
        include_cell(first, bounds);
}
#endif

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
    float bands = float(pc.offsets.w & 0xffu);
    float steps = max(bands - 1.0, 1.0);
    float seen = atan(d.y, level_distance);
    float band = clamp(floor(seen / 1.57079633 * steps + 0.5), 0.0, bands - 1.0);
    // The quad: band 0 upright; a band from above facing the camera, stretched to the figure's height from there.
    vec3 up;
    float cell_height;
    band_quad(band, steps, seen, toward, up, cell_height);
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
    vec2 f = im.forward_phase.xy;
    vec2 local_x = vec2(f.y, -f.x);  // the character's local x (world xz); local z is f
    float dirs = float(pc.offsets.x);
    float av = atan(dot(h, local_x), dot(h, f)) / 6.28318531 * dirs;  // the camera's azimuth in directions, (-dirs/2, dirs/2]
    float rows = float(pc.offsets.y);
    float phases = rows - 1.0;
    float phase = im.forward_phase.z;
    float all_rows = rows * bands;
#ifdef BLEND
    // The two baked directions either side of the camera's azimuth, the two walk phases either side of the
    // character's and the two bands either side of the camera's elevation, each pair with the second's weight.
    // Blending fades in with the quad's size from blend_from px (the nearest picture, as the far layer below it
    // shows) to twice that (a linear blend); blend_from 0: blended at any size.
    float blend_from = float(pc.offsets.w >> 8u);
    float sharpness = blend_from > 0.0 ? clamp(py / blend_from - 1.0, 0.0, 1.0) : 1.0;
    float v0 = floor(av);
    float wv = sharpen(av - v0, sharpness);
    if (wv >= 1.0) {
        v0 += 1.0;
        wv = 0.0;
    }
    float v1 = mod(v0 + 1.0, dirs);
    v0 = mod(v0, dirs);
    float k0 = rows - 1.0, wk = 0.0;  // the standing row for a negative phase
    if (phase >= 0.0) {
        float ap = phase * phases;
        k0 = floor(ap);
        wk = sharpen(ap - k0, sharpness);
        if (wk >= 1.0) {
            k0 += 1.0;
            wk = 0.0;
        }
        k0 = mod(k0, phases);
    }
    float k1 = phase >= 0.0 ? mod(k0 + 1.0, phases) : k0;
    float b0 = 0.0, wb = 0.0;  // band 0 for a camera below the pivot
    if (bands > 1.0) {
        float ab = clamp(seen / 1.57079633 * steps, 0.0, bands - 1.0);
        b0 = floor(ab);
        wb = sharpen(ab - b0, sharpness);
        if (wb >= 1.0) {
            b0 += 1.0;
            wb = 0.0;
        }
        if (b0 >= bands - 1.0) {
            b0 = bands - 1.0;
            wb = 0.0;
        }
    }
    float b1 = wb > 0.0 ? b0 + 1.0 : b0;
    // The quad drawn is the first band's; the second band's cells are read where the eye's ray through the pixel
    // meets the second band's quad (across()).
    vec3 up1;
    float cell_height1;
    band_quad(b0, steps, seen, toward, up, cell_height);
    band_quad(b1, steps, seen, toward, up1, cell_height1);
    // The corners of the (view, phase, band) weights' tetrahedron in the cube of two pictures each: from (0, 0, 0)
    // along the axes in the order of their weights, largest first, with weights (1 - w1, w1 - w2, w2 - w3, w3) for
    // the weights sorted w1 >= w2 >= w3 (linear in the weights, and the same on either side of each face where two
    // are equal). Axis bits: 1 the second view, 2 the second phase, 4 the second band.
    vec2 s1 = vec2(wv, 1.0), s2 = vec2(wk, 2.0), s3 = vec2(wb, 4.0);
    if (s2.x > s1.x) { vec2 t = s1; s1 = s2; s2 = t; }
    if (s3.x > s2.x) { vec2 t = s2; s2 = s3; s3 = t; }
    if (s2.x > s1.x) { vec2 t = s1; s1 = s2; s2 = t; }
    uint first_axis = uint(s1.y), two_axes = uint(s1.y) | uint(s2.y);
    vec4 weights = vec4(1.0 - s1.x, s1.x - s2.x, s2.x - s3.x, s3.x);
    // The quad covers every read cell's silhouette: the first band's cells' bounds, and the second band's mapped onto
    // the quad (their union's corners through across()).
    vec4 b = vec4(0.0), second = vec4(0.0);
    vec4 cell_rows = vec4(b0 * rows + k0, b0 * rows + k1, b1 * rows + k0, b1 * rows + k1);
    include_corner(0u, 1.0, cell_rows, v0, v1, b, second);
    include_corner(first_axis, weights.y, cell_rows, v0, v1, b, second);
    include_corner(two_axes, weights.z, cell_rows, v0, v1, b, second);
    include_corner(7u, weights.w, cell_rows, v0, v1, b, second);
    include_band_cell(b, second, pivot, right, scale, up1, cell_height1, up, cell_height);
    float row0 = cell_rows.x, row1 = cell_rows.y;  // among every band's rows
#else
    // The nearest baked direction and walk phase.
    float v0 = mod(floor(av + 0.5), dirs);
    float k0 = phase < 0.0 ? rows - 1.0 : mod(floor(phase * phases + 0.5), phases);
    float row0 = band * rows + k0;  // among every band's rows
    vec4 b = cells[2u + uint(row0) * pc.offsets.x + uint(v0)];
#endif
    if (b.z <= b.x) {  // empty cell(s): a degenerate quad
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    // A texel of that level that passes the alpha test holds a covered texel of level 0 within its 2^level
    // footprint; one more texel for footprints that do not divide the cell evenly.
    vec2 pad = (exp2(level) + 1.0) / grid.xy;
#ifdef BLEND
    // Not clamped to the cell: the second band's silhouette may reach past it (the fragment shader reads no texel
    // outside a cell).
    vec2 c = mix(b.xy - pad, b.zw + pad, kCorners[gl_VertexIndex]);
#else
    vec2 c = mix(max(b.xy - pad, 0.0), min(b.zw + pad, 1.0), kCorners[gl_VertexIndex]);
#endif
    vec3 world = pivot + scale * (right * ((c.x - 0.5) * pc.base_colour.x) + up * ((c.y - 0.5) * cell_height));
    v_level = vec3(max(floor(vec2(grid.x * dirs, grid.y * all_rows) / exp2(level)), 1.0), level);
    v_colour = im.colour;
#ifdef BLEND
    float baked0 = b0 * 1.57079633 / steps, baked1 = b1 * 1.57079633 / steps;
    vec2 cs = vec2(cos(baked0), sin(baked0)), cs1 = vec2(cos(baked1), sin(baked1));
    v_uv = c;
    vec3 on1 = wb > 0.0 ? across(c, pivot, right, scale, up, cell_height, up1, cell_height1) : vec3(c, 1.0);
    v_cell1 = vec3(on1.xy * on1.z, on1.z);
    v_base = vec4(v0 / dirs, (row0 + 1.0) / all_rows, (cell_rows.z + 1.0) / all_rows, 0.0);
    v_step = vec4((v1 - v0) / dirs, (row1 - row0) / all_rows, 1.0 / dirs, 1.0 / all_rows);
    v_weights = weights;
    v_corners = uvec2(first_axis, two_axes);
    v_up = cs;
    v_up1 = cs1;
    v_light_fade = vec4(light_in_view(v0, dirs, local_x, f, cs), im.forward_phase.w);
    v_light1 = wv > 0.0 ? light_in_view(v1, dirs, local_x, f, cs) : vec3(0.0);
    v_light2 = wb > 0.0 ? light_in_view(v0, dirs, local_x, f, cs1) : vec3(0.0);
    v_light3 = wb > 0.0 && wv > 0.0 ? light_in_view(v1, dirs, local_x, f, cs1) : vec3(0.0);
#else
    float baked = band * 1.57079633 / steps;
    vec2 cs = vec2(cos(baked), sin(baked));
    v_uv = vec2((v0 + c.x) / dirs, (row0 + 1.0 - c.y) / all_rows);
    v_up = cs;
    v_light_fade = vec4(light_in_view(v0, dirs, local_x, f, cs), im.forward_phase.w);
#endif
    gl_Position = pc.view_proj * vec4(world, 1.0);
}
