#include "systems/frame/impostor_share.hpp"

#include "systems/geometry/body_skin/triangle_grid.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace aloha {
namespace {

bool comparable(const ImpostorBakeInput& a, const ImpostorBakeInput& b) {
    if (a.rows.size() != b.rows.size() || a.rows.empty() || a.directions != b.directions || a.elevations != b.elevations ||
        a.cell_height_px != b.cell_height_px || a.cull_back_faces != b.cull_back_faces)
        return false;
    if (!std::equal(a.materials.begin(), a.materials.end(), b.materials.begin(), b.materials.end())) return false;
    if (!std::equal(a.textures.begin(), a.textures.end(), b.textures.begin(), b.textures.end())) return false;
    if (a.colours.empty() != b.colours.empty() || a.uvs.empty() != b.uvs.empty() || a.vertex_material.empty() != b.vertex_material.empty())
        return false;
    for (const ImpostorBakeInput* in : {&a, &b}) {
        if (in->indices.empty() || in->indices.size() % 3 != 0) return false;
        const size_t n = in->rows.front().positions.size();
        if (n == 0 || (!in->uvs.empty() && in->uvs.size() != n) || (!in->vertex_material.empty() && in->vertex_material.size() != n) ||
            (!in->colours.empty() && in->colours.size() != n))
            return false;
        for (const ImpostorPose& row : in->rows)
            if (row.positions.size() != n) return false;
        if (std::any_of(in->indices.begin(), in->indices.end(), [n](uint32_t i) { return i >= n; })) return false;
    }
    return true;
}

// sRGB-encoded byte -> LINEAR, all 256 at once.
const std::array<float, 256>& srgb_to_linear() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (size_t c = 0; c < t.size(); ++c) {
            const float x = static_cast<float>(c) / 255.0f;
            t[c] = x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
        }
        return t;
    }();
    return table;
}

// Texel coordinate i of `size` for texture coordinate `t` (nearest texel) under `wrap`.
uint32_t wrapped_texel(float t, uint32_t size, TextureWrap wrap) {
    float x = t;
    if (wrap == TextureWrap::Repeat) x = t - std::floor(t);
    else if (wrap == TextureWrap::MirroredRepeat) x = 1.0f - std::abs(t - 2.0f * std::floor(0.5f * t) - 1.0f);
    x = std::clamp(x, 0.0f, 1.0f);
    return std::min(static_cast<uint32_t>(x * static_cast<float>(size)), size - 1);
}

// The albedo a bake sees at a point of `in` with material `material`, texture coordinate `uv` and vertex colour
// `colour`: the material's base colour x its base colour texture (nearest texel, decoded) x the colour; LINEAR.
glm::vec4 albedo(const ImpostorBakeInput& in, uint16_t material, glm::vec2 uv, glm::vec4 colour) {
    if (material >= in.materials.size()) return colour;
    const SurfaceMaterial& m = in.materials[material];
    glm::vec4 c = m.base_colour * colour;
    if (m.texture >= 0 && static_cast<size_t>(m.texture) < in.textures.size() && !in.uvs.empty()) {
        const TextureImage& t = in.textures[static_cast<size_t>(m.texture)];
        if (t.width > 0 && t.height > 0 && t.rgba.size() == size_t{t.width} * t.height * 4) {
            const size_t i = (size_t{wrapped_texel(uv.y, t.height, t.wrap_v)} * t.width + wrapped_texel(uv.x, t.width, t.wrap_u)) * 4;
            const std::array<float, 256>& linear = srgb_to_linear();
            c *= glm::vec4(linear[t.rgba[i]], linear[t.rgba[i + 1]], linear[t.rgba[i + 2]], t.rgba[i + 3] / 255.0f);
        }
    }
    return c;
}

struct OneWay {
    float distance_px = 0.0f;  // the largest vertex-to-surface distance (the first over the tolerance when stopped)
    double colour_steps = 0.0; // summed albedo differences, largest channel, in 8-bit steps
    size_t vertices = 0;       // vertices compared
};

