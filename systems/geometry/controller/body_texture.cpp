// Generated body regions, grid UVs and texture (see body_texture.hpp).
#include "systems/geometry/controller/body_texture.hpp"

#include "systems/geometry/muscle/muscle_shape_job.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace aloha {

namespace {

constexpr uint32_t kTextureSize = 256;
constexpr uint32_t kColumns = 4;

float point_segment_distance(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
    const glm::vec3 ab = b - a;
    const float len2 = glm::dot(ab, ab);
    const float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (a + t * ab));
}

}  // namespace

std::vector<BodyRegion> bone_regions(const Skeleton& skeleton, std::span<const glm::mat4> rest_model) {
    const size_t n = static_cast<size_t>(skeleton.joint_count());
    const auto parents = skeleton.parents();
    std::vector<BodyRegion> region(n, BodyRegion::Shirt);
    if (n == 0) return region;
    auto y = [&](size_t j) { return rest_model[j][3].y; };
    float lo = FLT_MAX, hi = -FLT_MAX;
    size_t top = 0;
    for (size_t j = 0; j < n; ++j) {
        lo = std::min(lo, y(j));
        if (y(j) > hi) hi = y(j), top = j;
    }
    const float height = std::max(hi - lo, 1e-6f);
    std::vector<uint8_t> spine(n, 0);
    for (int j = static_cast<int>(top); j >= 0; j = parents[static_cast<size_t>(j)]) spine[static_cast<size_t>(j)] = 1;
    // Per joint: the spine joint its limb branches from (itself on the spine), and the path length from it.
    std::vector<int> branch(n, -1);
    std::vector<float> along(n, 0.0f);
    for (size_t j = 0; j < n; ++j) {  // parents precede children
        const int p = parents[j];
        if (spine[j] || p < 0) {
            branch[j] = static_cast<int>(j);
            continue;
        }
        branch[j] = spine[static_cast<size_t>(p)] ? p : branch[static_cast<size_t>(p)];
        along[j] = along[static_cast<size_t>(p)] + glm::length(glm::vec3(rest_model[j][3] - rest_model[static_cast<size_t>(p)][3]));
    }
    // Per limb (keyed by its first joint off the spine): lowest height and total length.
    std::vector<int> limb(n, -1);
    std::vector<float> limb_low(n, FLT_MAX), limb_length(n, 0.0f);
    for (size_t j = 0; j < n; ++j) {
        if (spine[j] || parents[j] < 0) continue;
        limb[j] = spine[static_cast<size_t>(parents[j])] ? static_cast<int>(j) : limb[static_cast<size_t>(parents[j])];
        const auto l = static_cast<size_t>(limb[j]);
        limb_low[l] = std::min(limb_low[l], y(j));
        limb_length[l] = std::max(limb_length[l], along[j]);
    }
    auto is_leg = [&](size_t l) { return limb_low[l] < lo + 0.15f * height; };
    float shoulders = -FLT_MAX;  // highest arm branch
    for (size_t j = 0; j < n; ++j)
        if (limb[j] == static_cast<int>(j) && !is_leg(j)) shoulders = std::max(shoulders, y(static_cast<size_t>(branch[j])));
    for (size_t j = 0; j < n; ++j) {
        if (spine[j]) {  // up to the arm branch: chest (shirt); above it: neck and head (skin)
            region[j] = shoulders > -FLT_MAX && y(j) > shoulders + 1e-4f * height ? BodyRegion::Skin : BodyRegion::Shirt;
            continue;
        }
        if (limb[j] < 0) continue;
        const auto l = static_cast<size_t>(limb[j]);
        if (is_leg(l)) region[j] = y(j) < lo + 0.1f * height ? BodyRegion::Shoes : BodyRegion::Trousers;
        else region[j] = along[j] < 0.5f * limb_length[l] ? BodyRegion::Shirt : BodyRegion::Skin;
    }
    return region;
}

