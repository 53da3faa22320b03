// Fat springs: rest state, joint snap stability (no NaN, decaying energy, bounded strain).
#include "systems/geometry/spring_skin/fat_spring.hpp"
#include "tests/systems/geometry/spring_skin/test_grids.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace aloha {
namespace {

constexpr uint32_t kT = 12, kP = 8;

TEST(FatSpring, StaticMuscleKeepsEndsAtRestLength) {
    const test::Grids g = test::ellipsoid(kT, kP, {0.05f, 0.04f, 0.12f});
    const std::vector<float> thickness{0.02f};
    FatSpringPool pool(1, 1, kT, kP);
    FatSpringJob job;
    job.theta_steps = kT;
    job.phi_steps = kP;
    job.muscle_positions = g.positions;
    job.muscle_normals = g.normals;
    job.thickness = thickness;
    job.state = pool.view(0, 1);
    std::vector<std::string> errors;
    ASSERT_TRUE(job.Validate(&errors)) << errors.front();
    for (int frame = 0; frame < 20; ++frame) job.Run();
    for (size_t i = 0; i < g.positions.size(); ++i) {
        // Exact: a static target gives d0 = 0, u0 = 0, and the transition of zero is zero.
        const glm::vec3 rest = g.positions[i] + thickness[0] * g.normals[i];
        EXPECT_NEAR(glm::length(job.state.end[i] - rest), 0.0f, 1e-6f);
    }
}

TEST(FatSpring, ValidateListsEveryFailure) {
    FatSpringJob job;
    job.theta_steps = 2;
    job.phi_steps = 1;
    job.params.dt = 0.0f;
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 3u);  // theta, phi, dt (sizes are not checked without a valid grid)

    const test::Grids g = test::ellipsoid(kT, kP, glm::vec3(0.1f));
    const std::vector<float> thickness{0.01f, 0.01f};  // one too many
    FatSpringPool pool(1, 1, kT, kP);
    FatSpringJob sized;
    sized.theta_steps = kT;
    sized.phi_steps = kP;
    sized.muscle_positions = g.positions;
    sized.thickness = thickness;
    sized.state = pool.view(0, 1);
    errors.clear();
    EXPECT_FALSE(sized.Validate(&errors));
    EXPECT_EQ(errors.size(), 3u);  // normals missing, thickness count, initialised flag count
}

// The muscle (long axis along +y, 0.15 m from the joint at the origin) rotates 180 degrees about
// the joint's z axis in a single frame at dt = 1/30 s, then holds still.
TEST(FatSpring, JointSnapIsStableWithDecayingEnergyAndBoundedStrain) {
    const float pi = std::numbers::pi_v<float>;
    const float h = 0.015f;
    FatSpringParams params;  // defaults: 12 Hz, zeta 0.6, lateral 8 Hz, max strain 0.5, dt 1/30
    auto muscle_at = [&](float angle) {
        const glm::mat4 place = glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 0, 1)) *
                                glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.15f, 0)) *
                                glm::rotate(glm::mat4(1.0f), 0.5f * pi, glm::vec3(1, 0, 0));
        return test::ellipsoid(kT, kP, {0.04f, 0.04f, 0.12f}, place);
    };
    const test::Grids before = muscle_at(0.0f), after = muscle_at(pi);
    const std::vector<float> thickness{h};
    FatSpringPool pool(1, 1, kT, kP);
    const int snap = 5, frames = 45;
    std::vector<float> energy;
    std::vector<glm::vec3> prev_rest(before.positions.size());
    float max_strain = 0.0f;
    for (int frame = 0; frame < frames; ++frame) {
        const test::Grids& g = frame < snap ? before : after;
        FatSpringJob job;
        job.theta_steps = kT;
        job.phi_steps = kP;
        job.params = params;
        job.muscle_positions = g.positions;
        job.muscle_normals = g.normals;
        job.thickness = thickness;
        job.state = pool.view(0, 1);
        job.Run();
        float e = 0.0f;
        for (size_t i = 0; i < g.positions.size(); ++i) {
            const glm::vec3 rest = g.positions[i] + h * g.normals[i];
            const glm::vec3 end = job.state.end[i];
            ASSERT_TRUE(std::isfinite(end.x) && std::isfinite(end.y) && std::isfinite(end.z)) << "frame " << frame;
            const glm::vec3 w = frame == 0 ? glm::vec3(0.0f) : (rest - prev_rest[i]) / params.dt;
            e += fat_spring_energy(params, end, job.state.velocity[i], rest, w, g.normals[i]);
            max_strain = std::max(max_strain, std::abs(glm::length(end - g.positions[i]) - h) / h);
            prev_rest[i] = rest;
        }
        energy.push_back(e);
    }
    // Before the snap the springs sit at rest.
    EXPECT_LT(energy[snap - 1], 1e-6f);
    const float peak = *std::max_element(energy.begin(), energy.end());
    EXPECT_GT(peak, 1e-3f) << "the snap must actually excite the springs";
    // Energy enters at the snap frame and at the next one (the root velocity jumps twice: to
    // 2 * 0.15 m / dt and back to 0); from then on the targets are still, the exact damped step never
    // increases energy and strain limiting only removes it. Tolerance: float rounding of a sum of
    // ~100 terms, relative 1e-4.
    for (int k = snap + 2; k + 1 < frames; ++k) {
        EXPECT_LE(energy[k + 1], energy[k] * (1.0f + 1e-4f) + 1e-12f) << "frame " << k + 1;
    }
    // Normal decay rate zeta * w0 = 0.6 * 2 pi * 12 = 45 /s: energy falls by exp(-2 * 45 / 30) ~ 0.05
    // per frame, so 30 frames later it is far below 1e-6 of the peak.
    EXPECT_LT(energy.back(), 1e-6f * peak);
    // Strain bound: |end - rest_end| <= max_strain * h after limiting and
    // | |end - root| - h | <= |end - rest_end| (triangle inequality), so |strain| <= max_strain.
    // Tolerance: float rounding of positions ~0.3 m (3e-8) divided by h = 0.015 -> ~1e-5.
    EXPECT_LE(max_strain, params.max_strain + 1e-4f);
    EXPECT_GT(max_strain, 0.5f * params.max_strain) << "the snap should drive the springs to the limit";
}

