// Bounds radii (character_bounds.hpp): every vertex a character displays stays inside its bounds
// cylinder while it walks, idles and reaches, so the frustum test and the occlusion estimate never cull
// a visible hand or foot; and the radii are no wider than what the poses need.
#include "host/scene/character_runtime.hpp"
#include "host/scene/scene_loader.hpp"
#include "host/scene/skin_sample.hpp"
#include "host/scene/world.hpp"
#include "tests/host/scene/world_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

namespace aloha {
namespace {

const std::string kScenes = std::string(ALOHA_SOURCE_DIR) + "/data/scenes/";

// The largest horizontal distance of `s`'s displayed vertices from its placement's vertical line, in
// units of the placement's scale (the frame Bounds is given in).
float displayed_radius(const SkinSample& s) {
    const glm::vec3 origin(s.placement[3]);
    const float scale = glm::length(glm::vec3(s.placement[0]));
    float r = 0.0f;
    for (const glm::vec3& p : s.positions) r = std::max(r, std::hypot(p.x - origin.x, p.z - origin.z));
    return r / scale;
}

TEST(CharacterBounds, DisplayedBodiesStayInsideTheirBoundsWhileWalkingIdlingAndReaching) {
    auto scene = load_scene(kScenes + "crowd_1k.json");
    ASSERT_TRUE(scene.ok());
    SceneDesc s = scene.value();
    s.crowds[0].count = 10;
    s.crowds[0].mix = {0.4f, 0.2f, 0.4f};
    s.crowds[0].radius = 4.0f;  // everyone in view of a camera 14 m away
    s.camera.keys = {CameraKey{0.0f, glm::vec3(0.0f, 2.0f, 14.0f), glm::vec3(0.0f, 1.0f, 0.0f)}};
    size_t reachers = 0;
    for (const CharacterDesc& c : expand_characters(s))
        for (const RequestDesc& r : c.requests) reachers += r.request.kind == RequestKind::Reach;
    ASSERT_GT(reachers, 0u);  // the reach widening is exercised
    auto w = scene_test::make_world(s);
    ASSERT_TRUE(w);
    // Every character at the skinned level: its skin follows the joints. (The layered levels' fat sways
    // up to ~25 mm beyond that at a sudden stop, FatWorld.*; not checked here.)
    uint8_t skinned = 0xFF;
    const RuleTable& table = w->rules().table();
    for (size_t l = 0; l < table.geom_levels.size(); ++l)
        if (table.geom_levels[l].method == GeomMethod::SkinnedMesh) skinned = static_cast<uint8_t>(l);
    ASSERT_NE(skinned, 0xFF);
    for (uint32_t i = 0; i < 10; ++i) ASSERT_TRUE(w->pin_geom_level(i, skinned).ok());
    std::map<std::pair<uint16_t, uint32_t>, float> radius;
    w->registry().view<const CharacterRef, const Bounds>().each(
        [&](const CharacterRef& c, const Bounds& b) { radius[{c.type, c.id}] = b.radius; });
    float worst = 0.0f, widest = 0.0f, narrowest = 1e9f;
    for (const auto& [key, r] : radius) widest = std::max(widest, r), narrowest = std::min(narrowest, r);
    SkinSample sample;
    std::vector<int> compared(10, 0);
    for (int f = 0; f < 96; ++f) {
        w->step();
        if (f % 6 != 5) continue;
        for (uint32_t i = 0; i < 10; ++i) {
            w->skin_sample(i, sample);
            if (sample.positions.empty()) continue;
            const float r = radius.at({sample.type, sample.id});
            const float shown = displayed_radius(sample);
            worst = std::max(worst, shown / r);
            EXPECT_LE(shown, r) << "character " << i << " frame " << f;
            ++compared[i];
        }
    }
    for (uint32_t i = 0; i < 10; ++i) EXPECT_GT(compared[i], 0) << "character " << i << " never showed a skin";
    std::printf("bounds radii %.3f-%.3f m; displayed skin reaches at most %.2f of its radius\n", narrowest, widest, worst);
}

}  // namespace
}  // namespace aloha
