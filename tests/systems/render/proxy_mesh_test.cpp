// The unit proxy box: geometry, the shader's index arithmetic, and bone placement.
#include "systems/render/proxy_mesh.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace aloha {
namespace {

TEST(ProxyMesh, UnitBoxFacesAreOutwardAndCounterClockwise) {
    const BoxMesh box = make_unit_box();
    for (uint32_t t = 0; t < kBoxIndexCount; t += 3) {
        const glm::vec3 a = box.positions[box.indices[t]], b = box.positions[box.indices[t + 1]],
                        c = box.positions[box.indices[t + 2]];
        const glm::vec3 n = box.normals[box.indices[t]];
        // Cross product of the edges has length 2 * area = 2 * 0.5 (half of a unit face) along n.
        const glm::vec3 cr = glm::cross(b - a, c - a);
        EXPECT_NEAR(glm::dot(cr, n), 1.0f, 1e-6f) << "triangle " << t / 3;
        EXPECT_NEAR(glm::dot(a, n), 0.5f, 1e-6f) << "face lies at distance 0.5 along its normal";
    }
}

TEST(ProxyMesh, BatchIndicesNameTheSameCornersAsTheBox) {
    const BoxMesh box = make_unit_box();
    std::vector<uint32_t> idx(3 * kBoxIndexCount);
    fill_box_batch_indices(3, idx);
    for (uint32_t b = 0; b < 3; ++b)
        for (uint32_t k = 0; k < kBoxIndexCount; ++k) {
            const uint32_t i = idx[b * kBoxIndexCount + k];
            ASSERT_EQ(i / kBoxCornerCount, b);
            // The shader's corner position (bit c -> +0.5) equals the box vertex the triangle uses.
            const uint32_t c = i % kBoxCornerCount;
            const glm::vec3 p(float(c & 1u) - 0.5f, float((c >> 1) & 1u) - 0.5f, float((c >> 2) & 1u) - 0.5f);
            EXPECT_EQ(p, box.positions[box.indices[k]]);
        }
}

TEST(ProxyMesh, BoneBoxSpansTheBone) {
    const glm::vec3 a(1, 2, 3), b(1, 4, 3);
    const glm::mat4 m = bone_box_matrix(a, b, 0.2f);
    EXPECT_NEAR(glm::distance(glm::vec3(m * glm::vec4(0, -0.5f, 0, 1)), a), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(glm::vec3(m * glm::vec4(0, 0.5f, 0, 1)), b), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::vec3(m[0])), 0.2f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::vec3(m[2])), 0.2f, 1e-6f);
}

}  // namespace
}  // namespace aloha
