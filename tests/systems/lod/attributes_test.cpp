// LodAttributesJob against hand-computed cases. Camera at the origin looking down -Z, 90 degree
// vertical field of view (tan(fovy/2) = 1), 800x600 viewport (aspect 4/3, so P[0][0] = 0.75).
#include "systems/lod/attributes.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

namespace aloha {
namespace {

// Float tolerance: every value is a handful of float multiply-adds on magnitudes <= ~100, so the
// rounding error is a few ulp of 100 (~1e-5); 1e-4 leaves margin.
constexpr float kTol = 1e-4f;

LodCamera test_camera() {
    return make_lod_camera({0, 0, 0}, {0, 0, -1}, glm::half_pi<float>(), {800, 600}, 0.1f, 100.0f);
}

struct Crowd {
    std::vector<Transform> t;
    std::vector<Velocity> v;
    std::vector<Bounds> b;
    std::vector<Importance> imp;
    // Adds a character standing so that its centre (half-way up a 1.8 m cylinder) is at `centre`.
    void add(glm::vec3 centre, float scale = 1.0f) {
        Transform x;
        x.position = centre - glm::vec3(0, 0.9f * scale, 0);
        x.scale = scale;
        t.push_back(x);
        v.push_back({});
        b.push_back({1.8f, 0.4f});
        imp.push_back({0.5f});
    }
    std::vector<LodAttributes> run(const LodCamera& cam) {
        std::vector<LodAttributes> out(t.size());
        LodAttributesJob job{t, v, b, imp, cam, out};
        std::vector<std::string> errors;
        EXPECT_TRUE(job.Validate(&errors));
        job.Run();
        return out;
    }
};

TEST(LodAttributes, CentredCharacter) {
    Crowd c;
    c.add({0, 0, -10});
    const LodAttributes a = c.run(test_camera())[0];
    EXPECT_NEAR(a.distance, 10.0f, kTol);
    // h * viewport_h / (2 z tan(fovy/2)) = 1.8 * 600 / (2 * 10 * 1) = 54 px.
    EXPECT_NEAR(a.projected_height_px, 54.0f, kTol);
    EXPECT_NEAR(a.eccentricity, 0.0f, kTol);
    EXPECT_EQ(a.visible, 1);
    EXPECT_NEAR(a.importance, 0.5f, 0.0f);
}

TEST(LodAttributes, BehindTheCamera) {
    Crowd c;
    c.add({0, 0, 10});
    const LodAttributes a = c.run(test_camera())[0];
    EXPECT_NEAR(a.distance, 10.0f, kTol);
    EXPECT_EQ(a.projected_height_px, 0.0f);
    EXPECT_EQ(a.visible, 0);
    EXPECT_EQ(a.eccentricity, kEccentricityBehind);
}

TEST(LodAttributes, ExactlyOnTheRightFrustumEdge) {
    // x_ndc = P00 * x / z = 0.75 * x / 10 = 1  =>  x = 40/3.
    Crowd c;
    c.add({40.0f / 3.0f, 0, -10});
    // Right plane through the eye, inward unit normal (-0.6, 0, -0.8): distance of (x,0,-10) is
    // 8 - 0.6 x. Radius 0.4: at 8 - 0.6x = -0.3 the cylinder still crosses the plane (visible),
    // at -0.5 it is wholly outside (x_ndc = 0.075 * x).
    c.add({(8.0f + 0.3f) / 0.6f, 0, -10});
    c.add({(8.0f + 0.5f) / 0.6f, 0, -10});
    const auto a = c.run(test_camera());
    EXPECT_NEAR(a[0].eccentricity, 1.0f, kTol);
    EXPECT_EQ(a[0].visible, 1);
    EXPECT_NEAR(a[1].eccentricity, 0.075f * 8.3f / 0.6f, kTol);
    EXPECT_EQ(a[1].visible, 1);
    EXPECT_NEAR(a[2].eccentricity, 0.075f * 8.5f / 0.6f, kTol);
    EXPECT_EQ(a[2].visible, 0);
}

TEST(LodAttributes, TopEdgeUsesHalfHeightAndRadius) {
    // y_ndc = y / z (P11 = 1). The top plane has inward unit normal (0,-1,-1)/sqrt(2); a centre at
    // y = 10 + d has signed distance -d/sqrt(2), and the cylinder reaches (0.9 + 0.4)/sqrt(2) towards
    // the plane (half height along y, radius along z), so it is visible while d <= 1.3.
    Crowd c;
    c.add({0, 10, -10});
    c.add({0, 10.0f + 1.2f, -10});
    c.add({0, 10.0f + 1.4f, -10});
    const auto a = c.run(test_camera());
    EXPECT_NEAR(a[0].eccentricity, 1.0f, kTol);
    EXPECT_EQ(a[0].visible, 1);
    EXPECT_NEAR(a[1].eccentricity, 1.12f, kTol);
    EXPECT_EQ(a[1].visible, 1);
    EXPECT_NEAR(a[2].eccentricity, 1.14f, kTol);
    EXPECT_EQ(a[2].visible, 0);
}

TEST(LodAttributes, NearAndFarPlanes) {
    Crowd c;
    c.add({0, 0, -99.5f});   // centre 0.5 m inside the far plane (depth 100): visible
    c.add({0, 0, -100.5f});  // centre 0.5 m beyond it, radius 0.4 reaches back only 0.4: invisible
    const auto a = c.run(test_camera());
    EXPECT_EQ(a[0].visible, 1);
    EXPECT_EQ(a[1].visible, 0);
    EXPECT_NEAR(a[1].projected_height_px, 1.8f * 600.0f / (2.0f * 100.5f), kTol);
}

TEST(LodAttributes, ScaleSpeedImportance) {
    Crowd c;
    c.add({0, 0, -10}, 2.0f);
    c.v[0].linear = {3, 0, 4};
    c.imp[0].value = 0.9f;
    const LodAttributes a = c.run(test_camera())[0];
    EXPECT_NEAR(a.projected_height_px, 108.0f, kTol);  // twice the 54 px of a scale-1 character
    EXPECT_NEAR(a.speed, 5.0f, kTol);                  // |(3,0,4)|
    EXPECT_NEAR(a.importance, 0.9f, 0.0f);
}

TEST(LodAttributes, StandardFormulaWithSixtyDegreeLens) {
    const LodCamera cam = make_lod_camera({0, 1.6f, 5}, {0, 1.6f, -20}, glm::radians(60.0f), {1280, 720}, 0.1f, 500.0f);
    Crowd c;
    c.add({0, 1.6f, -20});
    const LodAttributes a = c.run(cam)[0];
    const float expected = 1.8f * 720.0f / (2.0f * 25.0f * std::tan(glm::radians(30.0f)));
    EXPECT_NEAR(a.projected_height_px, expected, kTol * expected);
    EXPECT_NEAR(a.distance, 25.0f, kTol);
}

TEST(LodAttributes, EmptyOptionalSpansUseDefaults) {
    std::vector<Transform> t(1);
    t[0].position = {0, -0.9f, -10};
    std::vector<LodAttributes> out(1);
    LodAttributesJob job{t, {}, {}, {}, test_camera(), out};
    ASSERT_TRUE(job.Validate());
    job.Run();
    EXPECT_EQ(out[0].speed, 0.0f);
    EXPECT_EQ(out[0].importance, Importance{}.value);
    EXPECT_NEAR(out[0].projected_height_px, 54.0f, kTol);
}

// A camera straight above the crowd (an RTS view) sees the characters below it: its view is defined (it was NaN with
// +Y as the up hint, and every character tested invisible). Centre at depth 30 - 0.9 below the eye; the one 5 m to
// the side is at x_ndc = 5 / 29.1 (tan(fovy/2) = 1, aspect 4/3: x_ndc = 0.75 x / z).
TEST(LodAttributes, CameraStraightDownSeesTheCharactersBelow) {
    Crowd c;
    c.add({0, 0.9f, 0});
    c.add({5, 0.9f, 0});
    const LodCamera cam = make_lod_camera({0, 30, 0}, {0, 0, 0}, glm::half_pi<float>(), {800, 600}, 0.1f, 100.0f);
    const std::vector<LodAttributes> a = c.run(cam);
    EXPECT_EQ(a[0].visible, 1);
    EXPECT_NEAR(a[0].distance, 29.1f, kTol);
    EXPECT_NEAR(a[0].eccentricity, 0.0f, kTol);
    EXPECT_EQ(a[1].visible, 1);
    EXPECT_NEAR(a[1].eccentricity, 0.75f * 5.0f / 29.1f, kTol);
}

TEST(LodAttributes, ValidateListsEveryFailure) {
    std::vector<Transform> t(2);
    std::vector<Velocity> v(1);
    std::vector<LodAttributes> out(3);
    LodCamera cam = test_camera();
    cam.near_plane = 0.0f;
    cam.viewport_px = {0, 600};
    LodAttributesJob job{t, v, {}, {}, cam, out};
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 4u);  // output size, velocities size, viewport, near/far
}

}  // namespace
}  // namespace aloha
