// Clips played over and over (host/scene/character_loops.hpp). A file's own idle, which idlers play over and over: one whose ends nearly meet gets a looped version closed where it
// repeats (its first and last poses made equal, the note giving the seam it had), the clip itself kept as the file has
// it for a play once; one that does not loop has no looped version, with a note giving how far it jumps; a held pose
// (one key) is noted as the idle with no seam. Any other clip of a file or of a motion file, which a looping `play`
// repeats, is judged the same way, in one note for all.
#include "host/scene/character_type.hpp"
#include "host/scene/motion_sample.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/library/loop_cut.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/clip_pose.hpp"
#include "tests/common/gltf_writer.hpp"
#include "tests/common/rig_fixtures.hpp"
#include "tests/host/scene/character_checks.hpp"
#include "tests/host/scene/world_test_util.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

namespace fs = std::filesystem;
using namespace test;  // NOLINT: the character checks

// `idle` with the lower back turned by up to `angle` radians about X over its last `over` seconds (0 before).
RawAnimation drifting(const RawAnimation& idle, const Skeleton& sk, float angle, float over) {
    RawAnimation out = idle;
    RawTrack<glm::quat>& spine = out.tracks[static_cast<size_t>(sk.find("lowerback"))].rotations;
    for (size_t k = 0; k < spine.times.size(); ++k) {
        const float s = std::max(0.0f, (spine.times[k] - (out.duration - over)) / over);
        spine.values[k] = glm::angleAxis(angle * s, glm::vec3(1, 0, 0)) * spine.values[k];
    }
    return out;
}

// Mean joint distance between a clip's first and last poses.
float ends_apart(const AnimationClip& clip, const Skeleton& sk) {
    const auto a = clip_model_positions(clip, sk, 0.0f), b = clip_model_positions(clip, sk, clip.duration());
    float sum = 0.0f;
    for (size_t j = 0; j < a.size(); ++j) sum += glm::length(a[j] - b[j]);
    return sum / static_cast<float>(a.size());
}

// The built-in humanoid's idle as a file might ship it: `near`, its lower back turned 0.04 rad over the last half
// second (the ends a centimetre or so apart, within find_best_loop's 3 cm), and `far`, 0.6 rad (far beyond it).
struct DriftingIdles {
    Skeleton body = humanoid_skeleton_for({1.75f, 0.5f});
    MotionLibrary lib = make_motion_library(body, humanoid_rig(body), "src");
    AnimationClip near = built(drifting(lib.idle, body, 0.04f, 0.5f));
    AnimationClip far = built(drifting(lib.idle, body, 0.6f, 0.5f));
    [[nodiscard]] AnimationClip built(const RawAnimation& raw) const { return build_clip(raw, body, ClipEncoding::Float32).value(); }
};

std::string idle_note(const CharacterType& t) {
    for (const std::string& n : t.notes)
        if (n.rfind("idle: the file's clip", 0) == 0) return n;
    return "(no idle note)";
}