std::vector<glm::vec2> body_skin_uvs(const Skeleton& skeleton, std::span<const glm::mat4> rest_model, const MuscleSet& muscles,
                                     std::span<const glm::vec3> positions, std::span<const uint16_t> dominant_muscle) {
    const size_t m_count = static_cast<size_t>(muscles.size());
    std::vector<glm::vec2> uvs(positions.size(), glm::vec2(0.0f));
    if (m_count == 0 || dominant_muscle.size() != positions.size()) return uvs;
    const std::vector<BodyRegion> region = bone_regions(skeleton, rest_model);
    const auto parents = skeleton.parents();
    float lo = FLT_MAX, hi = -FLT_MAX;
    for (const glm::mat4& m : rest_model) lo = std::min(lo, m[3].y), hi = std::max(hi, m[3].y);
    const float height = std::max(hi - lo, 1e-6f);
    std::vector<glm::vec3> centres(m_count), radii(m_count);
    std::vector<glm::quat> rotations(m_count);
    const MuscleShapeJob shape{&muscles, rest_model, centres, rotations, radii};
    shape.Run();
    std::vector<float> column(m_count);
    for (size_t m = 0; m < m_count; ++m) {
        // Nearest bone (parent -> joint segment) to the rest centre; the region is the parent's outgoing bone's.
        float best = FLT_MAX;
        BodyRegion r = BodyRegion::Shirt;
        for (size_t j = 0; j < region.size(); ++j) {
            const int p = parents[j];
            if (p < 0) continue;
            const float d = point_segment_distance(centres[m], glm::vec3(rest_model[static_cast<size_t>(p)][3]), glm::vec3(rest_model[j][3]));
            if (d < best) best = d, r = region[static_cast<size_t>(p)];
        }
        column[m] = (static_cast<float>(r) + 0.5f) / static_cast<float>(kColumns);
    }
    for (size_t i = 0; i < positions.size(); ++i)
        uvs[i] = glm::vec2(column[dominant_muscle[i]], std::clamp((hi - positions[i].y) / height, 0.0f, 1.0f));
    return uvs;
}

TextureImage make_body_texture() {
    TextureImage t;
    t.name = "generated body texture";
    t.width = t.height = kTextureSize;
    t.rgba.resize(size_t{kTextureSize} * kTextureSize * 4);
    t.wrap_u = t.wrap_v = TextureWrap::ClampToEdge;
    const uint32_t column = kTextureSize / kColumns;
    for (uint32_t y = 0; y < kTextureSize; ++y)
        for (uint32_t x = 0; x < kTextureSize; ++x) {
            const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(kTextureSize);
            // A small fixed hash gives cloth a woven grain (deterministic: same image every run).
            const uint32_t h = (x * 73856093u) ^ (y * 19349663u);
            const float grain = static_cast<float>((h >> 7) % 17u) / 16.0f - 0.5f;
            glm::vec3 c;
            switch (x / column) {
                case 0: c = glm::vec3(0.88f, 0.69f, 0.56f) * (1.0f - 0.08f * v); break;  // skin, a touch darker lower down
                case 1: c = (y / 6u) % 3u == 0u ? glm::vec3(0.93f, 0.93f, 0.90f) : glm::vec3(0.16f, 0.36f, 0.66f); break;  // striped shirt
                case 2: c = glm::vec3(0.20f, 0.25f, 0.36f) + 0.04f * grain; break;  // trousers
                default: c = v > 0.975f ? glm::vec3(0.06f, 0.05f, 0.05f) : glm::vec3(0.30f, 0.18f, 0.10f) + 0.02f * grain; break;  // shoes
            }
            uint8_t* px = &t.rgba[(size_t{y} * kTextureSize + x) * 4];
            for (int k = 0; k < 3; ++k) px[k] = static_cast<uint8_t>(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
            px[3] = 255;
        }
    return t;
}

SurfaceMaterial body_material() {
    SurfaceMaterial m;
    m.name = "generated body";
    m.texture = 0;
    return m;
}

}  // namespace aloha
