// The fidelity reference's own fat springs (GeometryController::step_reference_springs): the full-detail
// body moving as the character moves, to read the deviation with the fat motion on both sides.
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <numeric>

namespace aloha {
namespace {

using test::humanoid;

constexpr float kDt = 1.0f / 30.0f;

// A second of walking forward at 1.4 m/s: the shown level updated with the character's placement and,
// after it (as World::step does), the reference springs at `reference_level`.
void walk(GeometryController& ctl, uint8_t shown_level, uint8_t reference_level, std::vector<glm::mat4>& pose) {
    const CharacterGeometry& g = *humanoid().geometry;
    const uint32_t c0 = 0, element = 0;
    for (int k = 0; k <= 30; ++k) {
        pose = test::clip_pose(g.skeleton(), humanoid().clip, 300 + 2 * k);
        Transform t;
        t.position = glm::vec3(0.0f, 0.0f, 1.4f * kDt * float(k));
        ctl.update(shown_level, std::span(&c0, 1), PoseSource{pose.data(), 0}, kDt, PlacementSource{std::span(&t, 1), std::span(&element, 1)});
        ctl.step_reference_springs(reference_level, std::span(&c0, 1), PoseSource{pose.data(), 0}, kDt, std::span(&t, 1));
    }
}

float mean_distance(std::span<const glm::vec3> a, std::span<const glm::vec3> b) {
    float sum = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) sum += glm::length(a[i] - b[i]);
    return a.empty() ? 0.0f : sum / float(a.size());
}

// A character shown at the reference level itself: its springs and the reference springs start at rest on
// the same frame and are stepped by the same code with the same poses, placements and time step, so the
// moving reference is the shown surface bit for bit, while the resting reference is not (the springs moved).
TEST(ReferenceSprings, AtTheShownLevelTheyAreTheShownSurface) {
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 1);
    ctl.begin_level(0, 1, -1, 0);  // Layered(16, 12), with fat springs
    std::vector<glm::mat4> pose;
    walk(ctl, 1, 1, pose);
    EXPECT_EQ(ctl.reference_spring_frames(0), 31u);
    std::vector<glm::vec3> current, ref, moving;
    ctl.deviation_pairs(PoseSource{pose.data(), 0}, 0, 1, current, ref, nullptr, &moving);
    ASSERT_EQ(moving.size(), current.size());
    EXPECT_GT(test::max_distance(current, ref), 1e-4f) << "the springs did not move: the test shows nothing";
    EXPECT_EQ(test::max_distance(current, moving), 0.0f);
}

// At a coarser layered level the shown springs move like the reference's, so the moving reference is
// nearer than the resting one. A regression guard (the margin depends on the tuning), not a proof.
TEST(ReferenceSprings, AtACoarserLevelTheMovingReferenceIsTheNearer) {
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 1);
    ctl.begin_level(0, 2, -1, 0);  // Layered(8, 6)
    std::vector<glm::mat4> pose;
    walk(ctl, 2, 1, pose);
    std::vector<glm::vec3> current, ref, rest, moving;
    ctl.deviation_pairs(PoseSource{pose.data(), 0}, 0, 1, current, ref, &rest, &moving);
    ASSERT_EQ(moving.size(), current.size());
    const float literal = mean_distance(current, ref), against_moving = mean_distance(current, moving);
    EXPECT_LT(against_moving, literal);
    std::cout << "mean distance: against the resting reference " << literal << " m, against the moving one " << against_moving
              << " m, both at rest " << mean_distance(rest, ref) << " m\n";
}

// Characters not given, or no longer at a mesh level, drop their reference springs (slots returned); so
// does a new level table; a level without fat springs carries none.
TEST(ReferenceSprings, DroppedWhenNotGivenOffTheMeshLevelsOrOnNewLevels) {
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 2);
    ctl.begin_level(0, 2, -1, 0);
    ctl.begin_level(1, 4, -1, 0);  // a rigid proxy: not a mesh level
    std::vector<glm::mat4> pose = test::clip_pose(g.skeleton(), humanoid().clip, 300);
    const PoseSource src{pose.data(), 0};
    const uint32_t both[2] = {0, 1};
    const Transform t[2] = {};
    ctl.step_reference_springs(1, both, src, kDt, t);
    EXPECT_EQ(ctl.reference_spring_frames(0), 1u);
    EXPECT_EQ(ctl.reference_spring_frames(1), 0u);
    ctl.step_reference_springs(1, std::span(both, 1), src, kDt, std::span(t, 1));
    EXPECT_EQ(ctl.reference_spring_frames(0), 2u);
    ctl.step_reference_springs(1, std::span(both + 1, 1), src, kDt, std::span(t + 1, 1));  // 0 not given
    EXPECT_EQ(ctl.reference_spring_frames(0), 0u);
    ctl.step_reference_springs(1, std::span(both, 1), src, kDt, std::span(t, 1));
    EXPECT_EQ(ctl.reference_spring_frames(0), 1u);  // started again
    // Dropped slots go back to the level's store: starting and dropping again and again takes no new room.
    const uint32_t capacity = ctl.slot_capacity(1);
    for (uint32_t k = 0; k < 3 * ctl.slots_per_page(1); ++k) {
        ctl.step_reference_springs(1, std::span(both + 1, 1), src, kDt, std::span(t + 1, 1));
        ctl.step_reference_springs(1, std::span(both, 1), src, kDt, std::span(t, 1));
    }
    EXPECT_EQ(ctl.slot_capacity(1), capacity);
    ctl.set_levels(test::test_levels());
    EXPECT_EQ(ctl.reference_spring_frames(0), 0u);
    ctl.step_reference_springs(3, both, src, kDt, t);  // SkinnedMesh: no fat springs
    EXPECT_EQ(ctl.reference_spring_frames(0), 0u);
    std::vector<glm::vec3> current, ref, moving;
    ctl.update(2, std::span(both, 1), src, kDt);
    ctl.deviation_pairs(src, 0, 1, current, ref, nullptr, &moving);
    EXPECT_FALSE(current.empty());
    EXPECT_TRUE(moving.empty());
}

}  // namespace
}  // namespace aloha