TEST(CharacterIdle, AFileIdleThatNearlyLoopsIsClosedWhereItRepeats) {
    const fs::path dir = temp_dir("idle_seam");
    const DriftingIdles idles;
    const Skeleton& body = idles.body;
    const AnimationClip &near = idles.near, &far = idles.far;
    const float near_apart = ends_apart(near, body), far_apart = ends_apart(far, body);
    ASSERT_GT(near_apart, 0.002f);
    ASSERT_LT(near_apart, kMaxLoopPoseError);
    ASSERT_GT(far_apart / 2.0f, kMaxSeamBend);  // closing would bend it by half its ends' distance at least

    write_gltf_with_clips((dir / "near.gltf").string(), body, {{"Idle", &near}});
    const CharacterType t = load_or_fail(desc_for("near", (dir / "near.gltf").string()));
    ASSERT_EQ(t.idle_clip, t.clips.find("Idle"));
    ASSERT_TRUE(t.clips.has_looped(static_cast<ClipId>(t.idle_clip)));
    const AnimationClip& closed = *t.clips.find_looped(static_cast<ClipId>(t.idle_clip));
    const float closed_apart = ends_apart(closed, t.skeleton);
    // Played once, the clip is the file's: its ends as far apart as they were, within the 16-bit keys' error (the
    // bound below, for each end).
    const AnimationClip& as_loaded = *t.clips.find(static_cast<ClipId>(t.idle_clip));
    EXPECT_NEAR(ends_apart(as_loaded, t.skeleton), near_apart, 2.0f * (2.0f * (2.0f * as_loaded.error_bound().rotation + as_loaded.error_bound().translation) + 1e-5f));
    std::printf("idle ends %.2f cm apart in the file, %.4f cm once closed; %s\n", static_cast<double>(100.0f * near_apart),
                static_cast<double>(100.0f * closed_apart), idle_note(t).c_str());
    // The ends' rotations are made equal before the clip is stored (16-bit keys): each end sits within the stored
    // key's error bound of the closed value, and a joint's position errs by at most that angle times its distance
    // from the root, summed down the chain (under 2 m of bones in all for this body).
    EXPECT_LT(closed_apart, 2.0f * (2.0f * closed.error_bound().rotation + closed.error_bound().translation) + 1e-5f);
    EXPECT_NE(idle_note(t).find("its ends differ by"), std::string::npos) << idle_note(t);
    EXPECT_NE(idle_note(t).find(": closed)"), std::string::npos) << idle_note(t);

    write_gltf_with_clips((dir / "far.gltf").string(), body, {{"Idle", &far}});
    const CharacterType f = load_or_fail(desc_for("far", (dir / "far.gltf").string()));
    ASSERT_EQ(f.idle_clip, f.clips.find("Idle"));
    EXPECT_FALSE(f.clips.has_looped(static_cast<ClipId>(f.idle_clip))) << "left as the file has it";
    EXPECT_NEAR(ends_apart(*f.clips.find_looped(static_cast<ClipId>(f.idle_clip)), f.skeleton), far_apart, 0.002f);
    EXPECT_NE(idle_note(f).find("too far to close (closing would bend it"), std::string::npos) << idle_note(f);
    EXPECT_NE(idle_note(f).find("faded over the level's cross-fade time each time idlers repeat it"), std::string::npos) << idle_note(f);

    // The scene's `idle` naming one of the file's animations closes it the same way.
    write_gltf_with_clips((dir / "breathe.gltf").string(), body, {{"Breathe", &near}});
    CharacterTypeDesc chosen = desc_for("breathe", (dir / "breathe.gltf").string());
    chosen.idle = "Breathe";
    const CharacterType b = load_or_fail(chosen);
    ASSERT_EQ(b.idle_clip, b.clips.find("Breathe"));
    EXPECT_LT(ends_apart(*b.clips.find_looped(static_cast<ClipId>(b.idle_clip)), b.skeleton), 2.0f * (2.0f * closed.error_bound().rotation + closed.error_bound().translation) + 1e-5f);
    bool noted = false;
    for (const std::string& n : b.notes) noted |= n.rfind("idle: 'Breathe' (the scene's choice) (its ends differ by", 0) == 0 && n.find(": closed)") != std::string::npos;
    EXPECT_TRUE(noted) << b.notes.back();

    // A held pose (one key) repeats nothing: noted as the idle, with no seam.
    RawAnimation pose = idles.lib.idle;
    for (RawJointTracks& tracks : pose.tracks) {
        for (auto* times : {&tracks.rotations.times, &tracks.translations.times, &tracks.scales.times}) times->resize(std::min<size_t>(times->size(), 1));
        tracks.rotations.values.resize(tracks.rotations.times.size());
        tracks.translations.values.resize(tracks.translations.times.size());
        tracks.scales.values.resize(tracks.scales.times.size());
    }
    pose.duration = 0.0f;
    const AnimationClip held = idles.built(pose);
    write_gltf_with_clips((dir / "held.gltf").string(), body, {{"Idle", &held}});
    const CharacterType h = load_or_fail(desc_for("held", (dir / "held.gltf").string()));
    EXPECT_EQ(idle_note(h), "idle: the file's clip 'Idle'");
}

