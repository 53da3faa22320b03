#include "systems/render/impostor_atlas.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/offscreen_target.hpp"
#include "engine/gpu/vk_error.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

namespace aloha {
namespace {

constexpr float kMargin = 0.04f;  // empty border of a cell, share of the bounds on each side

struct Cells {
    float width_m = 0.0f, height_m = 0.0f, bottom_m = 0.0f;  // one level cell in model units; its lower edge
    float elevated_height_m = 0.0f;                          // the cells of the bands from above (0 with one band)
    float depth_ratio = 0.0f;                                // mean depth along a level view over the height
    uint32_t width_px = 0, height_px = 0;
    [[nodiscard]] float pivot() const { return bottom_m + 0.5f * height_m; }
};

// Cells that hold the mesh in every pose and from every azimuth: the radius about the vertical axis by
// the height range, with a margin, at square pixels. Seen from elevation a, a point y above the pivot and r from
// the vertical axis lies at most |y| cos a + r sin a from the pivot on the image's vertical: the elevated bands'
// cells are as tall as the largest of that over their elevations (with the same margin), at the level cells'
// pixel height (their texels not quite square).
Cells cell_size(const ImpostorBakeInput& in, uint32_t elevations) {
    float radius = 0.0f, lo = 1e30f, hi = -1e30f;
    for (const ImpostorPose& p : in.rows)
        for (const glm::vec3& v : p.positions) {
            radius = std::max(radius, std::hypot(v.x, v.z));
            lo = std::min(lo, v.y);
            hi = std::max(hi, v.y);
        }
    Cells c;
    const float h = std::max(hi - lo, 1e-3f);
    c.height_m = h * (1.0f + 2.0f * kMargin);
    c.bottom_m = lo - h * kMargin;
    c.height_px = std::max<uint32_t>(in.cell_height_px, 8);
    const float metres_per_px = c.height_m / static_cast<float>(c.height_px);
    const float width = 2.0f * std::max(radius, 1e-3f) + 2.0f * h * kMargin;
    c.width_px = static_cast<uint32_t>(std::ceil(width / metres_per_px / 4.0f)) * 4;
    c.width_m = static_cast<float>(c.width_px) * metres_per_px;
    if (elevations < 2) return c;  // no band from above: no elevated cells, no stretch
    // The figure's depth along each level view (its extent towards that view's camera), averaged over the views and
    // the rows, over its height: how much of it a view from above adds to its picture's height.
    double depth = 0.0;
    const uint32_t dirs = std::max(in.directions, 1u);
    for (const ImpostorPose& p : in.rows)
        for (uint32_t d = 0; d < dirs; ++d) {
            const float azimuth = 6.28318531f * static_cast<float>(d) / static_cast<float>(dirs);
            const glm::vec2 toward(std::sin(azimuth), std::cos(azimuth));
            float near = -1e30f, far = 1e30f;
            for (const glm::vec3& v : p.positions) {
                const float z = v.x * toward.x + v.z * toward.y;
                near = std::max(near, z);
                far = std::min(far, z);
            }
            depth += near - far;
        }
    c.depth_ratio = static_cast<float>(depth / static_cast<double>(in.rows.size() * dirs)) / h;
    for (uint32_t e = 1; e < elevations; ++e) {
        const float a = impostor_elevation(e, elevations);
        const float half = 0.5f * h * std::cos(a) + std::max(radius, 1e-3f) * std::sin(a);
        c.elevated_height_m = std::max(c.elevated_height_m, 2.0f * half + 2.0f * h * kMargin);
    }
    return c;
}

uint64_t mip_chain_bytes(uint32_t w, uint32_t h) {
    uint64_t bytes = 0;
    for (;;) {
        bytes += uint64_t{w} * h * 4;
        if (w == 1 && h == 1) return bytes;
        w = std::max(1u, w / 2);
        h = std::max(1u, h / 2);
    }
}

}  // namespace

glm::mat4 impostor_view_rotation(uint32_t d, uint32_t directions) {
    const float azimuth = 6.28318531f * static_cast<float>(d) / static_cast<float>(std::max(directions, 1u));
    return glm::rotate(glm::mat4(1.0f), -azimuth, glm::vec3(0.0f, 1.0f, 0.0f));
}

float impostor_texel_size(const ImpostorBakeInput& in) {
    const Cells c = cell_size(in, 1);
    return c.height_m / static_cast<float>(c.height_px);
}

glm::mat4 impostor_view_transform(uint32_t d, uint32_t directions, float elevation, float pivot_y) {
    // Leaning +Y towards +Z by the elevation is a rotation about +X by that angle.
    return glm::rotate(glm::mat4(1.0f), elevation, glm::vec3(1.0f, 0.0f, 0.0f)) *
           glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -pivot_y, 0.0f)) * impostor_view_rotation(d, directions);
}

std::string impostor_atlas_image_name(const std::string& type) { return "impostor atlas '" + type + "'"; }