// After a one-frame thickness step the target stands still, so the deviation along the normal must
// follow the continuous damped oscillator d(t) = e^{-z w t} (d1 cos(wd t) + (u1 + z w d1) / wd sin(wd t))
// sampled every dt (the step is exact, not an approximation). Slow, lightly damped spring and no
// strain limiting so several oscillations are visible.
TEST(FatSpring, FreeRingingMatchesTheAnalyticDampedOscillator) {
    const test::Grids g = test::ellipsoid(6, 4, glm::vec3(0.1f));
    std::vector<float> thickness{0.02f};
    FatSpringPool pool(1, 1, 6, 4);
    FatSpringJob job;
    job.theta_steps = 6;
    job.phi_steps = 4;
    job.params.normal_hz = 2.0f;
    job.params.normal_damping = 0.2f;
    job.params.max_strain = 100.0f;
    job.muscle_positions = g.positions;
    job.muscle_normals = g.normals;
    job.thickness = thickness;
    job.state = pool.view(0, 1);
    job.Run();               // start at rest
    thickness[0] = 0.03f;    // the fat swells by 1 cm in one frame
    job.Run();
    const size_t i = 5;
    const glm::vec3 n = g.normals[i], rest = g.positions[i] + thickness[0] * n;
    const double d1 = glm::dot(job.state.end[i] - rest, n), u1 = glm::dot(job.state.velocity[i], n);
    const double w = 2.0 * std::numbers::pi * 2.0, z = 0.2, wd = w * std::sqrt(1.0 - z * z);
    double amplitude = std::abs(d1);
    int sign_changes = 0;
    double previous = d1;
    for (int k = 1; k <= 60; ++k) {
        job.Run();
        const double t = k * static_cast<double>(job.params.dt);
        const double expected = std::exp(-z * w * t) * (d1 * std::cos(wd * t) + (u1 + z * w * d1) / wd * std::sin(wd * t));
        const double actual = glm::dot(job.state.end[i] - rest, n);
        // Tolerance: float state (~1e-7 relative of 0.1 m positions) accumulated over 60 steps, 1e-6 m.
        EXPECT_NEAR(actual, expected, 1e-6) << "frame " << k;
        amplitude = std::max(amplitude, std::abs(actual));
        sign_changes += (actual > 0.0) != (previous > 0.0);
        previous = actual;
    }
    EXPECT_GT(amplitude, 1e-3);      // the step did excite the spring
    EXPECT_GE(sign_changes, 6);      // 2 s at 2 Hz damped frequency: about 8 crossings
}

TEST(FatSpring, ResetRestartsACharacterAtRest) {
    const test::Grids a = test::ellipsoid(kT, kP, glm::vec3(0.05f));
    test::Grids b = a;
    for (glm::vec3& p : b.positions) p += glm::vec3(0.3f, 0.0f, 0.0f);
    const std::vector<float> thickness{0.01f, 0.01f};
    test::Grids both = a;
    both.positions.insert(both.positions.end(), a.positions.begin(), a.positions.end());
    both.normals.insert(both.normals.end(), a.normals.begin(), a.normals.end());
    FatSpringPool pool(2, 1, kT, kP);
    EXPECT_EQ(pool.spring_count(), 2u * grid_vertex_count(kT, kP));
    FatSpringJob job;
    job.theta_steps = kT;
    job.phi_steps = kP;
    job.muscle_positions = both.positions;
    job.muscle_normals = both.normals;
    job.thickness = thickness;
    job.state = pool.view(0, 2);
    job.Run();
    // Teleport character 1 and reset it: it restarts exactly at rest, character 0 is untouched.
    std::copy(b.positions.begin(), b.positions.end(), both.positions.begin() + static_cast<ptrdiff_t>(a.positions.size()));
    pool.reset(1);
    job.Run();
    const size_t V = a.positions.size();
    for (size_t i = 0; i < V; ++i) {
        EXPECT_NEAR(glm::length(job.state.end[V + i] - (b.positions[i] + 0.01f * b.normals[i])), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(job.state.velocity[V + i]), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(job.state.end[i] - (a.positions[i] + 0.01f * a.normals[i])), 0.0f, 1e-6f);
    }
}

}  // namespace
}  // namespace aloha