bool has_note(const CharacterType& t, const std::string& start, const std::string& part) {
    for (const std::string& n : t.notes)
        if (n.rfind(start, 0) == 0 && n.find(part) != std::string::npos) return true;
    return false;
}

TEST(CharacterLoops, EveryClipThatNearlyLoopsGetsALoopedVersion) {
    const fs::path dir = temp_dir("clip_seams");
    const DriftingIdles idles;
    const Skeleton& body = idles.body;
    const AnimationClip &near = idles.near, &far = idles.far;
    write_gltf_with_clips((dir / "clips.gltf").string(), body, {{"Sway", &near}, {"Slump", &far}});
    const CharacterType t = load_or_fail(desc_for("clips", (dir / "clips.gltf").string()));
    const int sway = t.clips.find("Sway"), slump = t.clips.find("Slump"), inplace = t.inplace_clip;
    ASSERT_GE(sway, 0);
    ASSERT_GE(slump, 0);
    ASSERT_GE(inplace, 0);
    // Sway, and the in-place copy of the file's first clip (what a crowd plays by default), are closed: their looped
    // versions' ends meet within the 16-bit keys' error (as the idle's above); played once they are the file's.
    for (const int id : {sway, inplace}) {
        ASSERT_TRUE(t.clips.has_looped(static_cast<ClipId>(id))) << t.clips.find(static_cast<ClipId>(id))->name();
        const AnimationClip& looped = *t.clips.find_looped(static_cast<ClipId>(id));
        EXPECT_TRUE(looped.ends_meet());
        EXPECT_LT(ends_apart(looped, t.skeleton), 2.0f * (2.0f * looped.error_bound().rotation + looped.error_bound().translation) + 1e-5f);
        EXPECT_FALSE(t.clips.find(static_cast<ClipId>(id))->ends_meet());
    }
    EXPECT_FALSE(t.clips.has_looped(static_cast<ClipId>(slump)));  // jumps where it repeats: the controller fades it there
    // The idle idlers play here is the generated one retargeted: a cycle still, repeated without a transition.
    ASSERT_GE(t.idle_clip, 0);
    EXPECT_EQ(t.clips.find(static_cast<ClipId>(t.idle_clip))->name(), "clips.idle");
    EXPECT_TRUE(t.clips.find_looped(static_cast<ClipId>(t.idle_clip))->ends_meet());
    EXPECT_TRUE(has_note(t, "played looping, closed where they repeat: ", "'Sway' (its ends differ by"));
    EXPECT_TRUE(has_note(t, "played looping, closed where they repeat: ", "'clips.inplace'"));
    EXPECT_TRUE(has_note(t, "played looping, these are faded where they repeat (over the level's cross-fade time): ", "'Slump' (its ends differ by"));
    EXPECT_TRUE(has_note(t, "played looping, these are faded where they repeat (over the level's cross-fade time): ", "too far to close"));
}

TEST(CharacterLoops, OnlyTheFilesOwnAnimationsAreIdlesByName) {
    // The in-place copy of a file's first animation is named after the type: a type named "idler" must not take
    // "idler.inplace" for an idle by its name; with no animation named like an idle, it idles in the generated one.
    const fs::path dir = temp_dir("idle_by_name");
    const DriftingIdles idles;
    write_gltf_with_clips((dir / "sway.gltf").string(), idles.body, {{"Sway", &idles.near}});
    const CharacterType t = load_or_fail(desc_for("idler", (dir / "sway.gltf").string()));
    ASSERT_GE(t.idle_clip, 0);
    EXPECT_EQ(t.clips.find(static_cast<ClipId>(t.idle_clip))->name(), "idler.idle");
}

