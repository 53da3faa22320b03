// The blended skin's roots and rest ends: the four-lane form equals the scalar form bit for bit on arbitrary (sheared,
// noisy) muscle grids and bindings, zero weights anywhere among the influences, cells at the last vertex of the last
// muscle; it declines a degenerate frame (exactly at a pole); the four-lane spring step equals SpringStepper::step()
// (limits, zero-length and non-finite springs included); and BlendSpringJob, which uses them, places and steps every
// vertex exactly as the scalar forms do.
#include "systems/geometry/body_skin/blend_rest.hpp"
#include "tests/systems/geometry/spring_skin/test_grids.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace aloha {
namespace {

constexpr uint32_t kT = 16, kP = 12, kMuscles = 3;
constexpr float kPi = std::numbers::pi_v<float>;

// Three sheared ellipsoids with noise on every position and normal (normals no longer unit, so the sampled normal's
// normalisation does real work).
test::Grids noisy_muscles(std::mt19937& rng) {
    test::Grids g;
    std::uniform_real_distribution<float> noise(-0.004f, 0.004f);
    for (uint32_t m = 0; m < kMuscles; ++m) {
        glm::mat4 place = glm::translate(glm::mat4(1.0f), glm::vec3(0.2f * static_cast<float>(m), 0.05f, -0.1f));
        place = glm::rotate(place, 0.4f + static_cast<float>(m), glm::normalize(glm::vec3(1, 2, 3)));
        place[1][0] = 0.3f;  // shear
        test::append_ellipsoid(g, kT, kP, glm::vec3(0.1f, 0.04f, 0.03f), place);
    }
    for (glm::vec3& p : g.positions) p += glm::vec3(noise(rng), noise(rng), noise(rng));
    for (glm::vec3& n : g.normals) n = 1.3f * n + 25.0f * glm::vec3(noise(rng), noise(rng), noise(rng));
    return g;
}

// Bindings with 1 to 4 active influences, zero weights at any slot; every 16th binding's first influence sits just
// below the last muscle's north pole (its upper corners: the spans' last vertex).
std::vector<BlendBinding> random_bindings(std::mt19937& rng, size_t count) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), offset(-0.03f, 0.03f);
    std::vector<BlendBinding> out(count);
    for (size_t i = 0; i < count; ++i) {
        BlendBinding& b = out[i];
        float sum = 0.0f;
        for (int k = 0; k < kBlendInfluences; ++k) {
            b.muscle[k] = static_cast<uint32_t>(rng() % kMuscles);
            b.param[k] = {kPi * (2.0f * unit(rng) - 1.0f), 0.5f * kPi * (2.0f * unit(rng) - 1.0f)};
            if (k == 0 && i % 16 == 5) {
                b.muscle[k] = kMuscles - 1;
                b.param[k].phi = 0.5f * kPi - 0.05f;
            }
            b.cell[k] = grid_cell(kT, kP, b.param[k]);
            b.offset[k] = {offset(rng), offset(rng), offset(rng)};
            b.weight[k] = (k == 0 || rng() % 3 != 0) ? 0.1f + unit(rng) : 0.0f;
            sum += b.weight[k];
        }
        for (float& w : b.weight) w /= sum;
    }
    return out;
}

void expect_same_bits(glm::vec3 a, glm::vec3 b, size_t vertex) {
    for (int c = 0; c < 3; ++c)
        EXPECT_EQ(std::bit_cast<uint32_t>(a[c]), std::bit_cast<uint32_t>(b[c])) << "vertex " << vertex << " axis " << c;
}

TEST(BlendRest, FourLanesEqualTheScalarFormBitForBit) {
    std::mt19937 rng(7);
    const test::Grids g = noisy_muscles(rng);
    const std::vector<BlendBinding> bindings = random_bindings(rng, 4096);
    const uint32_t V = grid_vertex_count(kT, kP);
    for (const bool avx : {false, true}) {  // the SSE2 encoding, then the AVX one where the CPU has it
        size_t vectorised = 0;
        for (size_t i0 = 0; i0 < bindings.size(); i0 += 4) {
            float root[3][4], rest[3][4];
            if (!blend_rest_x4(g.positions, g.normals, V, &bindings[i0], root, rest, avx)) continue;
            ++vectorised;
            for (size_t lane = 0; lane < 4; ++lane) {
                glm::vec3 r, y;
                blend_rest(g.positions, g.normals, V, bindings[i0 + lane], r, y);
                expect_same_bits({root[0][lane], root[1][lane], root[2][lane]}, r, i0 + lane);
                expect_same_bits({rest[0][lane], rest[1][lane], rest[2][lane]}, y, i0 + lane);
            }
        }
#if defined(__SSE2__) || defined(_M_X64)
        EXPECT_EQ(vectorised, bindings.size() / 4);  // no frame here is degenerate
#endif
    }
}

