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
// Rows of the shoes' column that are sole: 5 of 256, about 3.4 cm of a 1.75 m body (v spans the skin's height).
constexpr float kSoleRows = 5.0f;

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
                                     std::span<const glm::vec3> positions, std::span<const uint16_t> dominant_muscle,
                                     std::span<const uint32_t> indices) {
    const size_t m_count = static_cast<size_t>(muscles.size());
    std::vector<glm::vec2> uvs(positions.size(), glm::vec2(0.0f));
    if (m_count == 0 || dominant_muscle.size() != positions.size()) return uvs;
    const std::vector<BodyRegion> region = bone_regions(skeleton, rest_model);
    const auto parents = skeleton.parents();
    std::vector<glm::vec3> centres(m_count), radii(m_count);
    std::vector<glm::quat> rotations(m_count);
    const MuscleShapeJob shape{&muscles, rest_model, centres, rotations, radii};
    shape.Run();
    std::vector<uint8_t> muscle_region(m_count);
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
        muscle_region[m] = static_cast<uint8_t>(r);
    }
    std::vector<uint8_t> vertex_region(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) vertex_region[i] = muscle_region[dominant_muscle[i]];
    const std::vector<float> u = hem_columns(vertex_region, positions, indices, kHemBand);
    // v over the skin's own height, so the texture's last rows (the soles) are the lowest centimetres of the feet.
    float top = -FLT_MAX, bottom = FLT_MAX;
    for (const glm::vec3& p : positions) top = std::max(top, p.y), bottom = std::min(bottom, p.y);
    const float extent = std::max(top - bottom, 1e-6f);
    for (size_t i = 0; i < positions.size(); ++i) uvs[i] = glm::vec2(u[i], std::clamp((top - positions[i].y) / extent, 0.0f, 1.0f));
    return uvs;
}

std::vector<float> hem_columns(std::span<const uint8_t> region, std::span<const glm::vec3> positions, std::span<const uint32_t> indices, float band) {
    const size_t n = region.size();
    constexpr float w = 1.0f / static_cast<float>(kColumns);
    std::vector<float> u(n);
    for (size_t i = 0; i < n; ++i) u[i] = (static_cast<float>(region[i]) + 0.5f) * w;
    if (indices.size() < 3 || positions.size() != n) return u;
    // One-ring neighbours, and the mean edge length that sets how many smoothing rounds make the band.
    std::vector<std::vector<uint32_t>> ring(n);
    double edge_sum = 0.0;
    size_t edges = 0;
    for (size_t t = 0; t + 2 < indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = indices[t + static_cast<size_t>(k)], b = indices[t + static_cast<size_t>((k + 1) % 3)];
            if (a >= n || b >= n) continue;
            ring[a].push_back(b), ring[b].push_back(a);
            edge_sum += static_cast<double>(glm::length(positions[a] - positions[b]));
            ++edges;
        }
    for (std::vector<uint32_t>& r : ring) {
        std::sort(r.begin(), r.end());
        r.erase(std::unique(r.begin(), r.end()), r.end());
    }
    const float edge = edges ? static_cast<float>(edge_sum / static_cast<double>(edges)) : band;
    // A round of s <- (s + mean of the ring) / 2 spreads a region's share by about half an edge squared in variance:
    // 2 (band / edge)^2 rounds spread it over about `band`, whatever the mesh's resolution.
    const int rounds = band > 0.0f ? std::clamp(static_cast<int>(std::ceil(2.0f * (band / edge) * (band / edge))), 1, kMaxHemRounds) : 0;
    std::vector<glm::vec4> share(n, glm::vec4(0.0f)), next(n);
    for (size_t i = 0; i < n; ++i) share[i][std::min<int>(region[i], 3)] = 1.0f;
    for (int round = 0; round < rounds; ++round) {
        for (size_t i = 0; i < n; ++i) {
            if (ring[i].empty()) {
                next[i] = share[i];
                continue;
            }
            glm::vec4 mean(0.0f);
            for (uint32_t j : ring[i]) mean += share[j];
            next[i] = 0.5f * (share[i] + mean / static_cast<float>(ring[i].size()));
        }
        share.swap(next);
    }
    for (size_t i = 0; i < n; ++i) {
        // The two regions with the largest shares: next to each other in the texture (skin | shirt | trousers |
        // shoes, as the body joins them), u runs from one's column centre to the other's by the second's share of
        // the two, so the column border (the hem) lies where both shares are equal. Regions not side by side: the
        // larger one's centre.
        int a = 0;
        for (int k = 1; k < 4; ++k)
            if (share[i][k] > share[i][a]) a = k;
        int b = a == 0 ? 1 : 0;
        for (int k = 0; k < 4; ++k)
            if (k != a && share[i][k] > share[i][b]) b = k;
        if (std::abs(a - b) != 1 || share[i][b] <= 0.0f) {
            u[i] = (static_cast<float>(a) + 0.5f) * w;
            continue;
        }
        const int low = std::min(a, b), high = std::max(a, b);
        const float t = share[i][high] / (share[i][low] + share[i][high]);
        u[i] = (static_cast<float>(low) + 0.5f + t) * w;
    }
    return u;
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
                default: c = v > 1.0f - kSoleRows / static_cast<float>(kTextureSize) ? glm::vec3(0.06f, 0.05f, 0.05f) : glm::vec3(0.30f, 0.18f, 0.10f) + 0.02f * grain; break;  // shoes
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
