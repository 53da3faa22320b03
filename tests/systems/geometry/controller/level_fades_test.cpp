// Cross-fades between the impostor level and a drawn level, and between mesh levels showing different
// surfaces (LevelFade): their frames and shares, the slot of the level left kept and posed while fading into
// the impostor or the other mesh level, and every way a fade ends.
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace aloha {
namespace {

using test::humanoid;

constexpr uint8_t kSubdivided = 0, kLayeredHigh = 1, kLayered = 2, kSkinned = 3, kProxy = 4, kHidden = 5, kImpostor = 6;

// test_levels() (0 Subdivided .. 5 Hidden) and an impostor level last.
std::vector<GeomLod> levels_with_impostor() {
    std::vector<GeomLod> levels = test::test_levels();
    GeomLod impostor;
    impostor.method = GeomMethod::Impostor;
    impostor.level = kImpostor;
    levels.push_back(impostor);
    return levels;
}

std::vector<glm::vec3> copy(std::span<const glm::vec3> s) { return {s.begin(), s.end()}; }

// Runs frame `now` as the spring_skin stage does (the kept slots posed first) for character 0, which switched from
// `from` into `to` with M geomorph frames, 1 left at `from` (the left surface at this pose) and 2, which entered `to`
// without a morph (the entered surface); then checks that 0's first frame shows the entered surface plus (1 - 1 / M)
// of the offset to the left one (geomorph.hpp) within float rounding, and that the left surface moved more than
// 1 cm since `shown_at_switch` (the start the switch captured: the test tells the two apart).
void expect_morph_starts_at_this_pose(GeometryController& ctl, uint8_t from, uint8_t to, const std::vector<glm::mat4>& now,
                                      const std::vector<glm::vec3>& shown_at_switch, uint16_t M) {
    const uint32_t switching[1] = {0}, left[1] = {1}, fresh[1] = {2};
    ctl.update_fades(PoseSource{now.data(), 0}, 1.0f / 60.0f);
    ctl.update(to, switching, PoseSource{now.data(), 0}, 1.0f / 60.0f);
    ctl.update(to, fresh, PoseSource{now.data(), 0}, 1.0f / 60.0f);
    ctl.update(from, left, PoseSource{now.data(), 0}, 1.0f / 60.0f);
    const std::span<const glm::vec3> shown = ctl.surface(0).positions, entered = ctl.surface(2).positions,
                                     left_now = ctl.surface(1).positions;
    ASSERT_EQ(shown.size(), entered.size());
    ASSERT_EQ(shown.size(), left_now.size());
    const float kept = 1.0f - 1.0f / float(M);
    float worst = 0.0f, moved = 0.0f;
    for (size_t i = 0; i < shown.size(); ++i) {
        worst = std::max(worst, glm::length(shown[i] - (entered[i] + kept * (left_now[i] - entered[i]))));
        moved = std::max(moved, glm::length(left_now[i] - shown_at_switch[i]));
    }
    // The same sums in float as GeomorphJob's, maybe in another order: a few roundings of coordinates under 2 m
    // (an ulp there is 1.2e-7 m). Measured: 0.
    EXPECT_LT(worst, 1e-6f);
    EXPECT_GT(moved, 0.01f);
}

TEST(LevelFades, IntoTheImpostorTheLeftMeshStaysPosedForNMinusOneFrames) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, levels_with_impostor(), 2);
    // Character 1 stays at the skinned level as the witness of what the fading character's mesh must show.
    for (const uint32_t c : {0u, 1u}) ctl.begin_level(c, kSkinned, -1, 0);
    const uint32_t both[2] = {0, 1}, witness[1] = {1};
    size_t key = 100;
    auto pose = test::clip_pose(g.skeleton(), humanoid().clip, key++);
    ctl.update(kSkinned, both, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    constexpr uint16_t N = 6;
    ctl.begin_level(0, kImpostor, kSkinned, N);
    ASSERT_NE(ctl.fade(0), nullptr);
    EXPECT_TRUE(ctl.fade(0)->into_impostor());
    EXPECT_EQ(ctl.fade(0)->from_level, kSkinned);
    EXPECT_EQ(ctl.fades().size(), 1u);
    EXPECT_EQ(ctl.level_of(0), kImpostor);
    EXPECT_EQ(ctl.characters_at(kSkinned), 2u);  // the witness and the kept slot
    EXPECT_EQ(ctl.fade(1), nullptr);
    for (uint16_t k = 1; k < N; ++k) {
        SCOPED_TRACE("frame " + std::to_string(k));
        if (k > 1) ctl.advance_fades();
        ASSERT_NE(ctl.fade(0), nullptr);
        EXPECT_EQ(ctl.fade(0)->frames_left, N - k);
        EXPECT_EQ(ctl.fade(0)->drawn_share(), float(N - k) / float(N));  // the impostor has k / N
        pose = test::clip_pose(g.skeleton(), humanoid().clip, key++);
        ctl.update(kSkinned, witness, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
        ctl.update_fades(PoseSource{pose.data(), 0}, 1.0f / 60.0f);
        // The same linear-blend skin of the same pose as the witness's, bit for bit: the mesh fading out walks on.
        const SurfaceView kept = ctl.fade_surface(0);
        EXPECT_EQ(kept.level, kSkinned);
        EXPECT_EQ(kept.topology_key, ctl.topology_key(kSkinned));
        EXPECT_EQ(copy(kept.positions), copy(ctl.surface(1).positions));
        EXPECT_EQ(copy(kept.normals), copy(ctl.surface(1).normals));
        EXPECT_TRUE(ctl.surface(0).positions.empty());  // the impostor level has no surface
    }
    ctl.advance_fades();  // frame N: the impostor alone, the kept slot released
    EXPECT_EQ(ctl.fade(0), nullptr);
    EXPECT_TRUE(ctl.fades().empty());
    EXPECT_EQ(ctl.characters_at(kSkinned), 1u);
    EXPECT_TRUE(ctl.fade_surface(0).positions.empty());

    // Out of the impostor: nothing is kept, the entered level's share grows k / N.
    ctl.begin_level(0, kSkinned, kImpostor, N);
    ASSERT_NE(ctl.fade(0), nullptr);
    EXPECT_FALSE(ctl.fade(0)->into_impostor());
    EXPECT_EQ(ctl.characters_at(kImpostor), 0u);
    for (uint16_t k = 1; k < N; ++k) {
        if (k > 1) ctl.advance_fades();
        ASSERT_NE(ctl.fade(0), nullptr);
        EXPECT_EQ(ctl.fade(0)->drawn_share(), float(k) / float(N));
        EXPECT_TRUE(ctl.fade_surface(0).positions.empty());  // the entered level's own surface() is drawn
    }
    ctl.advance_fades();
    EXPECT_EQ(ctl.fade(0), nullptr);
}

TEST(LevelFades, ProxyBoxesAndLayeredSkinsFadeOutPosed) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, levels_with_impostor(), 4);
    // 0 and 1 proxies, 2 and 3 layered; 0 and 2 fade into the impostor, 1 is the proxies' witness.
    const uint32_t proxies[2] = {0, 1}, layered[2] = {2, 3}, proxy_witness[1] = {1};
    for (const uint32_t c : proxies) ctl.begin_level(c, kProxy, -1, 0);
    for (const uint32_t c : layered) ctl.begin_level(c, kLayered, -1, 0);
    size_t key = 300;
    auto pose = test::clip_pose(g.skeleton(), humanoid().clip, key++);
    ctl.update(kProxy, proxies, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    ctl.update(kLayered, layered, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    ctl.begin_level(0, kImpostor, kProxy, 3);
    ctl.begin_level(2, kImpostor, kLayered, 3);
    pose = test::clip_pose(g.skeleton(), humanoid().clip, key++);
    ctl.update(kProxy, proxy_witness, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    ctl.update_fades(PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    const std::span<const glm::mat4> boxes = ctl.fade_proxy_boxes(0), witness_boxes = ctl.proxy_boxes(1);
    ASSERT_FALSE(boxes.empty());
    EXPECT_TRUE(std::equal(boxes.begin(), boxes.end(), witness_boxes.begin(), witness_boxes.end()));
    EXPECT_TRUE(ctl.fade_surface(0).positions.empty());
    // The layered skin: muscles, fat springs and skin run for the new pose (finite, at the level it left).
    ASSERT_FALSE(ctl.fade_surface(2).positions.empty());
    EXPECT_EQ(ctl.fade_surface(2).level, kLayered);
    EXPECT_TRUE(ctl.fade_proxy_boxes(2).empty());
    for (const glm::vec3& p : ctl.fade_surface(2).positions) EXPECT_TRUE(test::finite(p));
    ctl.advance_fades();
    ctl.advance_fades();  // N = 3: frames 1 and 2 show both
    EXPECT_TRUE(ctl.fades().empty());
    EXPECT_EQ(ctl.characters_at(kProxy), 1u);
    EXPECT_EQ(ctl.characters_at(kLayered), 1u);
}

// skinned <-> layered (the default rules' skinned -> layered_low of crowd_dense) and layered -> subdivided: the
// left mesh stays posed and shown beside the entered one, the entered level's share k / N, its geomorph kept,
// and at frame N the left level's slot is dropped.
TEST(LevelFades, BetweenMeshLevelsTheLeftSurfaceStaysPosedAndIsDroppedAtTheEnd) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, levels_with_impostor(), 2);
    struct Case {
        uint8_t from, to;
    };
    size_t key = 400;
    for (const Case sw : {Case{kSkinned, kLayeredHigh}, Case{kLayeredHigh, kSkinned}, Case{kLayered, kSubdivided}}) {
        SCOPED_TRACE("level " + std::to_string(sw.from) + " -> " + std::to_string(sw.to));
        // Character 1 stays at the left level as the witness of what the fading character's left mesh must show.
        for (const uint32_t c : {0u, 1u}) ctl.begin_level(c, sw.from, -1, 0);
        const uint32_t both[2] = {0, 1}, fading[1] = {0}, witness[1] = {1};
        auto pose = test::clip_pose(g.skeleton(), humanoid().clip, key++);
        ctl.update(sw.from, both, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
        constexpr uint16_t N = 8, M = 5;  // fade frames (the longer level's) and the entered level's geomorph frames
        ctl.begin_level(0, sw.to, sw.from, M, N);
        ASSERT_NE(ctl.fade(0), nullptr);
        EXPECT_TRUE(ctl.fade(0)->between_meshes);
        EXPECT_TRUE(ctl.fade(0)->keeps_left());
        EXPECT_FALSE(ctl.fade(0)->into_impostor());
        EXPECT_EQ(ctl.characters_at(sw.from), 2u);  // the witness and the kept slot
        for (uint16_t k = 1; k < N; ++k) {
            SCOPED_TRACE("frame " + std::to_string(k));
            if (k > 1) ctl.advance_fades();
            ASSERT_NE(ctl.fade(0), nullptr);
            EXPECT_EQ(ctl.fade(0)->drawn_share(), float(k) / float(N));  // the entered level's; the left shows the rest
            pose = test::clip_pose(g.skeleton(), humanoid().clip, key++);
            ctl.update(sw.to, fading, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
            ctl.update(sw.from, witness, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
            ctl.update_fades(PoseSource{pose.data(), 0}, 1.0f / 60.0f);
            EXPECT_EQ(ctl.geomorph_frames_left(0), k < M ? M - k : 0);  // the geomorph runs beside the fade
            const SurfaceView kept = ctl.fade_surface(0), entered = ctl.surface(0);
            EXPECT_EQ(kept.level, sw.from);
            EXPECT_EQ(kept.topology_key, ctl.topology_key(sw.from));
            EXPECT_EQ(entered.level, sw.to);
            EXPECT_EQ(entered.positions.size(), ctl.vertices_per_character(sw.to));
            EXPECT_EQ(kept.positions.size(), ctl.vertices_per_character(sw.from));
            // The witness's surface bit for bit: the same skin (linear blend, or muscles, fat springs from the same
            // state and skin, no placement for either) of the same poses: the mesh fading out walks on.
            EXPECT_EQ(copy(kept.positions), copy(ctl.surface(1).positions));
            EXPECT_EQ(copy(kept.normals), copy(ctl.surface(1).normals));
        }
        ctl.advance_fades();  // frame N: the entered level alone, the kept slot released
        EXPECT_EQ(ctl.fade(0), nullptr);
        EXPECT_EQ(ctl.characters_at(sw.from), 1u);
        EXPECT_TRUE(ctl.fade_surface(0).positions.empty());
        ctl.end_character(0);
        ctl.end_character(1);
    }
    // Two mesh levels showing the same surface alike (a level and its copy): a geomorph alone, no fade.
    std::vector<GeomLod> levels = levels_with_impostor();
    levels.push_back(levels[kLayered]);
    levels.back().level = static_cast<uint8_t>(levels.size() - 1);
    GeometryController same(g, levels, 1);
    same.begin_level(0, kLayered, -1, 0);
    const uint32_t one[1] = {0};
    const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 60);
    same.update(kLayered, one, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    same.begin_level(0, static_cast<uint8_t>(levels.size() - 1), kLayered, 6);
    EXPECT_EQ(same.fade(0), nullptr);
    EXPECT_EQ(same.geomorph_frames_left(0), 6u);
}

// A mesh level entered by a cross-fade starts its geomorph from the left level's surface at the pose of the frame
// it is first shown (the kept slot, posed by update_fades before the skins), not from the one shown at the switch:
// between those two frames the limbs moved (further still when the left level's animation updates every few
// frames), and a morph from there would replay that motion on top of the two levels' difference of shape.
TEST(LevelFades, AMeshEnteredByACrossFadeStartsItsGeomorphAtThisFramesPose) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, levels_with_impostor(), 3);
    // Skinned (8, 6) into layered (8, 6): the same vertices, lit otherwise, so a cross-fade and a geomorph vertex
    // by vertex. Character 1 stays skinned (the left surface at each pose); 2 enters the layered level without a
    // morph (the entered level's own surface at the pose).
    for (const uint32_t c : {0u, 1u}) ctl.begin_level(c, kSkinned, -1, 0);
    const uint32_t both[2] = {0, 1};
    const auto before = test::clip_pose(g.skeleton(), humanoid().clip, 500);
    ctl.update(kSkinned, both, PoseSource{before.data(), 0}, 1.0f / 60.0f);
    const std::vector<glm::vec3> shown_at_switch = copy(ctl.surface(0).positions);
    constexpr uint16_t M = 5, N = 8;
    ctl.begin_level(0, kLayered, kSkinned, M, N);
    ctl.begin_level(2, kLayered, -1, 0);
    const auto now = test::clip_pose(g.skeleton(), humanoid().clip, 504);  // four frames on: the skinned level's interval
    expect_morph_starts_at_this_pose(ctl, kSkinned, kLayered, now, shown_at_switch, M);
}

// The same where no cross-fade keeps the left level's slot (two layered levels at one (T, P), with and without the
// fat: the same vertices, lit alike): the switch keeps the slot as the morph's source until the next advance_fades,
// update_fades poses it, and the entered level starts from it at the frame's pose.
TEST(LevelFades, AMorphWithoutAFadeStartsAtThisFramesPoseFromTheLeftSlotKeptOneFrame) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    std::vector<GeomLod> levels = levels_with_impostor();
    GeomLod lean = levels[kLayered];
    lean.layers = kLayerSkeleton | kLayerMuscle | kLayerSkin;  // no fat springs
    lean.level = static_cast<uint8_t>(levels.size());
    levels.push_back(lean);
    GeometryController ctl(g, levels, 3);
    for (const uint32_t c : {0u, 1u}) ctl.begin_level(c, kLayered, -1, 0);
    const uint32_t both[2] = {0, 1};
    auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 320);
    for (int f = 0; f < 3; ++f) {  // a few frames walked, so the fat springs carry motion
        pose = test::clip_pose(g.skeleton(), humanoid().clip, 320 + size_t(f));
        ctl.update(kLayered, both, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    }
    const std::vector<glm::vec3> shown_at_switch = copy(ctl.surface(0).positions);
    constexpr uint16_t M = 5;
    ctl.begin_level(0, lean.level, kLayered, M);
    ctl.begin_level(2, lean.level, -1, 0);
    EXPECT_EQ(ctl.fade(0), nullptr);                 // no cross-fade between these two
    EXPECT_EQ(ctl.characters_at(kLayered), 2u);      // the witness and the morph's source
    pose = test::clip_pose(g.skeleton(), humanoid().clip, 326);
    expect_morph_starts_at_this_pose(ctl, kLayered, lean.level, pose, shown_at_switch, M);
    ctl.advance_fades();  // the source has served: released
    EXPECT_EQ(ctl.characters_at(kLayered), 1u);
    // A switch back keeps it again; ending the character releases both its slots.
    ctl.begin_level(0, kLayered, static_cast<int8_t>(lean.level), M);
    EXPECT_EQ(ctl.characters_at(lean.level), 2u);
    ctl.end_character(0);
    EXPECT_EQ(ctl.characters_at(lean.level), 1u);
    EXPECT_EQ(ctl.characters_at(kLayered), 1u);
    // With the source released before the entered level's first update (advance_fades between them) there is no
    // start to read: the morph is dropped and the level shows its own surface.
    ctl.begin_level(2, kLayered, static_cast<int8_t>(lean.level), M);
    EXPECT_EQ(ctl.geomorph_frames_left(2), M);
    ctl.advance_fades();
    const uint32_t late[1] = {2};
    ctl.update(kLayered, late, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    EXPECT_EQ(ctl.geomorph_frames_left(2), 0);
}

TEST(LevelFades, OnlyImpostorSwitchesOfTwoFramesOrMoreFadeAndEveryEndReleasesTheKeptSlot) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, levels_with_impostor(), 2);
    const uint32_t one[1] = {0};
    const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 50);
    auto show = [&](uint8_t level) { ctl.update(level, one, PoseSource{pose.data(), 0}, 1.0f / 60.0f); };
    // A mesh never shown (no update since it entered) has nothing to fade out.
    ctl.begin_level(0, kSkinned, -1, 0);
    ctl.begin_level(0, kImpostor, kSkinned, 6);
    EXPECT_EQ(ctl.fade(0), nullptr);
    EXPECT_EQ(ctl.characters_at(kSkinned), 0u);
    // One frame is a pop (frame 1 of 1 is the new level alone), as for a geomorph.
    ctl.begin_level(0, kSkinned, kImpostor, 1);
    EXPECT_EQ(ctl.fade(0), nullptr);
    show(kSkinned);
    // Between mesh levels showing different surfaces a fade too (skinned 8x6 -> layered 8x6: the same vertices,
    // lit per vertex against per pixel); to or from hidden nothing.
    ctl.begin_level(0, kLayered, kSkinned, 6);
    ASSERT_NE(ctl.fade(0), nullptr);
    EXPECT_TRUE(ctl.fade(0)->between_meshes);
    show(kLayered);
    ctl.begin_level(0, kHidden, kLayered, 6);
    EXPECT_EQ(ctl.fade(0), nullptr);
    ctl.begin_level(0, kImpostor, kHidden, 6);
    EXPECT_EQ(ctl.fade(0), nullptr);
    // A switch during a fade ends it (kept slot released) and starts the new one.
    ctl.begin_level(0, kSkinned, kImpostor, 0);
    show(kSkinned);
    ctl.begin_level(0, kImpostor, kSkinned, 6);
    ASSERT_NE(ctl.fade(0), nullptr);
    EXPECT_EQ(ctl.characters_at(kSkinned), 1u);
    ctl.begin_level(0, kLayered, kImpostor, 6);
    ASSERT_NE(ctl.fade(0), nullptr);
    EXPECT_FALSE(ctl.fade(0)->into_impostor());
    EXPECT_EQ(ctl.characters_at(kSkinned), 0u);
    EXPECT_EQ(ctl.fades().size(), 1u);
    // Despawning and a rule reload end fades too.
    show(kLayered);
    ctl.begin_level(0, kImpostor, kLayered, 6);
    EXPECT_EQ(ctl.characters_at(kLayered), 1u);
    ctl.end_character(0);
    EXPECT_TRUE(ctl.fades().empty());
    EXPECT_EQ(ctl.characters_at(kLayered), 0u);
    ctl.begin_level(1, kSkinned, -1, 0);
    const uint32_t other[1] = {1};
    ctl.update(kSkinned, other, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    ctl.begin_level(1, kImpostor, kSkinned, 6);
    EXPECT_EQ(ctl.fades().size(), 1u);
    ctl.set_levels(levels_with_impostor());
    EXPECT_TRUE(ctl.fades().empty());
    EXPECT_EQ(ctl.characters_at(kSkinned), 0u);
    EXPECT_EQ(ctl.level_of(1), kImpostor);
}

}  // namespace
}  // namespace aloha
