#include "host/scene/scene_loader.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace aloha {
namespace {

SceneDesc crowd_scene(CrowdDesc::Layout layout, uint32_t count) {
    SceneDesc s;
    CharacterTypeDesc type;
    type.name = "humanoid";
    type.bvh = "x.bvh";
    s.types.push_back(type);
    s.camera.keys.push_back({});
    CrowdDesc c;
    c.count = count;
    c.layout = layout;
    c.radius = 20.0f;
    c.seed = 42;
    s.crowds.push_back(c);
    return s;
}

TEST(Crowd, SameSeedSameCrowdOtherSeedOtherCrowd) {
    const SceneDesc s = crowd_scene(CrowdDesc::Layout::Disc, 500);
    const auto a = expand_characters(s), b = expand_characters(s), c = expand_characters(s, 99);
    ASSERT_EQ(a.size(), 500u);
    bool differs = false;
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].position, b[i].position);
        EXPECT_EQ(a[i].requests.front().request.kind, b[i].requests.front().request.kind);
        differs |= a[i].position != c[i].position;
    }
    EXPECT_TRUE(differs);
}

TEST(Crowd, DiscStaysInsideRadiusAndGridIsCentred) {
    const auto disc = expand_characters(crowd_scene(CrowdDesc::Layout::Disc, 2000));
    for (const auto& c : disc) EXPECT_LE(std::hypot(c.position.x, c.position.z), 20.0f + 1e-4f);
    const auto grid = expand_characters(crowd_scene(CrowdDesc::Layout::Grid, 100));
    glm::vec3 sum(0.0f);
    for (const auto& c : grid) sum += c.position;
    EXPECT_NEAR(sum.x / 100.0f, 0.0f, 1e-4f);  // 10x10 grid symmetric about the centre
    EXPECT_NEAR(sum.z / 100.0f, 0.0f, 1e-4f);
}

TEST(Crowd, MixFractionsAreRespected) {
    SceneDesc s = crowd_scene(CrowdDesc::Layout::Grid, 10000);
    s.crowds[0].mix = {0.5f, 0.3f, 0.2f};
    int walk = 0, idle = 0, reach = 0;
    for (const auto& c : expand_characters(s)) {
        switch (c.requests.front().request.kind) {
            case RequestKind::Walk: ++walk; break;
            case RequestKind::PlayClip: ++idle; break;
            case RequestKind::Reach: ++reach; break;
            default: break;
        }
    }
    // Binomial standard deviation for n = 10000, p = 0.5 is 50; allow 5 sigma.
    EXPECT_NEAR(walk, 5000, 250);
    EXPECT_NEAR(idle, 3000, 250);
    EXPECT_NEAR(reach, 2000, 250);
}

// walk_route "circle": every walker gets a looping route of its own round the crowd's centre at its
// starting distance (at least kMinCircleRadius), starting one waypoint ahead and facing it; alternate
// walkers turn opposite ways. Everything drawn from the seed is what the straight crowd gets, so a
// scene without the key expands exactly as before.
TEST(Crowd, CircleWalkersGetALoopRoundTheCentre) {
    SceneDesc straight = crowd_scene(CrowdDesc::Layout::Disc, 400);
    straight.crowds[0].center = glm::vec3(3.0f, 0.0f, -2.0f);
    straight.crowds[0].mix = {1.0f, 0.0f, 0.0f};
    SceneDesc circle = straight;
    circle.crowds[0].walk_route = CrowdDesc::WalkRoute::Circle;
    const auto a = expand_characters(straight), b = expand_characters(circle);
    ASSERT_EQ(a.size(), b.size());
    const glm::vec3 centre = circle.crowds[0].center;
    int ccw = 0, cw = 0;
    for (size_t i = 0; i < b.size(); ++i) {
        EXPECT_EQ(a[i].position, b[i].position);
        EXPECT_EQ(a[i].importance, b[i].importance);
        EXPECT_EQ(a[i].requests[0].request.speed, b[i].requests[0].request.speed);
        EXPECT_TRUE(a[i].requests[0].route.empty());
        const auto& route = b[i].requests[0].route;
        ASSERT_EQ(route.size(), static_cast<size_t>(kCircleRouteWaypoints));
        const glm::vec3 off = b[i].position - centre;
        const float radius = std::max(kMinCircleRadius, std::hypot(off.x, off.z));
        for (const glm::vec3& p : route) {
            EXPECT_NEAR(std::hypot(p.x - centre.x, p.z - centre.z), radius, 1e-5f * radius);  // a few float roundings
            EXPECT_EQ(p.y, centre.y);
        }
        // The last waypoint is back at the start's angle (a whole turn), the first 1/16 turn on.
        const float start_angle = std::atan2(off.z, off.x);
        const glm::vec3 last = route.back() - centre;
        EXPECT_NEAR(std::remainder(std::atan2(last.z, last.x) - start_angle, glm::two_pi<float>()), 0.0f, 1e-4f);
        const glm::vec3 first = route.front() - centre;
        const float turned = std::remainder(std::atan2(first.z, first.x) - start_angle, glm::two_pi<float>());
        EXPECT_NEAR(std::fabs(turned), glm::two_pi<float>() / kCircleRouteWaypoints, 1e-4f);
        (turned > 0.0f ? ccw : cw) += 1;
        EXPECT_EQ(turned > 0.0f, i % 2 == 0);
        // Facing the first waypoint: heading h looks along (sin h, 0, cos h).
        const glm::vec3 to = route.front() - b[i].position;
        const float h = glm::radians(b[i].heading_deg);
        EXPECT_NEAR(std::sin(h) * to.z - std::cos(h) * to.x, 0.0f, 1e-4f * glm::length(to));
        EXPECT_GT(std::sin(h) * to.x + std::cos(h) * to.z, 0.0f);
    }
    EXPECT_EQ(ccw, 200);
    EXPECT_EQ(cw, 200);
}

}  // namespace
}  // namespace aloha