TEST(BlendRest, FourLanesDeclineADegenerateFrameAtAPole) {
    std::mt19937 rng(11);
    const test::Grids g = noisy_muscles(rng);
    std::vector<BlendBinding> bindings = random_bindings(rng, 4);
    // Exactly at the north pole the cell's upper corners are one vertex and the tangent vanishes.
    bindings[2].param[0] = {0.3f, 0.5f * kPi};
    bindings[2].cell[0] = grid_cell(kT, kP, bindings[2].param[0]);
    ASSERT_EQ(bindings[2].cell[0].fr, 1.0f);
    float root[3][4], rest[3][4];
    for (const bool avx : {false, true})
        EXPECT_FALSE(blend_rest_x4(g.positions, g.normals, grid_vertex_count(kT, kP), bindings.data(), root, rest, avx));
}

TEST(BlendRest, SpringJobPlacesTheSkinWhereTheScalarFormDoes) {
    std::mt19937 rng(3);
    const test::Grids g = noisy_muscles(rng);
    std::vector<BlendBinding> bindings = random_bindings(rng, 4 * 50 + 3);  // a partial last group
    bindings[9].param[1] = {-1.0f, -0.5f * kPi};                            // a south-pole frame
    bindings[9].cell[1] = grid_cell(kT, kP, bindings[9].param[1]);
    bindings[9].weight[1] = bindings[9].weight[0];
    std::vector<glm::vec3> out(bindings.size());
    FatSpringParams params;
    params.dt = 1.0f / 30.0f;
    const BlendSpringJob job{kT, kP, kMuscles, params, false, g.positions, g.normals, bindings, {out, {}, {}, {}}};
    ASSERT_TRUE(job.Validate());
    job.Run();
    for (size_t i = 0; i < bindings.size(); ++i) {
        glm::vec3 r, y;
        blend_rest(g.positions, g.normals, grid_vertex_count(kT, kP), bindings[i], r, y);
        expect_same_bits(out[i], y, i);
    }
}

// Per-lane different tunings; lanes that hit the strain limit, the rate limit, a zero-length spring and a non-finite
// state: four lanes equal SpringStepper::step() one by one, bit for bit.
TEST(BlendRest, FourSpringStepsEqualTheScalarStepBitForBit) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    FatSpringParams soft, stiff;
    soft.dt = stiff.dt = 1.0f / 30.0f;
    stiff.normal_hz = 9.0f;
    stiff.lateral_hz = 7.0f;
    stiff.normal_damping = 0.3f;
    stiff.max_strain = 0.2f;
    const SpringStepper steppers[2] = {SpringStepper(soft), SpringStepper(stiff)};
    for (int round = 0; round < 2000; ++round) {
        float root[3][4], rest[3][4];
        glm::vec3 end[4], velocity[4], prev[4];
        const SpringStepper* tuned[4];
        const float reach = round % 3 == 0 ? 0.2f : 0.01f;  // a third far enough out for the limits
        for (int lane = 0; lane < 4; ++lane) {
            for (int a = 0; a < 3; ++a) {
                root[a][lane] = 0.1f * u(rng);
                rest[a][lane] = root[a][lane] + 0.02f * u(rng);
            }
            const glm::vec3 y{rest[0][lane], rest[1][lane], rest[2][lane]};
            prev[lane] = y + 0.01f * glm::vec3(u(rng), u(rng), u(rng));
            end[lane] = y + reach * glm::vec3(u(rng), u(rng), u(rng));
            velocity[lane] = 10.0f * reach * glm::vec3(u(rng), u(rng), u(rng));
            tuned[lane] = &steppers[rng() % 2];
        }
        if (round % 7 == 1)
            for (int a = 0; a < 3; ++a) root[a][2] = rest[a][2];  // zero length: +z normal
        if (round % 11 == 2) end[1].y = std::numeric_limits<float>::infinity();
        if (round % 13 == 3) velocity[3].x = std::numeric_limits<float>::quiet_NaN();
        glm::vec3 e[4], v[4], p[4];
        for (int lane = 0; lane < 4; ++lane) {
            e[lane] = end[lane];
            v[lane] = velocity[lane];
            p[lane] = prev[lane];
            const glm::vec3 r{root[0][lane], root[1][lane], root[2][lane]}, y{rest[0][lane], rest[1][lane], rest[2][lane]};
            const float h = glm::length(y - r);
            const glm::vec3 n = h > 1e-6f ? (y - r) / h : glm::vec3(0.0f, 0.0f, 1.0f);
            tuned[lane]->step(y, n, h, e[lane], v[lane], p[lane]);
        }
        for (const bool avx : {false, true}) {  // the SSE2 encoding, then the AVX one where the CPU has it
            glm::vec3 end4[4], velocity4[4], prev4[4];
            std::copy(end, end + 4, end4);
            std::copy(velocity, velocity + 4, velocity4);
            std::copy(prev, prev + 4, prev4);
            spring_step_x4(root, rest, tuned, end4, velocity4, prev4, avx);
            for (size_t lane = 0; lane < 4; ++lane) {
                expect_same_bits(end4[lane], e[lane], lane);
                expect_same_bits(velocity4[lane], v[lane], lane);
                expect_same_bits(prev4[lane], p[lane], lane);
            }
        }
    }
}