Result<ImpostorAtlas> bake_impostor_atlas(gpu::Context& ctx, const ImpostorBakeInput& in) {
    const auto t0 = std::chrono::steady_clock::now();
    auto fail = [&](const std::string& what) { return gpu::gpu_error("impostor atlas of '" + in.name + "': " + what); };
    if (in.rows.size() < 2) return fail("needs at least one walk phase and the standing pose, has " + std::to_string(in.rows.size()) + " rows");
    if (in.indices.empty() || in.indices.size() % 3 != 0 || in.rows[0].positions.empty()) return fail("empty mesh");
    for (size_t r = 0; r < in.rows.size(); ++r)
        if (in.rows[r].positions.size() != in.rows[0].positions.size() || in.rows[r].normals.size() != in.rows[0].positions.size())
            return fail("row " + std::to_string(r) + " has " + std::to_string(in.rows[r].positions.size()) + " positions and " +
                        std::to_string(in.rows[r].normals.size()) + " normals for " + std::to_string(in.rows[0].positions.size()) + " vertices");
    if (in.elevations < 1 || in.elevations > kMaxImpostorElevations)
        return fail(std::to_string(in.elevations) + " elevations (bands of views), expected 1 to " + std::to_string(kMaxImpostorElevations));
    const uint32_t dirs = std::max(in.directions, 1u), rows = static_cast<uint32_t>(in.rows.size()), bands = in.elevations;
    const Cells cells = cell_size(in, bands);
    const uint32_t width = dirs * cells.width_px, band_height = rows * cells.height_px, height = bands * band_height;
    if (width > 8192 || 2 * height > 8192) return fail("atlas of " + std::to_string(width) + " x " + std::to_string(2 * height) + " pixels is too large");

    RendererOptions options;
    options.initial_vertices = static_cast<uint32_t>(in.rows[0].positions.size()) * dirs * rows + 1;
    options.initial_instances = dirs * rows;
    options.frames_in_flight = 1;
    options.blend_texture_mips = true;  // baked once: the best filtering on every device, the same atlas on every one
    Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(ctx, options);
    if (!made) return made.error();
    CrowdRenderer& renderer = *made.value();
    Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(ctx, width, band_height);  // one band at a time
    if (!target) return target.error();

    std::vector<uint32_t> textures, materials;
    for (const TextureImage& t : in.textures) {
        Result<uint32_t> id = renderer.register_texture(t);
        if (!id) return id.error();
        textures.push_back(id.value());
    }
    for (const SurfaceMaterial& m : in.materials) {
        Result<uint32_t> id = renderer.register_material(m, textures);
        if (!id) return id.error();
        materials.push_back(id.value());
    }
    TopologySurface surface;
    if (!materials.empty()) surface = {in.uvs, in.vertex_material, materials, in.colours};
    Result<uint32_t> topology = renderer.register_topology(in.indices, static_cast<uint32_t>(in.rows[0].positions.size()),
                                                           in.cull_back_faces, surface);
    if (!topology) return topology.error();

    ImpostorAtlas out;
    out.image.name = impostor_atlas_image_name(in.name);
    out.image.width = width;
    out.image.height = 2 * height;
    out.image.rgba.resize(size_t{width} * 2 * height * 4);
    FrameInput frame;
    frame.camera.view = glm::lookAt(glm::vec3(0.0f, 0.0f, 10.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    frame.camera.eye_at_infinity = true;  // orthographic: every cell is seen along -Z, however far off the axis
    frame.clear_colour = glm::vec4(0.0f);
    frame.ambient = 1.0f;  // white sky and ground (the defaults): the albedo, unlit
    std::vector<DeformableMesh> meshes;
    for (uint32_t band = 0; band < bands; ++band) {
        // Cell (d, r) of the band: column d, row r from the top; the character's pivot at the cell's centre, seen
        // from the band's elevation (band 0: its quad's lower edge, bottom_m above the origin, on the cell's lower edge).
        const float cell_h = band == 0 ? cells.height_m : cells.elevated_height_m;
        const float elevation = impostor_elevation(band, bands);
        meshes.clear();
        for (uint32_t r = 0; r < rows; ++r)
            for (uint32_t d = 0; d < dirs; ++d) {
                const glm::vec3 centre((static_cast<float>(d) + 0.5f) * cells.width_m, -(static_cast<float>(r) + 0.5f) * cell_h, 0.0f);
                meshes.push_back({topology.value(), in.rows[r].positions, in.rows[r].normals,
                                  glm::translate(glm::mat4(1.0f), centre) * impostor_view_transform(d, dirs, elevation, cells.pivot()),
                                  glm::vec4(1.0f)});
            }
        frame.meshes = meshes;
        // Depth: 10 m either side of the cells' plane, where any figure under 10 m from its pivot lies, leant or not.
        frame.camera.proj = glm::ortho(0.0f, static_cast<float>(dirs) * cells.width_m, -static_cast<float>(rows) * cell_h, 0.0f, 0.1f, 20.0f);
        for (size_t half = 0; half < 2; ++half) {
            frame.write_normals = half == 1;
            if (Status s = renderer.render(frame, target.value()); !s) return s.error();
            if (Status s = renderer.finish(); !s) return s.error();
            Result<gpu::Rgba8Image> image = target.value().read_back(ctx);
            if (!image) return image.error();
            const size_t band_bytes = size_t{width} * band_height * 4;
            std::memcpy(out.image.rgba.data() + half * size_t{width} * height * 4 + band * band_bytes, image.value().pixels.data(), band_bytes);
        }
    }
    out.layout = {dirs, rows, cells.width_m, cells.bottom_m, cells.height_m, bands, cells.elevated_height_m, cells.depth_ratio};
    out.texture_bytes = 2 * mip_chain_bytes(width, height);  // packed: (colour, normal) pairs over one half (impostor_packing.hpp)
    out.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace aloha
