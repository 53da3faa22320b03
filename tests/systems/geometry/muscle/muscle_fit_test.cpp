// Per-bone muscle fitting on a synthetic skinned cylinder bound to two bones.
#include "systems/geometry/muscle/muscle_fit.hpp"
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "systems/geometry/muscle/superellipsoid.hpp"
#include "tests/systems/geometry/muscle/test_skeletons.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace aloha {
namespace {

constexpr float kRadius = 0.05f;   // cylinder radius (m)
constexpr int kSides = 16;         // vertices per ring
constexpr float kFat = 0.01f;

// Cylinder along +y from 0 to 0.6 m: rings at y = 0.01 + 0.02 i. Joint 0 ("Upper") at the origin,
// joint 1 ("Lower") at y = 0.3. Weights blend linearly over 0.2..0.4 m, so the dominant joint
// switches at 0.3 m and no ring sits on the switch.
struct Cylinder {
    Skeleton skeleton = test::make_skeleton({{"Upper", "", {0, 0, 0}}, {"Lower", "Upper", {0, 0.3f, 0}}}, 1.0f);
    std::vector<glm::vec3> positions;
    std::vector<glm::ivec4> joints;
    std::vector<glm::vec4> weights;
    Cylinder() {
        for (int i = 0; i < 30; ++i) {
            const float y = 0.01f + 0.02f * static_cast<float>(i);
            const float w1 = std::clamp((y - 0.2f) / 0.2f, 0.0f, 1.0f);
            for (int k = 0; k < kSides; ++k) {
                const float a = 2.0f * std::numbers::pi_v<float> * static_cast<float>(k) / kSides;
                positions.push_back({kRadius * std::cos(a), y, kRadius * std::sin(a)});
                joints.push_back({0, 1, 0, 0});
                weights.push_back({1.0f - w1, w1, 0.0f, 0.0f});
            }
        }
    }
};

TEST(MuscleFit, CylinderGetsOneMuscleInsideTheSkinPerBone) {
    const Cylinder cyl;
    const auto bind = rest_model_matrices(cyl.skeleton);
    MuscleFitOptions opt;
    opt.fat_thickness = kFat;
    auto fitted = fit_muscles_per_bone(cyl.skeleton, bind, cyl.positions, cyl.joints, cyl.weights, opt);
    ASSERT_TRUE(fitted.ok()) << fitted.error().to_string();
    const MuscleSet& set = fitted.value();
    ASSERT_EQ(set.size(), 2);
    EXPECT_EQ(set.names[0], "Upper_muscle");
    EXPECT_EQ(set.names[1], "Lower_muscle");
    EXPECT_EQ(set.insertion_joint[0], 1);  // crosses onto the child bone
    EXPECT_EQ(set.insertion_joint[1], 1);  // leaf bone: both tendons on it

    std::vector<glm::vec3> centres(2), radii(2);
    std::vector<glm::quat> rots(2);
    MuscleShapeJob shape{&set, bind, centres, rots, radii};
    ASSERT_TRUE(shape.Validate());
    shape.Run();
    // Each bone owns 15 rings spanning 0.28 m: half-length 0.14 minus the fat (float: 1e-5).
    const float cos_half_step = std::cos(std::numbers::pi_v<float> / kSides);
    for (int m = 0; m < 2; ++m) {
        EXPECT_NEAR(radii[m].x, 0.14f - kFat, 1e-5f);
        // Across the axis a 16-gon's half-extent lies between R cos(pi/16) and R, depending on the
        // direction the principal axes picked (the ring is isotropic), minus the fat.
        for (float r : {radii[m].y, radii[m].z}) {
            EXPECT_GE(r, kRadius * cos_half_step - kFat - 1e-5f);
            EXPECT_LE(r, kRadius - kFat + 1e-5f);
        }
        EXPECT_NEAR(std::fabs(glm::dot(glm::mat3_cast(rots[m])[0], glm::vec3(0, 1, 0))), 1.0f, 1e-5f);
    }
    EXPECT_NEAR(glm::length(centres[0] - glm::vec3(0, 0.15f, 0)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::length(centres[1] - glm::vec3(0, 0.45f, 0)), 0.0f, 1e-4f);

    // Every tessellated muscle vertex is inside the skin by at least the fat thickness, up to the
    // polygon's inset R (1 - cos(pi/16)) ~ 1e-3 m.
    const SuperEllipsoidTables tables(16, 12, set);
    std::vector<glm::vec3> pos(2 * tables.vertices_per_muscle()), nrm(pos.size());
    MuscleTessellateJob tess{&tables, centres, rots, radii, pos, nrm};
    ASSERT_TRUE(tess.Validate());
    tess.Run();
    for (const glm::vec3 p : pos) {
        EXPECT_LE(std::hypot(p.x, p.z), kRadius - kFat + 1e-5f);
        EXPECT_GE(p.y, 0.01f + kFat - 1e-5f);
        EXPECT_LE(p.y, 0.59f - kFat + 1e-5f);
    }
}

TEST(MuscleFit, MuscleAcrossTheJointKeepsVolumeWhenBent) {
    const Cylinder cyl;
    const auto bind = rest_model_matrices(cyl.skeleton);
    auto fitted = fit_muscles_per_bone(cyl.skeleton, bind, cyl.positions, cyl.joints, cyl.weights);
    ASSERT_TRUE(fitted.ok());
    const MuscleSet& set = fitted.value();
    const glm::quat rot[2] = {glm::quat(1, 0, 0, 0), glm::angleAxis(1.2f, glm::vec3(0, 0, 1))};
    const auto bent = test::pose_model(cyl.skeleton, rot);
    std::vector<glm::vec3> centres(2), radii(2);
    std::vector<glm::quat> rots(2);
    MuscleShapeJob shape{&set, bent, centres, rots, radii};
    ASSERT_TRUE(shape.Validate());
    shape.Run();
    EXPECT_NEAR(superellipsoid_volume(glm::dvec3(radii[0]), 1, 1) / set.volume[0], 1.0, 1e-5);
    EXPECT_NE(radii[0].x, 0.5f * set.rest_length[0]);  // its length changed with the bend
}

TEST(MuscleFit, BadInputIsAnError) {
    const Cylinder cyl;
    const auto bind = rest_model_matrices(cyl.skeleton);
    std::vector<glm::ivec4> joints = cyl.joints;
    joints[5] = {7, 0, 0, 0};
    auto bad_joint = fit_muscles_per_bone(cyl.skeleton, bind, cyl.positions, joints, cyl.weights);
    ASSERT_FALSE(bad_joint.ok());
    EXPECT_NE(bad_joint.error().message.find("vertex 5 is bound to joint 7"), std::string::npos);
    auto short_weights = fit_muscles_per_bone(cyl.skeleton, bind, cyl.positions, cyl.joints,
                                              std::span<const glm::vec4>(cyl.weights).first(3));
    EXPECT_FALSE(short_weights.ok());
    auto short_bind = fit_muscles_per_bone(cyl.skeleton, std::span<const glm::mat4>(bind).first(1), cyl.positions,
                                           cyl.joints, cyl.weights);
    EXPECT_FALSE(short_bind.ok());
}

}  // namespace
}  // namespace aloha
