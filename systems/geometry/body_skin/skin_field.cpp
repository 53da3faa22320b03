// Body field sampling and marching-tetrahedra polygonisation (see skin_field.hpp).
#include "systems/geometry/body_skin/skin_field.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace aloha {
namespace {

float smooth_min(float a, float b, float k) {
    const float h = std::max(k - std::abs(a - b), 0.0f) / k;
    return std::min(a, b) - 0.25f * k * h * h;
}

// Axis-aligned bounds of a primitive (model space).
struct Box {
    glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
    void add(glm::vec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
};

Box bounds(const FieldEllipsoid& e) {
    // The super-ellipsoid lies inside its radii box; the rotated box's extent per model axis.
    const glm::mat3 r = glm::mat3_cast(e.rotation);
    const glm::vec3 ext = glm::abs(r[0]) * e.radii.x + glm::abs(r[1]) * e.radii.y + glm::abs(r[2]) * e.radii.z;
    Box b;
    b.add(e.centre - ext);
    b.add(e.centre + ext);
    return b;
}

Box bounds(const FieldCapsule& c) {
    Box b;
    b.add(glm::min(c.a, c.b) - glm::vec3(c.radius));
    b.add(glm::max(c.a, c.b) + glm::vec3(c.radius));
    return b;
}

}  // namespace

float ellipsoid_distance(const FieldEllipsoid& e, glm::vec3 p) {
    const glm::vec3 q = glm::conjugate(e.rotation) * (p - e.centre);
    const float len = glm::length(q);
    const float A = e.exponents.x, B = e.exponents.y;
    const glm::vec3 s = glm::abs(q) / e.radii;
    const float F = std::pow(std::pow(s.x, 2.0f / B) + std::pow(s.y, 2.0f / B), B / A) + std::pow(s.z, 2.0f / A);
    const float r = std::pow(F, 0.5f * A);
    if (r < 1e-6f) return -std::min({e.radii.x, e.radii.y, e.radii.z});
    return len * (1.0f - 1.0f / r);
}

float capsule_distance(const FieldCapsule& c, glm::vec3 p) {
    const glm::vec3 ab = c.b - c.a;
    const float len2 = glm::dot(ab, ab);
    const float t = len2 > 0.0f ? std::clamp(glm::dot(p - c.a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (c.a + t * ab)) - c.radius;
}

namespace {

// One pass of a normalised Gaussian (standard deviation `sigma` grid cells, cut at 3 sigma) along `axis` of
// `grid`'s layout; beyond the grid the border value repeats.
void blur_axis(std::vector<float>& values, const SampledField& grid, int axis, float sigma) {
    const int radius = std::max(1, static_cast<int>(std::ceil(3.0f * sigma)));
    std::vector<float> kernel(static_cast<size_t>(2 * radius + 1));
    float sum = 0.0f;
    for (int i = -radius; i <= radius; ++i)
        sum += kernel[static_cast<size_t>(i + radius)] = std::exp(-0.5f * static_cast<float>(i * i) / (sigma * sigma));
    for (float& k : kernel) k /= sum;
    const int n[3] = {static_cast<int>(grid.nx), static_cast<int>(grid.ny), static_cast<int>(grid.nz)};
    const size_t stride[3] = {1, grid.nx, size_t{grid.nx} * grid.ny};
    const int len = n[axis], a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    std::vector<float> line(static_cast<size_t>(len));
    for (int u = 0; u < n[a1]; ++u)
        for (int v = 0; v < n[a2]; ++v) {
            const size_t base = static_cast<size_t>(u) * stride[a1] + static_cast<size_t>(v) * stride[a2];
            for (int i = 0; i < len; ++i) line[static_cast<size_t>(i)] = values[base + static_cast<size_t>(i) * stride[axis]];
            for (int i = 0; i < len; ++i) {
                float acc = 0.0f;
                for (int k = -radius; k <= radius; ++k)
                    acc += kernel[static_cast<size_t>(k + radius)] * line[static_cast<size_t>(std::clamp(i + k, 0, len - 1))];
                values[base + static_cast<size_t>(i) * stride[axis]] = acc;
            }
        }
}

}  // namespace

void fill_concavities(std::vector<float>& values, const SampledField& grid, float sigma) {
    assert(values.size() == size_t{grid.nx} * grid.ny * grid.nz && sigma > 0.0f);
    std::vector<float> blurred = values;
    for (int axis = 0; axis < 3; ++axis) blur_axis(blurred, grid, axis, sigma / grid.cell);
    for (size_t i = 0; i < values.size(); ++i) values[i] = std::min(values[i], blurred[i]);
}

SampledField sample_body_field(const BodyField& field, float cell) {
    assert(cell > 0.0f && (!field.ellipsoids.empty() || !field.capsules.empty()));
    std::vector<Box> boxes;
    for (const FieldEllipsoid& e : field.ellipsoids) boxes.push_back(bounds(e));
    for (const FieldCapsule& c : field.capsules) boxes.push_back(bounds(c));
    Box all;
    for (const Box& b : boxes) {
        all.add(b.lo);
        all.add(b.hi);
    }
    const glm::vec3 margin(field.blend + 2.0f * cell);
    SampledField out;
    out.cell = cell;
    out.origin = all.lo - margin;
    const glm::vec3 size = (all.hi + margin) - out.origin;
    out.nx = static_cast<uint32_t>(std::ceil(size.x / cell)) + 1;
    out.ny = static_cast<uint32_t>(std::ceil(size.y / cell)) + 1;
    out.nz = static_cast<uint32_t>(std::ceil(size.z / cell)) + 1;
    // Far from every primitive the field only needs to be positive: the margin is a safe value.
    const float far = field.blend + 2.0f * cell;
    const size_t count = boxes.size(), ne = field.ellipsoids.size();
    auto group_of = [&](size_t k) -> uint8_t {
        if (k < ne) return field.ellipsoid_group.empty() ? 0 : field.ellipsoid_group[k];
        return field.capsule_group.empty() ? 0 : field.capsule_group[k - ne];
    };
    uint8_t groups = 1;
    for (size_t k = 0; k < count; ++k) groups = std::max<uint8_t>(groups, static_cast<uint8_t>(group_of(k) + 1));
    const size_t points = size_t{out.nx} * out.ny * out.nz;
    std::vector<std::vector<float>> layer(groups, std::vector<float>(points, far));
    for (size_t k = 0; k < count; ++k) {
        std::vector<float>& values = layer[group_of(k)];
        const glm::vec3 lo = (boxes[k].lo - glm::vec3(field.blend) - out.origin) / cell;
        const glm::vec3 hi = (boxes[k].hi + glm::vec3(field.blend) - out.origin) / cell;
        const glm::uvec3 a(glm::max(glm::floor(lo), glm::vec3(0.0f)));
        const glm::uvec3 b(glm::min(glm::ceil(hi), glm::vec3(out.nx - 1, out.ny - 1, out.nz - 1)));
        for (uint32_t z = a.z; z <= b.z; ++z)
            for (uint32_t y = a.y; y <= b.y; ++y)
                for (uint32_t x = a.x; x <= b.x; ++x) {
                    const glm::vec3 p = out.origin + cell * glm::vec3(x, y, z);
                    const float d = k < ne ? ellipsoid_distance(field.ellipsoids[k], p) : capsule_distance(field.capsules[k - ne], p);
                    float& v = values[(size_t{z} * out.ny + y) * out.nx + x];
                    v = smooth_min(v, d, field.blend);
                }
    }
    if (field.trunk_fill > 0.0f) fill_concavities(layer[0], out, field.trunk_fill);
    if (groups == 1) {
        out.values = std::move(layer[0]);
    } else {
        out.values.assign(points, far);
        for (uint8_t g = 1; g < groups; ++g)
            for (size_t i = 0; i < points; ++i) out.values[i] = std::min(out.values[i], smooth_min(layer[0][i], layer[g][i], field.blend));
    }
    for (float& v : out.values)
        if (v == 0.0f) v = 1e-7f;
    fill_cavities(out);
    return out;
}

void fill_cavities(SampledField& field) {
    const uint32_t nx = field.nx, ny = field.ny, nz = field.nz;
    std::vector<uint8_t> outside(field.values.size(), 0);
    std::vector<uint64_t> stack;
    auto push = [&](uint32_t x, uint32_t y, uint32_t z) {
        const uint64_t i = (uint64_t{z} * ny + y) * nx + x;
        if (outside[i] || field.values[i] < 0.0f) return;
        outside[i] = 1;
        stack.push_back(i);
    };
    for (uint32_t z = 0; z < nz; ++z)
        for (uint32_t y = 0; y < ny; ++y)
            for (uint32_t x = 0; x < nx; ++x)
                if (x == 0 || y == 0 || z == 0 || x + 1 == nx || y + 1 == ny || z + 1 == nz) push(x, y, z);
    while (!stack.empty()) {
        const uint64_t i = stack.back();
        stack.pop_back();
        const auto x = static_cast<uint32_t>(i % nx), y = static_cast<uint32_t>((i / nx) % ny), z = static_cast<uint32_t>(i / (uint64_t{nx} * ny));
        if (x > 0) push(x - 1, y, z);
        if (x + 1 < nx) push(x + 1, y, z);
        if (y > 0) push(x, y - 1, z);
        if (y + 1 < ny) push(x, y + 1, z);
        if (z > 0) push(x, y, z - 1);
        if (z + 1 < nz) push(x, y, z + 1);
    }
    for (size_t i = 0; i < field.values.size(); ++i)
        if (!outside[i] && field.values[i] > 0.0f) field.values[i] = -field.values[i];
}

float SampledField::sample(glm::vec3 p) const {
    const glm::vec3 g = glm::clamp((p - origin) / cell, glm::vec3(0.0f), glm::vec3(nx - 1, ny - 1, nz - 1) - 1e-4f);
    const glm::uvec3 i(g);
    const glm::vec3 f = g - glm::vec3(i);
    auto at = [&](uint32_t x, uint32_t y, uint32_t z) { return values[(size_t{z} * ny + y) * nx + x]; };
    const float c00 = glm::mix(at(i.x, i.y, i.z), at(i.x + 1, i.y, i.z), f.x);
    const float c10 = glm::mix(at(i.x, i.y + 1, i.z), at(i.x + 1, i.y + 1, i.z), f.x);
    const float c01 = glm::mix(at(i.x, i.y, i.z + 1), at(i.x + 1, i.y, i.z + 1), f.x);
    const float c11 = glm::mix(at(i.x, i.y + 1, i.z + 1), at(i.x + 1, i.y + 1, i.z + 1), f.x);
    return glm::mix(glm::mix(c00, c10, f.y), glm::mix(c01, c11, f.y), f.z);
}

glm::vec3 SampledField::gradient(glm::vec3 p) const {
    const float h = 0.5f * cell;
    return glm::vec3(sample(p + glm::vec3(h, 0, 0)) - sample(p - glm::vec3(h, 0, 0)),
                     sample(p + glm::vec3(0, h, 0)) - sample(p - glm::vec3(0, h, 0)),
                     sample(p + glm::vec3(0, 0, h)) - sample(p - glm::vec3(0, 0, h))) /
           (2.0f * h);
}

TriangleSurface polygonise(const SampledField& field) {
    TriangleSurface out;
    const uint32_t nx = field.nx, ny = field.ny, nz = field.nz;
    auto id = [&](uint32_t x, uint32_t y, uint32_t z) { return (uint64_t{z} * ny + y) * nx + x; };
    auto point = [&](uint64_t i) {
        const uint64_t x = i % nx, y = (i / nx) % ny, z = i / (uint64_t{nx} * ny);
        return field.origin + field.cell * glm::vec3(x, y, z);
    };
    std::unordered_map<uint64_t, uint32_t> edge_vertex;
    const uint64_t total = uint64_t{nx} * ny * nz;
    // One vertex per crossed grid edge (a, b), at the linear zero crossing.
    auto vertex = [&](uint64_t a, uint64_t b) {
        if (a > b) std::swap(a, b);
        const auto [it, inserted] = edge_vertex.try_emplace(a * total + b, static_cast<uint32_t>(out.positions.size()));
        if (inserted) {
            const float fa = field.values[a], fb = field.values[b];
            out.positions.push_back(glm::mix(point(a), point(b), fa / (fa - fb)));
        }
        return it->second;
    };
    // Emits triangle (a, b, c) facing from the inside points towards the outside ones.
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c, glm::vec3 outward) {
        const glm::vec3 n = glm::cross(out.positions[b] - out.positions[a], out.positions[c] - out.positions[a]);
        if (glm::dot(n, outward) < 0.0f) std::swap(b, c);
        out.indices.insert(out.indices.end(), {a, b, c});
    };
    // The six Kuhn tetrahedra of a cube: corners 0 and 7 plus a monotone path between them.
    static constexpr std::array<std::array<int, 4>, 6> kTets{{{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                                              {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}}};
    for (uint32_t z = 0; z + 1 < nz; ++z)
        for (uint32_t y = 0; y + 1 < ny; ++y)
            for (uint32_t x = 0; x + 1 < nx; ++x) {
                uint64_t corner[8];
                int inside = 0;
                for (int c = 0; c < 8; ++c) {
                    corner[c] = id(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
                    inside += field.values[corner[c]] < 0.0f;
                }
                if (inside == 0 || inside == 8) continue;
                for (const auto& tet : kTets) {
                    uint64_t in[4], outp[4];
                    int ni = 0, no = 0;
                    for (int v : tet) (field.values[corner[v]] < 0.0f ? in[ni++] : outp[no++]) = corner[v];
                    if (ni == 0 || no == 0) continue;
                    glm::vec3 ci(0.0f), co(0.0f);
                    for (int i = 0; i < ni; ++i) ci += point(in[i]) / static_cast<float>(ni);
                    for (int i = 0; i < no; ++i) co += point(outp[i]) / static_cast<float>(no);
                    const glm::vec3 outward = co - ci;
                    if (ni == 1) {
                        emit(vertex(in[0], outp[0]), vertex(in[0], outp[1]), vertex(in[0], outp[2]), outward);
                    } else if (ni == 3) {
                        emit(vertex(outp[0], in[0]), vertex(outp[0], in[1]), vertex(outp[0], in[2]), outward);
                    } else {  // quad: (i0 o0) (i0 o1) (i1 o1) (i1 o0) is a cycle
                        const uint32_t a = vertex(in[0], outp[0]), b = vertex(in[0], outp[1]);
                        const uint32_t c = vertex(in[1], outp[1]), d = vertex(in[1], outp[0]);
                        emit(a, b, c, outward);
                        emit(a, c, d, outward);
                    }
                }
            }
    return out;
}

}  // namespace aloha
