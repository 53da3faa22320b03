// The generated motion library on characters from files (host/scene/character_library.hpp): a mapped humanoid
// brought without motion walks, idles, turns and waves as the built-in humanoid does, arms down whatever its rest
// pose; its own walk loops stay its walk; `generated_motion: false` and non-humanoids get none.
#include "systems/motion/clip.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/clip_pose.hpp"
#include "tests/common/rig_fixtures.hpp"
#include "tests/host/scene/character_checks.hpp"

#include <cstdio>
#include <iterator>

namespace aloha {
namespace {

namespace fs = std::filesystem;
using namespace test;  // NOLINT: the character checks

bool has_note(const CharacterType& t, const std::string& part) {
    for (const std::string& n : t.notes)
        if (n.find(part) != std::string::npos) return true;
    return false;
}

// A Rigify-named glTF of the built-in proportions (one animation, "sway", that does not loop), arms down or in a
// T-pose, loaded as type `name`.
CharacterType rigify_type(const fs::path& dir, const std::string& name, bool t_pose, bool generated = true) {
    RigStyle style;
    style.t_pose = t_pose;
    const fs::path file = dir / (name + ".gltf");
    test::write_text(file.string(), test::gltf_text(test::styled(test::renamed_humanoid(test::rigify_names("DEF-"), {}, t_pose), style), 1, 0.3f));
    CharacterTypeDesc d = desc_for(name, file.string());
    d.generated_motion = generated;
    return load_or_fail(d);
}

// Joints from `j` up to the root: how many rotations a model-space direction below `j` is the product of.
int chain_depth(const Skeleton& sk, int j) {
    int depth = 0;
    for (; j >= 0; j = sk.parents()[static_cast<size_t>(j)]) ++depth;
    return depth;
}

const char* const kClipNames[] = {"walk_0.50", "walk_1.40", "run_3.00", "idle", "turn", "wave"};

// The same generated clip on an arms-down and a T-posed rig of one body: every aligned limb bone (upper arm, forearm,
// thigh, shin) points the same way at every 1/30 s, since retargeting turns each target bone onto the source bone's
// direction whatever its rest. Bound: each clip is stored quantised, a model direction below joint j is off by at
// most depth(j) x the rotation bound plus twice the translation bound over the bone's length, on each side; 1e-5 rad
// for retargeting's float arithmetic (Retarget.* measure 1.4e-6).
TEST(CharacterLibrary, TPosedRigPlaysTheLibraryAsTheArmsDownRigDoes) {
    const fs::path dir = temp_dir("library_tpose");
    const CharacterType down = rigify_type(dir, "down", false), tee = rigify_type(dir, "tee", true);
    const std::pair<const char*, const char*> bones[] = {{"LeftShoulder", "LeftElbow"}, {"LeftElbow", "LeftWrist"},   {"RightShoulder", "RightElbow"},
                                                         {"RightElbow", "RightWrist"},  {"LeftHip", "LeftKnee"},       {"LeftKnee", "LeftAnkle"},
                                                         {"RightHip", "RightKnee"},     {"RightKnee", "RightAnkle"}};
    float worst = 0.0f;
    for (const char* clip_name : kClipNames) {
        const int a = find_clip(down, std::string("down.") + clip_name), b = find_clip(tee, std::string("tee.") + clip_name);
        ASSERT_GE(a, 0) << clip_name;
        ASSERT_GE(b, 0) << clip_name;
        const AnimationClip& ca = *down.clips.find(static_cast<ClipId>(a));
        const AnimationClip& cb = *tee.clips.find(static_cast<ClipId>(b));
        ASSERT_NEAR(ca.duration(), cb.duration(), 1e-6f) << clip_name << ": one body, one library";
        for (float t = 0.0f; t <= ca.duration(); t += 1.0f / 30.0f) {
            const std::vector<glm::vec3> pa = clip_model_positions(ca, down.skeleton, t), pb = clip_model_positions(cb, tee.skeleton, t);
            for (const auto& [from, to] : bones) {
                const int fa = down.map.find(from), ta = down.map.find(to), fb = tee.map.find(from), tb = tee.map.find(to);
                const glm::vec3 da = pa[static_cast<size_t>(ta)] - pa[static_cast<size_t>(fa)], db = pb[static_cast<size_t>(tb)] - pb[static_cast<size_t>(fb)];
                const float length = std::min(glm::length(da), glm::length(db));
                const float bound = static_cast<float>(chain_depth(down.skeleton, ta)) * ca.error_bound().rotation +
                                    static_cast<float>(chain_depth(tee.skeleton, tb)) * cb.error_bound().rotation +
                                    2.0f * (ca.error_bound().translation + cb.error_bound().translation) / length + 1e-5f;
                // atan2 of sine and cosine: acos of a float cosine cannot tell angles under 5e-4 rad from 0.
                const float angle = std::atan2(glm::length(glm::cross(da, db)), glm::dot(da, db));
                worst = std::max(worst, angle);
                ASSERT_LE(angle, bound) << clip_name << " at " << t << " s: " << from << " -> " << to;
            }
        }
    }
    std::printf("[figure] T-posed against arms-down rig, generated clips: largest limb bone angle %.2g rad\n", static_cast<double>(worst));
    // And the arms hang: in the idle's first pose each wrist is more than 0.8 arm lengths below its shoulder (the
    // T-pose's rest has them level; the built-in idle's arms hang close to vertical).
    const AnimationClip& idle = *tee.clips.find(static_cast<ClipId>(tee.idle_clip));
    const std::vector<glm::vec3> p = clip_model_positions(idle, tee.skeleton, 0.0f);
    for (const char* side : {"Left", "Right"}) {
        const glm::vec3 shoulder = p[static_cast<size_t>(tee.map.find(std::string(side) + "Shoulder"))];
        const glm::vec3 elbow = p[static_cast<size_t>(tee.map.find(std::string(side) + "Elbow"))];
        const glm::vec3 wrist = p[static_cast<size_t>(tee.map.find(std::string(side) + "Wrist"))];
        const float arm = glm::length(elbow - shoulder) + glm::length(wrist - elbow);
        EXPECT_GT(shoulder.y - wrist.y, 0.8f * arm) << side;
    }
}

// What the type gets: the eight gaits are its walk (slowest first), the idle is what idlers play, turn and wave play
// by name; one note says where it came from. The gaits walk with planted feet at the clip level: the bar the
// kinematic walk and retargeted takes are held to (CharacterMotions.WalkTakeBecomesTheTypesClipWalk: drift under
// 1 cm), at 1.2 m/s (between two gaits: the nearest is warped) and 2.6 m/s (a run).
TEST(CharacterLibrary, GaitsAreTheWalkAndTheIdleIsWhatIdlersPlay) {
    const fs::path dir = temp_dir("library_walk");
    const CharacterType t = rigify_type(dir, "rig", true);
    ASSERT_EQ(t.gait_clips.size(), std::size(kLibraryGaitSpeeds)) << "the file's 'sway' does not loop: the gaits are the walk";
    for (size_t g = 1; g < t.gait_clips.size(); ++g)
        EXPECT_LT(t.clips.find(t.gait_clips[g - 1])->root_speed(), t.clips.find(t.gait_clips[g])->root_speed()) << "slowest first";
    EXPECT_EQ(find_clip(t, ""), find_clip(t, "rig.idle")) << "idlers play the generated idle";
    EXPECT_GE(find_clip(t, "rig.turn"), 0);
    EXPECT_GE(find_clip(t, "rig.wave"), 0);
    EXPECT_GE(find_clip(t, "sway"), 0) << "the file's own clips stay";
    EXPECT_TRUE(has_note(t, "generated motion retargeted from the built-in humanoid at 1.75 m (pelvis travel x1.000")) << t.notes.back();
    EXPECT_TRUE(has_note(t, "the gaits are its walk"));
    ASSERT_TRUE(t.rig.has_value());
    for (const float speed : {1.2f, 2.6f}) expect_clip_walk(t, speed, "generated gaits on a T-posed Rigify glTF");
}

// The scene's `idle` names any of the type's clips to idle in (here the file's "sway" over the generated idle); one the
// type lacks is an error at the type's "idle".
TEST(CharacterLibrary, TheScenesIdleChoiceWins) {
    const fs::path dir = temp_dir("library_idle");
    RigStyle style;
    const fs::path file = dir / "rig.gltf";
    test::write_text(file.string(), test::gltf_text(test::styled(test::renamed_humanoid(test::rigify_names("DEF-")), style), 1, 0.3f));
    CharacterTypeDesc d = desc_for("rig", file.string());
    d.idle = "sway";
    const CharacterType t = load_or_fail(d);
    EXPECT_EQ(t.idle_clip, find_clip(t, "sway"));
    EXPECT_EQ(find_clip(t, ""), find_clip(t, "sway")) << "what idlers play";
    EXPECT_TRUE(has_note(t, "idle: 'sway' (the scene's choice)"));
    d.idle = "rig.wave";
    EXPECT_EQ(load_or_fail(d).idle_clip, find_clip(t, "rig.wave")) << "a generated clip will do too";
    d.idle = "Idle";
    const Result<CharacterType> missing = load_character_type(d);
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().to_string().find("test-scene.json: /character_types/0/idle: type 'rig' has no clip 'Idle' to idle in"),
              std::string::npos)
        << missing.error().to_string();
}

// `generated_motion: false` leaves the type as its file made it; a non-humanoid gets no library (nothing to
// retarget through), and says nothing about one.
TEST(CharacterLibrary, NoneWhenTurnedOffOrNotAHumanoid) {
    const fs::path dir = temp_dir("library_off");
    const CharacterType off = rigify_type(dir, "off", true, false);
    EXPECT_TRUE(off.gait_clips.empty());
    EXPECT_EQ(off.idle_clip, -1);
    EXPECT_LT(find_clip(off, "off.idle"), 0);
    EXPECT_FALSE(has_note(off, "generated motion"));

    test::write_text((dir / "dog.bvh").string(), test::bvh_text(test::quadruped(), 30, glm::vec3(0, 0, 1), 1.0f));
    const CharacterType dog = load_or_fail(desc_for("dog", (dir / "dog.bvh").string()));
    EXPECT_FALSE(dog.map.humanoid);
    EXPECT_EQ(dog.idle_clip, -1);
    EXPECT_LT(find_clip(dog, "dog.walk_1.40"), 0);
    EXPECT_FALSE(has_note(dog, "generated motion"));
    // Nor can a crowd vary its height (a standing height needs the canonical legs and head to measure).
    CharacterTypeDesc tall = desc_for("dog", (dir / "dog.bvh").string());
    tall.standing_height = 1.7f;
    const Result<CharacterType> refused = load_character_type(tall);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().to_string().find("is no mapped humanoid: it has no standing height to vary"), std::string::npos)
        << refused.error().to_string();
}

}  // namespace
}  // namespace aloha
