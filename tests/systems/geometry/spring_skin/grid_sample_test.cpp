// Grid sampling: the cell-based sampling (grid_cell computed once, then gathers and arithmetic, as the
// per-frame skin uses it) gives exactly the bits of the param-based sampling, and of a copy of the
// param-based code as it was before cells existed (the World state hash depends on every bit).
#include "systems/geometry/spring_skin/grid_sample.hpp"
#include "tests/systems/geometry/spring_skin/test_grids.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace aloha {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// --- Reference: the param-based sampling as written before GridCell (recomputes the cell per call).
uint32_t ref_vertex_at(uint32_t T, uint32_t P, uint32_t r, uint32_t t) {
    if (r == 0) return 0;
    if (r >= P) return grid_vertex_count(T, P) - 1;
    return grid_ring_vertex(T, r, t % T);
}

void ref_continuous_coords(uint32_t T, uint32_t P, GridParam param, float& rf, float& tf) {
    rf = std::clamp((param.phi + 0.5f * kPi) * static_cast<float>(P) / kPi, 0.0f, static_cast<float>(P));
    tf = (param.theta + kPi) * static_cast<float>(T) / (2.0f * kPi);
    tf = tf - std::floor(tf / static_cast<float>(T)) * static_cast<float>(T);
    if (!(tf < static_cast<float>(T))) tf = 0.0f;
}

glm::vec3 ref_sample(std::span<const glm::vec3> values, uint32_t T, uint32_t P, GridParam param) {
    float rf = 0.0f, tf = 0.0f;
    ref_continuous_coords(T, P, param, rf, tf);
    const uint32_t r0 = std::min(static_cast<uint32_t>(rf), P - 1);
    const uint32_t t0 = std::min(static_cast<uint32_t>(tf), T - 1);
    const float fr = rf - static_cast<float>(r0), ft = tf - static_cast<float>(t0);
    const glm::vec3 low = glm::mix(values[ref_vertex_at(T, P, r0, t0)], values[ref_vertex_at(T, P, r0, t0 + 1)], ft);
    const glm::vec3 high = glm::mix(values[ref_vertex_at(T, P, r0 + 1, t0)], values[ref_vertex_at(T, P, r0 + 1, t0 + 1)], ft);
    return glm::mix(low, high, fr);
}

GridFrame ref_frame(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, uint32_t T, uint32_t P,
                    GridParam param) {
    GridFrame frame;
    frame.point = ref_sample(positions, T, P, param);
    glm::vec3 n = ref_sample(normals, T, P, param);
    const float nlen = glm::length(n);
    frame.normal = nlen > 1e-20f ? n / nlen : glm::vec3(0.0f, 0.0f, 1.0f);
    float rf = 0.0f, tf = 0.0f;
    ref_continuous_coords(T, P, param, rf, tf);
    const uint32_t r0 = std::min(static_cast<uint32_t>(rf), P - 1);
    const uint32_t t0 = std::min(static_cast<uint32_t>(tf), T - 1);
    const float fr = rf - static_cast<float>(r0);
    const glm::vec3 d_low = positions[ref_vertex_at(T, P, r0, t0 + 1)] - positions[ref_vertex_at(T, P, r0, t0)];
    const glm::vec3 d_high = positions[ref_vertex_at(T, P, r0 + 1, t0 + 1)] - positions[ref_vertex_at(T, P, r0 + 1, t0)];
    glm::vec3 tangent = glm::mix(d_low, d_high, fr);
    tangent -= glm::dot(tangent, frame.normal) * frame.normal;
    float tlen = glm::length(tangent);
    if (!(tlen > 1e-12f)) {
        const glm::vec3 axis = std::abs(frame.normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        tangent = axis - glm::dot(axis, frame.normal) * frame.normal;
        tlen = glm::length(tangent);
    }
    frame.tangent = tangent / tlen;
    frame.bitangent = glm::cross(frame.normal, frame.tangent);
    return frame;
}
// --- End of reference.

std::array<uint32_t, 3> bits(glm::vec3 v) {
    return {std::bit_cast<uint32_t>(v.x), std::bit_cast<uint32_t>(v.y), std::bit_cast<uint32_t>(v.z)};
}

// Parameters covering the grid: random ones, every vertex's own, the poles, theta at and past +-pi
// (wrap), phi past the poles (clamped).
std::vector<GridParam> params_for(uint32_t T, uint32_t P) {
    std::vector<GridParam> out;
    std::mt19937 rng(T * 131 + P);
    std::uniform_real_distribution<float> theta(-1.2f * kPi, 1.2f * kPi), phi(-0.6f * kPi, 0.6f * kPi);
    for (int i = 0; i < 400; ++i) out.push_back({theta(rng), phi(rng)});
    for (uint32_t i = 0; i < grid_vertex_count(T, P); ++i) out.push_back(grid_vertex_param(T, P, i));
    for (const float th : {-kPi, kPi, std::nextafter(kPi, 0.0f), std::nextafter(-kPi, -4.0f), 0.0f})
        for (const float ph : {-0.5f * kPi, 0.5f * kPi, 0.0f, -kPi, kPi}) out.push_back({th, ph});
    return out;
}

TEST(GridSample, CellSamplingHasTheBitsOfParamSampling) {
    for (const auto [T, P] : {std::array<uint32_t, 2>{3, 2}, {8, 6}, {7, 5}, {16, 12}, {24, 18}}) {
        const test::Grids g = test::ellipsoid(T, P, {0.06f, 0.045f, 0.15f},
                                              glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, -0.2f, 0.9f)), 0.7f,
                                                          glm::normalize(glm::vec3(1, 2, 3))));
        const std::span<const glm::vec3> pos = g.positions, nrm = g.normals;
        for (const GridParam& p : params_for(T, P)) {
            const GridCell cell = grid_cell(T, P, p);
            for (const uint32_t c : cell.corner) ASSERT_LT(c, grid_vertex_count(T, P));
            EXPECT_EQ(bits(sample_grid(pos, cell)), bits(ref_sample(pos, T, P, p))) << T << "x" << P << " " << p.theta << "," << p.phi;
            EXPECT_EQ(bits(sample_grid(pos, T, P, p)), bits(ref_sample(pos, T, P, p)));
            const GridFrame a = sample_grid_frame(pos, nrm, cell), b = sample_grid_frame(pos, nrm, T, P, p);
            const GridFrame r = ref_frame(pos, nrm, T, P, p);
            for (const GridFrame* f : {&a, &b}) {
                EXPECT_EQ(bits(f->point), bits(r.point)) << T << "x" << P << " " << p.theta << "," << p.phi;
                EXPECT_EQ(bits(f->tangent), bits(r.tangent));
                EXPECT_EQ(bits(f->bitangent), bits(r.bitangent));
                EXPECT_EQ(bits(f->normal), bits(r.normal));
            }
        }
    }
}

TEST(GridSample, CellFractionsAreInTheUnitInterval) {
    for (const auto [T, P] : {std::array<uint32_t, 2>{3, 2}, {8, 6}, {16, 12}}) {
        for (const GridParam& p : params_for(T, P)) {
            const GridCell cell = grid_cell(T, P, p);
            EXPECT_GE(cell.ft, 0.0f);
            EXPECT_LE(cell.ft, 1.0f);
            EXPECT_GE(cell.fr, 0.0f);
            EXPECT_LE(cell.fr, 1.0f);
        }
    }
}

}  // namespace
}  // namespace aloha