TEST(CharacterLoops, AMotionFilesClipsAndIdleAreClosedToo) {
    const fs::path dir = temp_dir("motion_seams");
    const DriftingIdles idles;
    const Skeleton& body = idles.body;
    const AnimationClip &near = idles.near, &far = idles.far;
    write_gltf_with_clips((dir / "moves.gltf").string(), body, {{"Breathe", &near}, {"Slump", &far}, {"Sway", &near}});
    CharacterTypeDesc d;
    d.name = "m";
    d.humanoid = builtin_humanoid();
    d.scene_file = "test-scene.json";
    d.pointer = "/character_types/0";
    MotionFileDesc m;
    m.gltf = (dir / "moves.gltf").string();
    m.pointer = "/character_types/0/motions/0";
    d.motions.push_back(m);
    d.idle = "m.Breathe";  // the scene names a motion file's clip as the idle
    const CharacterType t = load_or_fail(d);
    ASSERT_EQ(t.idle_clip, t.clips.find("m.Breathe"));
    EXPECT_TRUE(t.clips.has_looped(static_cast<ClipId>(t.idle_clip)));
    EXPECT_TRUE(has_note(t, "idle: 'm.Breathe' (the scene's choice) (its ends differ by", ": closed)"));
    EXPECT_TRUE(t.clips.has_looped(static_cast<ClipId>(t.clips.find("m.Sway"))));
    EXPECT_FALSE(t.clips.has_looped(static_cast<ClipId>(t.clips.find("m.Slump"))));
    EXPECT_TRUE(has_note(t, "played looping, closed where they repeat: ", "'m.Sway'"));
    EXPECT_FALSE(has_note(t, "played looping, closed where they repeat: ", "'m.Breathe'")) << "the idle's own note says it";
    // The built-in humanoid's own generated clips are made as cycles: only the motion file's two are closed.
    size_t looped = 0;
    for (size_t i = 0; i < t.clips.size(); ++i) looped += t.clips.has_looped(static_cast<ClipId>(i)) ? 1 : 0;
    EXPECT_EQ(looped, 2u);
}

TEST(CharacterLoops, AnIdlerStartsInThePoseItsTypeStandsIn) {
    // Characters stand in the first pose of the idle as idlers play it: its looped version, whose first pose is half
    // the seam away from the file's. A stander and an idler of a type whose Idle ends 0.68 cm from where it starts.
    const fs::path dir = temp_dir("stance");
    const DriftingIdles idles;
    write_gltf_with_clips((dir / "idle.gltf").string(), idles.body, {{"Idle", &idles.near}});
    const std::string json = R"({"name": "stance", "frames": 5, "camera": {"position": [1.5, 1.5, 6], "target": [1.5, 1, 0]},
      "character_types": [{"name": "t", "gltf": "idle.gltf"}],
      "characters": [{"type": "t", "position": [0, 0, 0]},
                     {"type": "t", "position": [3, 0, 0], "requests": [{"type": "play", "clip": "Idle", "loop": true}]}]})";
    WorldOptions o;
    o.pose_every_character = true;
    auto w = scene_test::make_world(scene_test::scene_from_json(json, (dir / "scene.json").string()), o);
    ASSERT_TRUE(w);
    const CharacterType& type = w->type(0);
    ASSERT_TRUE(type.clips.has_looped(static_cast<ClipId>(type.idle_clip)));
    w->step();
    MotionSample stander, idler;
    w->motion_sample(0, stander);
    w->motion_sample(1, idler);
    ASSERT_EQ(stander.joints.size(), idler.joints.size());
    ASSERT_EQ(stander.method, "rest");
    ASSERT_EQ(idler.method, "play_clip");
    float apart = 0.0f;
    for (size_t j = 0; j < stander.joints.size(); ++j) apart += glm::length((stander.joints[j] - stander.root) - (idler.joints[j] - idler.root));
    apart /= static_cast<float>(stander.joints.size());
    // The file's first pose is half the seam (0.34 cm per joint on the mean) from the looped version's; the idler has
    // moved one frame on (the idle's lower back turns at most 0.04 rad over its last half second, and its breathing
    // a few millimetres a second): well under a millimetre.
    const float half_seam = 0.5f * ends_apart(idles.near, idles.body);
    std::printf("stander and idler %.3f mm apart per joint after one frame (half the seam: %.2f mm)\n", static_cast<double>(1000.0f * apart),
                static_cast<double>(1000.0f * half_seam));
    EXPECT_LT(apart, 0.3f * half_seam);
}

}  // namespace
}  // namespace aloha
