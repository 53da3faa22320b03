// A file's own idle, which idlers play over and over: one whose ends nearly meet is closed where it repeats (its
// first and last poses made equal, the note giving the seam it had); one that does not loop is left as the file has it,
// with a note giving how far it jumps; a held pose (one key) is noted as the idle with no seam.
#include "host/scene/character_type.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/library/loop_cut.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/clip_pose.hpp"
#include "tests/common/gltf_writer.hpp"
#include "tests/common/rig_fixtures.hpp"
#include "tests/host/scene/character_checks.hpp"

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

std::string idle_note(const CharacterType& t) {
    for (const std::string& n : t.notes)
        if (n.rfind("idle: the file's clip", 0) == 0) return n;
    return "(no idle note)";
}

TEST(CharacterIdle, AFileIdleThatNearlyLoopsIsClosedWhereItRepeats) {
    const fs::path dir = temp_dir("idle_seam");
    const Skeleton body = humanoid_skeleton_for({1.75f, 0.5f});
    const MotionLibrary lib = make_motion_library(body, humanoid_rig(body), "src");
    ASSERT_GE(body.find("lowerback"), 0);
    auto built = [&](const RawAnimation& raw) { return build_clip(raw, body, ClipEncoding::Float32).value(); };
    // 0.04 rad over the last half second: the ends a centimetre or so apart, within find_best_loop's 3 cm; 0.6 rad:
    // far beyond it.
    const AnimationClip near = built(drifting(lib.idle, body, 0.04f, 0.5f)), far = built(drifting(lib.idle, body, 0.6f, 0.5f));
    const float near_apart = ends_apart(near, body), far_apart = ends_apart(far, body);
    ASSERT_GT(near_apart, 0.002f);
    ASSERT_LT(near_apart, kMaxLoopPoseError);
    ASSERT_GT(far_apart, kMaxLoopPoseError);

    write_gltf_with_clips((dir / "near.gltf").string(), body, {{"Idle", &near}});
    const CharacterType t = load_or_fail(desc_for("near", (dir / "near.gltf").string()));
    ASSERT_EQ(t.idle_clip, t.clips.find("Idle"));
    const AnimationClip& closed = *t.clips.find(static_cast<ClipId>(t.idle_clip));
    const float closed_apart = ends_apart(closed, t.skeleton);
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
    EXPECT_NEAR(ends_apart(*f.clips.find(static_cast<ClipId>(f.idle_clip)), f.skeleton), far_apart, 0.002f) << "left as the file has it";
    EXPECT_NE(idle_note(f).find("(does not loop: its ends differ by"), std::string::npos) << idle_note(f);
    EXPECT_NE(idle_note(f).find("it jumps each time idlers repeat it"), std::string::npos) << idle_note(f);

    // The scene's `idle` naming one of the file's animations closes it the same way.
    write_gltf_with_clips((dir / "breathe.gltf").string(), body, {{"Breathe", &near}});
    CharacterTypeDesc chosen = desc_for("breathe", (dir / "breathe.gltf").string());
    chosen.idle = "Breathe";
    const CharacterType b = load_or_fail(chosen);
    ASSERT_EQ(b.idle_clip, b.clips.find("Breathe"));
    EXPECT_LT(ends_apart(*b.clips.find(static_cast<ClipId>(b.idle_clip)), b.skeleton), 2.0f * (2.0f * closed.error_bound().rotation + closed.error_bound().translation) + 1e-5f);
    bool noted = false;
    for (const std::string& n : b.notes) noted |= n.rfind("idle: 'Breathe' (the scene's choice) (its ends differ by", 0) == 0 && n.find(": closed)") != std::string::npos;
    EXPECT_TRUE(noted) << b.notes.back();

    // A held pose (one key) repeats nothing: noted as the idle, with no seam.
    RawAnimation pose = lib.idle;
    for (RawJointTracks& tracks : pose.tracks) {
        for (auto* times : {&tracks.rotations.times, &tracks.translations.times, &tracks.scales.times}) times->resize(std::min<size_t>(times->size(), 1));
        tracks.rotations.values.resize(tracks.rotations.times.size());
        tracks.translations.values.resize(tracks.translations.times.size());
        tracks.scales.values.resize(tracks.scales.times.size());
    }
    pose.duration = 0.0f;
    const AnimationClip held = built(pose);
    write_gltf_with_clips((dir / "held.gltf").string(), body, {{"Idle", &held}});
    const CharacterType h = load_or_fail(desc_for("held", (dir / "held.gltf").string()));
    EXPECT_EQ(idle_note(h), "idle: the file's clip 'Idle'");
}

}  // namespace
}  // namespace aloha
