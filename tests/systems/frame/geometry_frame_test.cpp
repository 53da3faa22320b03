// apply_level_switches' transition lengths: a geomorph takes the entered level's geomorph_s, a cross-fade
// into or out of the impostor level the longer of the two levels' geomorph_s (so impostor <-> rigid proxy,
// whose proxy side has geomorph_s 0, fades over the impostor's frames instead of popping).
#include "systems/frame/geometry_frame.hpp"
#include "systems/lod/resolver.hpp"
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace aloha {
namespace {

using test::humanoid;

constexpr uint8_t kLayered = 1, kSkinned = 3, kProxy = 4, kImpostor = 6;
constexpr float kDt = 1.0f / 60.0f;

// test_levels() with the default rules' transition times (layered 0.2 s, skinned 0.1 s, proxy 0) and an
// impostor level (0.1 s) last.
std::vector<GeomLod> levels() {
    std::vector<GeomLod> l = test::test_levels();
    l[kLayered].geomorph_s = 0.2f;
    l[kSkinned].geomorph_s = 0.1f;
    l[kProxy].geomorph_s = 0.0f;
    GeomLod impostor;
    impostor.method = GeomMethod::Impostor;
    impostor.level = kImpostor;
    impostor.geomorph_s = 0.1f;
    l.push_back(impostor);
    return l;
}

// One character of one type through apply_level_switches, the way the world calls it each frame.
struct Switcher {
    std::vector<GeomLod> table = levels();
    GeometryController ctl{*humanoid().geometry, table, 1};
    std::vector<glm::mat4> pose = test::clip_pose(humanoid().geometry->skeleton(), humanoid().clip, 40);
    std::vector<GeometryType> types{GeometryType{&ctl, PoseSource{pose.data(), 0}}};
    std::vector<CharacterRef> refs{CharacterRef{0, 0}};
    std::vector<LodState> states{LodState{}};
    std::vector<GeomLod> geom{GeomLod{}};

    // Frame with the character asked to be at `level` (the resolver's outcome), then its stages run.
    void frame(uint8_t level, bool first = false) {
        const uint32_t changed[1] = {0};
        states[0].prev_geom_level = ctl.level_of(0) == GeometryController::kNoLevel ? level : ctl.level_of(0);
        states[0].geom_level = level;
        geom[0] = table[level];
        apply_level_switches(types, refs, states, geom, first ? std::span<const uint32_t>{} : changed, first, kDt);
        const uint32_t one[1] = {0};
        ctl.update(level, one, types[0].poses, kDt);
        ctl.update_fades(types[0].poses, kDt);
    }
};

// Frame k of a cross-fade of n frames into (or out of) the impostor: the drawn level has (n - k) / n (or
// k / n) of the pixels; frame n has no fade.
void expect_fade_frame(const GeometryController& ctl, uint16_t k, uint16_t n, bool into_impostor) {
    const LevelFade* f = ctl.fade(0);
    if (k == n) {
        EXPECT_EQ(f, nullptr);
        return;
    }
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->into_impostor(), into_impostor);
    EXPECT_EQ(f->frames_total, n);
    EXPECT_EQ(f->drawn_share(), float(into_impostor ? n - k : k) / float(n));
}

TEST(GeometryFrame, ImpostorAndRigidProxyCrossFadeOverTheImpostorsFramesBothWays) {
    ASSERT_NE(humanoid().geometry, nullptr);
    Switcher s;
    const uint16_t n = transition_frames(0.1f, kDt);  // max(proxy 0, impostor 0.1 s) = 6 frames at 60 Hz
    ASSERT_EQ(n, 6u);
    ASSERT_EQ(transition_frames(s.table[kProxy].geomorph_s, kDt), 0u);  // what the entered level alone would give
    s.frame(kProxy, true);
    ASSERT_FALSE(s.ctl.proxy_boxes(0).empty());

    // proxy -> impostor: the boxes are kept and fade out, (N - k) / N of the pixels on frame k.
    for (uint16_t k = 1; k <= n; ++k) {
        SCOPED_TRACE("into the impostor, frame " + std::to_string(k));
        s.frame(kImpostor);
        expect_fade_frame(s.ctl, k, n, true);
        if (k < n) {
            EXPECT_FALSE(s.ctl.fade_proxy_boxes(0).empty());
        }
    }
    EXPECT_EQ(s.ctl.characters_at(kProxy), 0u);

    // impostor -> proxy: the entered proxy (geomorph_s 0) fades in over the impostor's N frames, k / N of the
    // pixels on frame k (the impostor the complementary (N - k) / N; was a one-frame pop).
    for (uint16_t k = 1; k <= n; ++k) {
        SCOPED_TRACE("out of the impostor, frame " + std::to_string(k));
        s.frame(kProxy);
        EXPECT_FALSE(s.ctl.proxy_boxes(0).empty());  // the entered level draws its own boxes from frame 1
        expect_fade_frame(s.ctl, k, n, false);
    }
}

TEST(GeometryFrame, AFadeTakesTheLongerLevelsTimeAndAGeomorphTheEnteredLevels) {
    ASSERT_NE(humanoid().geometry, nullptr);
    Switcher s;
    s.frame(kLayered, true);
    // layered (0.2 s) -> impostor (0.1 s): the fade lasts 0.2 s, 12 frames.
    s.frame(kImpostor);
    ASSERT_NE(s.ctl.fade(0), nullptr);
    EXPECT_EQ(s.ctl.fade(0)->frames_total, transition_frames(0.2f, kDt));
    EXPECT_EQ(s.ctl.fade(0)->frames_total, 12u);
    for (int i = 0; i < 12; ++i) s.frame(kImpostor);
    EXPECT_EQ(s.ctl.fade(0), nullptr);
    // impostor (0.1 s) -> skinned (0.1 s): 6 frames either way.
    s.frame(kSkinned);
    ASSERT_NE(s.ctl.fade(0), nullptr);
    EXPECT_EQ(s.ctl.fade(0)->frames_total, 6u);
    for (int i = 0; i < 6; ++i) s.frame(kSkinned);
    // skinned (0.1 s) -> layered (0.2 s) and back: geomorphs of the entered level's time, and (a skinned level is
    // lit per vertex, a layered one per pixel) mesh cross-fades of the longer one's, 12 frames both ways.
    s.frame(kLayered);
    ASSERT_NE(s.ctl.fade(0), nullptr);
    EXPECT_TRUE(s.ctl.fade(0)->between_meshes);
    EXPECT_EQ(s.ctl.fade(0)->frames_total, 12u);
    EXPECT_EQ(s.ctl.geomorph_frames_left(0), transition_frames(0.2f, kDt) - 1);  // frame 1 of 12 shown
    for (int i = 0; i < 12; ++i) s.frame(kLayered);
    EXPECT_EQ(s.ctl.fade(0), nullptr);
    s.frame(kSkinned);
    ASSERT_NE(s.ctl.fade(0), nullptr);
    EXPECT_TRUE(s.ctl.fade(0)->between_meshes);
    EXPECT_EQ(s.ctl.fade(0)->frames_total, 12u);  // the longer level's time, as every fade
    EXPECT_EQ(s.ctl.geomorph_frames_left(0), transition_frames(0.1f, kDt) - 1);  // 6, not the layered level's 12
}

}  // namespace
}  // namespace aloha