// One direction of the comparison in one row: every vertex of `from` (its positions times `from_scale`) against
// the surface `to` (`to_positions`, scaled, indexed by `grid`): its distance in atlas pixels (`texel` model units
// each) and the albedo there. Stops at the first distance over `tolerance_px`.
OneWay one_way(const ImpostorBakeInput& from, std::span<const glm::vec3> from_positions, float from_scale,
               const ImpostorBakeInput& to, const TriangleGrid& grid, float texel, float tolerance_px) {
    OneWay out;
    for (size_t v = 0; v < from_positions.size(); ++v) {
        const TriangleGrid::Hit hit = grid.closest(from_positions[v] * from_scale);
        const float d = std::sqrt(hit.distance_sq) / texel;
        out.distance_px = std::max(out.distance_px, d);
        if (!(d <= tolerance_px)) return out;
        const uint32_t* corner = &to.indices[size_t{hit.triangle} * 3];
        const glm::vec3 w = hit.bary;
        // The closest point's material: its triangle's corner of the largest weight (a triangle across a material
        // boundary is drawn in both).
        const int k = w.x >= w.y && w.x >= w.z ? 0 : w.y >= w.z ? 1 : 2;
        const uint16_t mine = from.vertex_material.empty() ? 0 : from.vertex_material[v];
        const uint16_t theirs = to.vertex_material.empty() ? 0 : to.vertex_material[corner[k]];
        const glm::vec2 uv_mine = from.uvs.empty() ? glm::vec2(0.0f) : from.uvs[v];
        const glm::vec2 uv_theirs = to.uvs.empty() ? glm::vec2(0.0f) : w.x * to.uvs[corner[0]] + w.y * to.uvs[corner[1]] + w.z * to.uvs[corner[2]];
        const glm::vec4 c_mine = from.colours.empty() ? glm::vec4(1.0f) : from.colours[v];
        const glm::vec4 c_theirs = to.colours.empty() ? glm::vec4(1.0f) : w.x * to.colours[corner[0]] + w.y * to.colours[corner[1]] + w.z * to.colours[corner[2]];
        const glm::vec4 apart = glm::abs(albedo(from, mine, uv_mine, c_mine) - albedo(to, theirs, uv_theirs, c_theirs)) * 255.0f;
        out.colour_steps += std::max(std::max(apart.x, apart.y), std::max(apart.z, apart.w));
        ++out.vertices;
    }
    return out;
}

}  // namespace

glm::vec2 impostor_vertical_range(const ImpostorBakeInput& in) {
    glm::vec2 e(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity());
    for (const ImpostorPose& row : in.rows)
        for (const glm::vec3& v : row.positions) e = glm::vec2(std::min(e.x, v.y), std::max(e.y, v.y));
    return e;
}

ImpostorShare impostor_share_between(const ImpostorBakeInput& owner, const ImpostorBakeInput& other, float tolerance_px) {
    ImpostorShare out;
    if (!comparable(owner, other)) return out;
    const glm::vec2 a = impostor_vertical_range(owner), b = impostor_vertical_range(other);
    if (!(a.y > a.x) || !(b.y > b.x)) return out;
    out.comparable = true;
    out.scale = (b.y - b.x) / (a.y - a.x);
    // Distances are measured at `other`'s size, in the owner's pixels drawn that size.
    const float texel = impostor_texel_size(owner) * out.scale;
    // Rows in parallel (each its own grids and sums; the result does not depend on which thread ran which row).
    std::vector<OneWay> rows(2 * owner.rows.size());
    tbb::parallel_for(size_t{0}, owner.rows.size(), [&](size_t r) {
        const std::span<const glm::vec3> mine = other.rows[r].positions;
        std::vector<glm::vec3> scaled(owner.rows[r].positions.size());
        std::transform(owner.rows[r].positions.begin(), owner.rows[r].positions.end(), scaled.begin(),
                       [&](const glm::vec3& p) { return p * out.scale; });
        const TriangleGrid owner_grid(scaled, owner.indices);
        rows[2 * r] = one_way(other, mine, 1.0f, owner, owner_grid, texel, tolerance_px);
        if (!(rows[2 * r].distance_px <= tolerance_px)) return;
        const TriangleGrid other_grid(mine, other.indices);
        rows[2 * r + 1] = one_way(owner, owner.rows[r].positions, out.scale, other, other_grid, texel, tolerance_px);
    });
    out.distance_px = 0.0f;
    double colour_steps = 0.0;
    size_t vertices = 0;
    for (const OneWay& w : rows) {
        out.distance_px = std::max(out.distance_px, w.distance_px);
        colour_steps += w.colour_steps;
        vertices += w.vertices;
    }
    if (!(out.distance_px <= tolerance_px)) return out;
    out.colour_steps = vertices > 0 ? static_cast<float>(colour_steps / static_cast<double>(vertices)) : 0.0f;
    return out;
}

}  // namespace aloha
