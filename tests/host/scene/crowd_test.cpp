#include "host/scene/scene_loader.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace aloha