// Several frames of the springs on moving muscles, with a tuning per vertex: the job (four lanes where it can) equals
// blend_rest() + SpringStepper::step() vertex by vertex, bit for bit.
TEST(BlendRest, SpringJobStepsTheSpringsAsTheScalarFormDoes) {
    std::mt19937 rng(9);
    const test::Grids rest_muscles = noisy_muscles(rng);
    std::vector<BlendBinding> bindings = random_bindings(rng, 4 * 40 + 2);
    bindings[6].param[0] = {0.5f, 0.5f * kPi};  // a north-pole frame: its four vertices go one by one
    bindings[6].cell[0] = grid_cell(kT, kP, bindings[6].param[0]);
    const size_t n = bindings.size();
    std::vector<uint8_t> region(n);
    for (size_t i = 0; i < n; ++i) region[i] = static_cast<uint8_t>(i % 3 == 0);
    FatSpringParams tunings[2];
    tunings[0].dt = tunings[1].dt = 1.0f / 30.0f;
    tunings[1].normal_hz = 8.0f;
    tunings[1].max_strain = 0.1f;
    std::vector<glm::vec3> end(n), velocity(n), prev(n), ref_end(n), ref_velocity(n), ref_prev(n);
    uint8_t initialised = 0;
    const uint32_t V = grid_vertex_count(kT, kP);
    for (int frame = 0; frame < 6; ++frame) {
        test::Grids m = rest_muscles;  // the muscles bulge and move from frame to frame
        const float s = 1.0f + 0.15f * static_cast<float>(frame % 3);
        for (glm::vec3& p : m.positions) p = s * p + glm::vec3(0.03f * static_cast<float>(frame), 0.0f, 0.0f);
        const BlendSpringJob job{kT,         kP,       kMuscles,
                                 tunings[0], true,     m.positions,
                                 m.normals,  bindings, {end, velocity, prev, std::span(&initialised, 1)},
                                 region,     tunings};
        ASSERT_TRUE(job.Validate());
        job.Run();
        const SpringStepper steppers[2] = {SpringStepper(tunings[0]), SpringStepper(tunings[1])};
        for (size_t i = 0; i < n; ++i) {
            glm::vec3 r, y;
            blend_rest(m.positions, m.normals, V, bindings[i], r, y);
            if (frame == 0) {
                ref_end[i] = ref_prev[i] = y;
                ref_velocity[i] = glm::vec3(0.0f);
                continue;
            }
            // The first step after the start gives each spring its rest end's velocity (kSpringsStarted).
            if (frame == 1) ref_velocity[i] = (y - ref_prev[i]) * steppers[0].inv_dt;
            const float h = glm::length(y - r);
            const glm::vec3 nrm = h > 1e-6f ? (y - r) / h : glm::vec3(0.0f, 0.0f, 1.0f);
            steppers[region[i]].step(y, nrm, h, ref_end[i], ref_velocity[i], ref_prev[i]);
        }
        for (size_t i = 0; i < n; ++i) {
            expect_same_bits(end[i], ref_end[i], i);
            expect_same_bits(velocity[i], ref_velocity[i], i);
            expect_same_bits(prev[i], ref_prev[i], i);
        }
    }
}

}  // namespace
}  // namespace aloha
