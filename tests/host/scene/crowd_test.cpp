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

// A crowd of 3 with 16 body variants picks at most 3 of them: the others are dropped before anything builds them, the
// types after each dropped one move down and every character's type follows, naming the same variant as before; the
// base type (no character, no variant) and a placed character's type stay; a crowd that picked every variant drops
// nothing.
TEST(Crowd, BodyVariantsNoCharacterPickedAreDropped) {
    const auto variants_scene = [](uint32_t count) {
        Result<SceneDesc> s = parse_scene(R"({"camera": {"position": [0, 2, 12], "target": [0, 1, 0]},
          "character_types": [{"name": "a", "humanoid": "builtin:humanoid"},
            {"name": "b", "humanoid": "builtin:humanoid"}],
          "characters": [{"type": "b", "position": [0, 0, 0]}],
          "crowds": [{"type": "a", "count": )" + std::to_string(count) + R"(, "height": [1.5, 1.9], "variants": 16}]})",
                                          std::string(ALOHA_SOURCE_DIR) + "/data/scenes/variants_inline.json");
        EXPECT_TRUE(s.ok()) << (s.ok() ? std::string() : s.error().to_string());
        return s.ok() ? s.value() : SceneDesc{};
    };
    SceneDesc s = variants_scene(3);
    ASSERT_EQ(s.types.size(), 18u) << "two types and 16 variants";
    std::vector<CharacterDesc> chars = expand_characters(s);
    ASSERT_EQ(chars.size(), 4u);
    std::vector<std::string> before;
    for (const CharacterDesc& c : chars) before.push_back(s.types[static_cast<size_t>(c.type)].name);
    const size_t dropped = drop_unused_variants(s, chars);
    EXPECT_GE(dropped, 13u);
    EXPECT_EQ(s.types.size(), 18u - dropped);
    EXPECT_EQ(s.types[0].name, "a") << "the base type stays";
    EXPECT_EQ(s.types[1].name, "b");
    for (size_t i = 0; i < chars.size(); ++i) {
        ASSERT_LT(static_cast<size_t>(chars[i].type), s.types.size());
        EXPECT_EQ(s.types[static_cast<size_t>(chars[i].type)].name, before[i]) << "character " << i << " keeps its body";
    }
    for (size_t t = 2; t < s.types.size(); ++t)
        EXPECT_TRUE(std::any_of(chars.begin(), chars.end(), [&](const CharacterDesc& c) { return c.type == static_cast<int>(t); }))
            << s.types[t].name << " is drawn";
    EXPECT_EQ(s.characters[0].type, 1);
    EXPECT_EQ(s.crowds[0].type, 0);
    ASSERT_EQ(s.crowds[0].variant_types.size(), 16u) << "the picks keep their odds";
    EXPECT_EQ(std::count(s.crowds[0].variant_types.begin(), s.crowds[0].variant_types.end(), -1), static_cast<long>(dropped));
    // Expanding the pruned scene again picks the same bodies.
    const std::vector<CharacterDesc> again = expand_characters(s);
    for (size_t i = 0; i < chars.size(); ++i) EXPECT_EQ(again[i].type, chars[i].type) << i;

    SceneDesc all = variants_scene(400);
    std::vector<CharacterDesc> many = expand_characters(all);
    EXPECT_EQ(drop_unused_variants(all, many), 0u) << "400 characters pick all 16";
    EXPECT_EQ(all.types.size(), 18u);
}

}  // namespace
}  // namespace aloha
