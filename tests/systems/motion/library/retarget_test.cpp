// Motion retargeting (systems/motion/library/retarget.hpp) on the built-in humanoid's generated walk:
// - onto the same skeleton it is the clip itself (every joint's model position within float rounding);
// - onto a taller, heavier body whose arms rest in a T-pose and whose knees rest bent, every canonical bone the
//   two align (the bones along each chain, the legs' thigh and shank aside) points where the source's points at
//   every key (angle within float rounding of 0), the pelvis travels as the source's times the ratio k of the rest
//   hip heights, from the ground each stands on, each ankle follows the source's ankle path scaled the same way
//   (the leg IK), so a foot the source plants stays planted, and bones keep the target's lengths;
// - a skeleton that is not a mapped humanoid is an error.
// Tolerances: 1e-5 m and 1e-5 rad are float rounding over a chain of some twenty quaternion and matrix products
// (about 1e-7 each; measured at most 7.2e-7 m and 1.4e-6 rad), with room for another compiler's rounding.
#include "engine/anim/humanoid_map.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "systems/motion/library/retarget.hpp"
#include "tests/common/clip_pose.hpp"
#include "tests/common/test_humanoid.hpp"

#include <glm/gtx/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string_view>

namespace aloha {
namespace {

using test::clip_model_positions;

HumanoidMap mapped(const Skeleton& sk) {
    Result<HumanoidMap> m = map_humanoid(sk);
    EXPECT_TRUE(m.ok() && m.value().humanoid);
    return m.ok() ? m.value() : HumanoidMap{};
}

// The built-in humanoid's raw skeleton for `body`, with its arms raised to a T-pose at the shoulders and its
// knees bent 20 degrees at rest.
Skeleton t_posed(const HumanoidBody& body) {
    auto def = load_humanoid_definition(test::humanoid_definition_path());
    EXPECT_TRUE(def.ok());
    RawSkeleton raw = humanoid_skeleton(def.value(), body);
    for (RawJoint& j : raw.joints) {
        if (j.name == "LeftShoulder") j.rotation = glm::angleAxis(glm::radians(80.0f), glm::vec3(0, 0, 1));
        if (j.name == "RightShoulder") j.rotation = glm::angleAxis(glm::radians(-80.0f), glm::vec3(0, 0, 1));
        if (j.name == "LeftKnee" || j.name == "RightKnee") j.rotation = glm::angleAxis(glm::radians(20.0f), glm::vec3(1, 0, 0));
    }
    Result<Skeleton> sk = build_skeleton(raw, "t_posed");
    EXPECT_TRUE(sk.ok());
    return sk.ok() ? std::move(sk).value() : Skeleton{};
}

class Retarget : public ::testing::Test {
protected:
    Skeleton source = test::humanoid_skeleton_for({1.62f, 0.3f});
    HumanoidMap source_map = mapped(source);
    RawAnimation walk = make_motion_library(source, test::humanoid_rig(source), "s").gaits[3];
};

TEST_F(Retarget, OntoTheSameSkeletonIsTheClipItself) {
    Result<RawAnimation> out = retarget_clip(walk, {&source, &source_map}, {&source, &source_map}, "same");
    ASSERT_TRUE(out.ok()) << out.error().to_string();
    const AnimationClip a = build_clip(walk, source, ClipEncoding::Float32).value();
    const AnimationClip b = build_clip(out.value(), source, ClipEncoding::Float32).value();
    ASSERT_EQ(a.key_count(), b.key_count());
    float worst = 0.0f;
    for (const float t : a.times()) {
        const std::vector<glm::vec3> pa = clip_model_positions(a, source, t), pb = clip_model_positions(b, source, t);
        for (size_t j = 0; j < pa.size(); ++j) worst = std::max(worst, glm::length(pa[j] - pb[j]));
    }
    EXPECT_LT(worst, 1e-5f);
}

TEST_F(Retarget, BonesPointAsTheSourcesWhateverTheRestPoseAndPelvisTravelScales) {
    const Skeleton target = t_posed({1.93f, 0.9f});
    const HumanoidMap target_map = mapped(target);
    RetargetReport report;
    Result<RawAnimation> out = retarget_clip(walk, {&source, &source_map}, {&target, &target_map}, "t.walk", &report);
    ASSERT_TRUE(out.ok()) << out.error().to_string();
    EXPECT_EQ(out.value().name, "t.walk");
    EXPECT_TRUE(report.kept_at_rest.empty());
    const AnimationClip a = build_clip(walk, source, ClipEncoding::Float32).value();
    const AnimationClip b = build_clip(out.value(), target, ClipEncoding::Float32).value();
    const std::vector<glm::vec3> rest_s = clip_model_positions(build_clip(RawAnimation{}, source).value(), source, 0.0f);
    const std::vector<glm::vec3> rest_t = clip_model_positions(build_clip(RawAnimation{}, target).value(), target, 0.0f);
    const auto joints = canonical_humanoid();
    const auto hips_s = static_cast<size_t>(source_map.joint[0]), hips_t = static_cast<size_t>(target_map.joint[0]);
    // Heights from the lowest body (canonical) joint; the built-in humanoid's joints are all canonical.
    float lowest_s = 1e9f, lowest_t = 1e9f;
    for (const int j : source_map.joint)
        if (j >= 0) lowest_s = std::min(lowest_s, rest_s[static_cast<size_t>(j)].y);
    for (const int j : target_map.joint)
        if (j >= 0) lowest_t = std::min(lowest_t, rest_t[static_cast<size_t>(j)].y);
    const float k = (rest_t[hips_t].y - lowest_t) / (rest_s[hips_s].y - lowest_s);
    EXPECT_NEAR(report.scale, k, 1e-6f);
    EXPECT_GT(k, 1.1f) << "a taller body";
    float ground_s = 1e9f;  // the lowest any source body joint comes over the clip
    for (const float t : a.times()) {
        const std::vector<glm::vec3> p = clip_model_positions(a, source, t);
        for (const int j : source_map.joint)
            if (j >= 0) ground_s = std::min(ground_s, p[static_cast<size_t>(j)].y);
    }
    float worst_angle = 0.0f, worst_travel = 0.0f, worst_length = 0.0f, worst_ankle = 0.0f, worst_planted = 0.0f;
    std::vector<glm::vec3> previous_s, previous_t;
    for (const float t : a.times()) {
        const std::vector<glm::vec3> ps = clip_model_positions(a, source, t), pt = clip_model_positions(b, target, t);
        for (size_t c = 1; c < joints.size(); ++c) {
            const int parent = joints[c].parent;
            const int s0 = source_map.joint[static_cast<size_t>(parent)], s1 = source_map.joint[c];
            const int t0 = target_map.joint[static_cast<size_t>(parent)], t1 = target_map.joint[c];
            // Bones along a chain: the first child on the parent's side (the spine's centre child, not a collar; the
            // fingers, not the thumb). Not the pelvis's: its orientation is the body's, taken as it is.
            if (parent == 0 || joints[c].side != joints[static_cast<size_t>(parent)].side) continue;
            bool first = true;
            for (size_t e = static_cast<size_t>(parent) + 1; e < c; ++e)
                if (joints[e].parent == parent && joints[e].side == joints[c].side) first = false;
            if (!first) continue;
            // The thigh and shank are the leg IK's (checked below by the ankle's path).
            if (std::string_view(joints[c].name).find("Knee") != std::string_view::npos ||
                std::string_view(joints[c].name).find("Ankle") != std::string_view::npos)
                continue;
            const glm::vec3 bs = ps[static_cast<size_t>(s1)] - ps[static_cast<size_t>(s0)];
            const glm::vec3 bt = pt[static_cast<size_t>(t1)] - pt[static_cast<size_t>(t0)];
            if (glm::length(bs) < 1e-3f) continue;
            // atan2(|a x b|, a . b): accurate at small angles, where acos of a float cosine is not (1 ulp below 1 is 3.5e-4 rad).
            worst_angle = std::max(worst_angle, std::atan2(glm::length(glm::cross(bs, bt)), glm::dot(bs, bt)));
            const glm::vec3 rest_bone = rest_t[static_cast<size_t>(t1)] - rest_t[static_cast<size_t>(t0)];
            worst_length = std::max(worst_length, std::abs(glm::length(bt) - glm::length(rest_bone)));
        }
        const glm::vec3 want(k * ps[hips_s].x, lowest_t + k * (ps[hips_s].y - ground_s), k * ps[hips_s].z);
        worst_travel = std::max(worst_travel, glm::length(pt[hips_t] - want));
        // Each ankle on the source ankle's path, scaled as the pelvis travel, from its own rest height.
        for (const char* ankle : {"LeftAnkle", "RightAnkle"}) {
            const auto as = static_cast<size_t>(source_map.find(ankle)), at = static_cast<size_t>(target_map.find(ankle));
            const float rest_s_h = rest_s[as].y - lowest_s, rest_t_h = rest_t[at].y - lowest_t;
            const glm::vec3 path(k * ps[as].x, lowest_t + rest_t_h + k * (ps[as].y - ground_s - rest_s_h), k * ps[as].z);
            worst_ankle = std::max(worst_ankle, glm::length(pt[at] - path));
            // Planted: where the source's ankle moves under 1 mm between keys, the target's moves at most k times as far.
            if (t > 0.0f) {
                const float moved_s = glm::length(ps[as] - previous_s[as]), moved_t = glm::length(pt[at] - previous_t[at]);
                if (moved_s < 1e-3f) worst_planted = std::max(worst_planted, moved_t - k * moved_s);
            }
        }
        previous_s = ps;
        previous_t = pt;
    }
    EXPECT_LT(worst_ankle, 1e-5f) << "m: the ankles on the scaled path (report: " << report.foot_reach_error << ")";
    EXPECT_LT(worst_planted, 1e-5f) << "m: a planted source foot is planted on the target";
    EXPECT_LT(report.foot_reach_error, 1e-5f);
    EXPECT_LT(worst_angle, 1e-5f) << "radians";
    EXPECT_LT(worst_travel, 1e-5f) << "m";
    EXPECT_LT(worst_length, 1e-5f) << "m: the target's bone lengths";
}

TEST_F(Retarget, ASkeletonThatIsNotAMappedHumanoidIsAnError) {
    HumanoidMap none;
    Result<RawAnimation> out = retarget_clip(walk, {&source, &none}, {&source, &source_map}, "x");
    ASSERT_FALSE(out.ok());
    EXPECT_NE(out.error().to_string().find("not a mapped humanoid"), std::string::npos) << out.error().to_string();
}

}  // namespace
}  // namespace aloha
