// MuscleShapeJob + MuscleTessellateJob: volume preservation over a joint sweep, bulging across the
// elbow, vertex counts, normals, sphere case, mesh volume convergence and Validate().
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "systems/geometry/muscle/superellipsoid.hpp"
#include "systems/geometry/surface_grid.hpp"
#include "tests/systems/geometry/muscle/test_skeletons.hpp"
#include "tests/systems/geometry/muscle/grid_volume.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace aloha {
namespace {

// Biceps-like muscle: origin on the upper arm near the shoulder (front, +z), insertion on the
// forearm just below the elbow. Flexing the elbow about x swings the forearm forward (+z).
MuscleSet arm_muscles(const Skeleton& arm, glm::vec2 ab = {1, 1}) {
    MuscleDef d;
    d.name = "biceps";
    d.origin = {"Shoulder", 0.0f, {0.0f, -0.04f, 0.03f}};
    d.insertion = {"Elbow", 0.0f, {0.0f, -0.04f, 0.02f}};
    d.rest_radii = {0.03f, 0.025f};
    d.exponent_a = ab.x;
    d.exponent_b = ab.y;
    auto set = resolve_muscles(std::span<const MuscleDef>(&d, 1), arm, "arm");
    EXPECT_TRUE(set.ok()) << (set.ok() ? "" : set.error().to_string());
    return set.ok() ? set.value() : MuscleSet{};
}

struct Shapes {
    std::vector<glm::vec3> centres, radii;
    std::vector<glm::quat> rotations;
};

Shapes run_shapes(const MuscleSet& set, std::span<const glm::mat4> model) {
    Shapes s;
    const size_t n = model.size() / static_cast<size_t>(set.joint_count) * static_cast<size_t>(set.size());
    s.centres.resize(n);
    s.radii.resize(n);
    s.rotations.resize(n);
    MuscleShapeJob job{&set, model, s.centres, s.rotations, s.radii};
    std::vector<std::string> errors;
    EXPECT_TRUE(job.Validate(&errors)) << (errors.empty() ? "" : errors.front());
    job.Run();
    return s;
}


TEST(MuscleJobs, ElbowFlexionKeepsVolumeShortensAndThickens) {
    const Skeleton arm = test::make_arm_skeleton();
    const MuscleSet set = arm_muscles(arm);
    ASSERT_EQ(set.size(), 1);
    // 15 poses, elbow 0..140 degrees, evaluated as 15 characters in one job run.
    std::vector<glm::mat4> model;
    for (int k = 0; k < 15; ++k) {
        const float angle = glm::radians(10.0f * k);
        const glm::quat rot[3] = {glm::quat(1, 0, 0, 0), glm::angleAxis(-angle, glm::vec3(1, 0, 0)), glm::quat(1, 0, 0, 0)};
        const auto m = test::pose_model(arm, rot);
        model.insert(model.end(), m.begin(), m.end());
    }
    const Shapes s = run_shapes(set, model);
    const double v0 = set.volume[0];
    EXPECT_NEAR(v0, superellipsoid_volume({0.5 * set.rest_length[0], 0.03, 0.025}, 1, 1), 1e-6 * v0);
    for (size_t k = 0; k < s.radii.size(); ++k) {
        // Analytic volume of the generated radii: float rounding only (a few ulp), bound 1e-5 relative.
        EXPECT_NEAR(superellipsoid_volume(glm::dvec3(s.radii[k]), 1, 1) / v0, 1.0, 1e-5) << k;
        EXPECT_NEAR(s.radii[k].y / s.radii[k].z, 0.03 / 0.025, 1e-5);
        if (k > 0) {
            EXPECT_LT(s.radii[k].x, s.radii[k - 1].x) << "muscle must shorten as the elbow flexes, pose " << k;
            EXPECT_GT(s.radii[k].z, s.radii[k - 1].z) << "muscle must thicken as the elbow flexes, pose " << k;
        }
    }
    EXPECT_LT(s.radii.back().x, 0.8f * s.radii.front().x);  // visibly shorter at 140 degrees
}

TEST(MuscleJobs, VertexCountFollowsTheOneParameter) {
    const Skeleton arm = test::make_arm_skeleton();
    const MuscleSet set = arm_muscles(arm);
    const auto rest = rest_model_matrices(arm);
    std::vector<glm::mat4> model;
    for (int c = 0; c < 3; ++c) model.insert(model.end(), rest.begin(), rest.end());
    const Shapes s = run_shapes(set, model);
    for (const auto& [T, P] : {std::pair<uint32_t, uint32_t>{3, 2}, {8, 6}, {16, 12}, {33, 7}}) {
        const SuperEllipsoidTables tables(T, P, set);
        const size_t expected = 3u * static_cast<size_t>(set.size()) * (T * (P - 1) + 2);
        std::vector<glm::vec3> pos(expected), nrm(expected);
        MuscleTessellateJob job{&tables, s.centres, s.rotations, s.radii, pos, nrm};
        ASSERT_TRUE(job.Validate());
        job.Run();
        EXPECT_EQ(tables.vertices_per_muscle() * job.shape_count(), expected);
        std::vector<glm::vec3> short_pos(expected - 1);
        MuscleTessellateJob too_small{&tables, s.centres, s.rotations, s.radii, short_pos, nrm};
        EXPECT_FALSE(too_small.Validate());
    }
}

TEST(MuscleJobs, NormalsAreUnitAndOutward) {
    const Skeleton arm = test::make_arm_skeleton();
    for (const glm::vec2 ab : {glm::vec2(1, 1), glm::vec2(0.4f, 0.6f), glm::vec2(1.7f, 1.2f)}) {
        const MuscleSet set = arm_muscles(arm, ab);
        const glm::quat rot[3] = {glm::angleAxis(0.4f, glm::normalize(glm::vec3(1, 2, 3))),
                                  glm::angleAxis(-1.0f, glm::vec3(1, 0, 0)), glm::quat(1, 0, 0, 0)};
        const auto model = test::pose_model(arm, rot);
        const Shapes s = run_shapes(set, model);
        const SuperEllipsoidTables tables(24, 16, set);
        std::vector<glm::vec3> pos(tables.vertices_per_muscle()), nrm(pos.size());
        MuscleTessellateJob job{&tables, s.centres, s.rotations, s.radii, pos, nrm};
        ASSERT_TRUE(job.Validate());
        job.Run();
        const glm::mat3 R = glm::mat3_cast(s.rotations[0]);
        for (size_t v = 0; v < pos.size(); ++v) {
            EXPECT_NEAR(glm::length(nrm[v]), 1.0f, 1e-5f);  // one rsqrt-normalise in float: ~2 ulp
            EXPECT_GT(glm::dot(nrm[v], pos[v] - s.centres[0]), 0.0f);  // Euler: p . grad F = 2/A > 0
            // Each vertex lies on the implicit surface F = 1 (float positions: ~1e-4 after 2/A powers).
            const glm::dvec3 local = glm::transpose(R) * (pos[v] - s.centres[0]);
            EXPECT_NEAR(superellipsoid_implicit(local, glm::dvec3(s.radii[0]), ab.x, ab.y), 1.0, 5e-4);
        }
    }
}

TEST(MuscleJobs, UnitExponentsEqualRadiiGiveASphere) {
    MuscleSet set;
    set.joint_count = 1;
    set.push_back("ball", 0, {0, 0, 0}, 0, {0.2f, 0, 0}, {0, 0, 1}, 1.0f, 1.0f, {1, 1}, 0.0f, 0.2f);
    const std::vector<glm::vec3> centres{{0.3f, -0.2f, 0.5f}}, radii{{0.1f, 0.1f, 0.1f}};
    const std::vector<glm::quat> rot{glm::angleAxis(0.7f, glm::normalize(glm::vec3(-1, 2, 0.5f)))};
    const SuperEllipsoidTables tables(32, 17, set);
    std::vector<glm::vec3> pos(tables.vertices_per_muscle()), nrm(pos.size());
    MuscleTessellateJob job{&tables, centres, rot, radii, pos, nrm};
    ASSERT_TRUE(job.Validate());
    job.Run();
    for (size_t v = 0; v < pos.size(); ++v) {
        const glm::vec3 d = pos[v] - centres[0];
        // Float: table values and the rotation carry ~1e-7 relative error each; 1e-6 m on 0.1 m.
        EXPECT_NEAR(glm::length(d), 0.1f, 1e-6f) << v;
        EXPECT_NEAR(glm::length(nrm[v] - d / 0.1f), 0.0f, 2e-6f) << v;  // sphere normal = radial
    }
}

TEST(MuscleJobs, MeshVolumeConvergesToAnalyticVolume) {
    const Skeleton arm = test::make_arm_skeleton();
    for (const glm::vec2 ab : {glm::vec2(1, 1), glm::vec2(0.7f, 0.8f)}) {
        const MuscleSet set = arm_muscles(arm, ab);
        const auto model = rest_model_matrices(arm);
        const Shapes s = run_shapes(set, model);
        const double exact = superellipsoid_volume(glm::dvec3(s.radii[0]), ab.x, ab.y);
        double previous = 1.0;
        for (uint32_t T = 8; T <= 256; T *= 2) {
            const uint32_t P = T * 3 / 4;
            const SuperEllipsoidTables tables(T, P, set);
            std::vector<glm::vec3> pos(tables.vertices_per_muscle()), nrm(pos.size());
            MuscleTessellateJob job{&tables, s.centres, s.rotations, s.radii, pos, nrm};
            ASSERT_TRUE(job.Validate());
            job.Run();
            const double err = std::fabs(test::grid_volume(pos, T, P, 0) / exact - 1.0);
            // Inscribed polyhedron: error falls with the steps (second order for the smooth ellipsoid).
            EXPECT_LT(err, previous) << "T=" << T;
            if (ab == glm::vec2(1, 1) && T >= 16) {
                EXPECT_LT(err, 0.4 * previous) << "T=" << T;
            }
            previous = err;
        }
        EXPECT_LT(previous, ab == glm::vec2(1, 1) ? 2e-4 : 5e-3);
    }
}

std::string join_lines(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += l + "\n";
    return out;
}

TEST(MuscleJobs, ValidateListsEveryFailure) {
    const Skeleton arm = test::make_arm_skeleton();
    const MuscleSet set = arm_muscles(arm);
    const std::vector<glm::mat4> four(4), six(6);  // 4 is not a multiple of 3 joints; 6 is two characters
    std::vector<glm::vec3> small(0);
    std::vector<glm::quat> q(0);
    std::vector<std::string> errors;
    EXPECT_FALSE((MuscleShapeJob{&set, four, small, q, small}.Validate(&errors)));
    EXPECT_EQ(errors.size(), 4u) << join_lines(errors);  // model count + three outputs too small
    errors.clear();
    EXPECT_FALSE((MuscleShapeJob{&set, six, small, q, small}.Validate(&errors)));
    EXPECT_EQ(errors.size(), 3u) << join_lines(errors);  // centres, rotations, radii each too small
    MuscleTessellateJob tess;
    errors.clear();
    EXPECT_FALSE(tess.Validate(&errors));
    EXPECT_EQ(errors.size(), 1u);
}

}  // namespace
}  // namespace aloha
