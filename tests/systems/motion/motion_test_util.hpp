// Synthetic skeletons and clips shared by the motion tests and benchmark.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/raw_skeleton.hpp"
#include "engine/anim/skeleton.hpp"

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <string>

namespace aloha::test {

/// A chain of `n` joints, each 0.1 m along +Y from its parent.
inline RawSkeleton make_chain(int n) {
    RawSkeleton raw;
    for (int i = 0; i < n; ++i) {
        RawJoint j;
        j.name = "j" + std::to_string(i);
        j.parent = i - 1;
        j.translation = i == 0 ? glm::vec3(0.0f) : glm::vec3(0.0f, 0.1f, 0.0f);
        raw.joints.push_back(j);
    }
    return raw;
}

/// A 64-joint humanoid-like tree: spine of 6, head 2, two arms of 14 (shoulder..fingers), two legs
/// of 6, and 16 leaf joints spread over hands/feet. Parents precede children in file order.
inline RawSkeleton make_humanoid64() {
    RawSkeleton raw;
    auto add = [&](int parent, glm::vec3 offset) {
        RawJoint j;
        j.name = "joint" + std::to_string(raw.joints.size());
        j.parent = parent;
        j.translation = offset;
        raw.joints.push_back(j);
        return static_cast<int>(raw.joints.size()) - 1;
    };
    int spine = add(-1, glm::vec3(0.0f, 1.0f, 0.0f));
    const int pelvis = spine;
    for (int i = 0; i < 5; ++i) spine = add(spine, glm::vec3(0.0f, 0.1f, 0.0f));
    int head = add(spine, glm::vec3(0.0f, 0.1f, 0.0f));
    add(head, glm::vec3(0.0f, 0.1f, 0.0f));
    for (int side = -1; side <= 1; side += 2) {
        int a = spine;
        for (int i = 0; i < 14; ++i) a = add(a, glm::vec3(0.08f * static_cast<float>(side), 0.0f, 0.0f));
        int l = pelvis;
        for (int i = 0; i < 6; ++i) l = add(l, glm::vec3(0.05f * static_cast<float>(side), -0.15f, 0.0f));
        for (int i = 0; i < 8; ++i) add(i < 4 ? a : l, glm::vec3(0.0f, 0.0f, 0.02f));
    }
    return raw;
}

/// A clip over `skeleton` with `keys` uniform keys over `duration` seconds animating translation,
/// rotation and scale of every joint with smooth, joint-dependent curves.
inline RawAnimation make_wave_clip(const Skeleton& skeleton, int keys, float duration) {
    RawAnimation anim;
    anim.name = "wave";
    anim.duration = duration;
    const int n = skeleton.joint_count();
    anim.tracks.resize(static_cast<size_t>(n));
    for (int j = 0; j < n; ++j) {
        RawJointTracks& tr = anim.tracks[static_cast<size_t>(j)];
        for (int k = 0; k < keys; ++k) {
            const float t = duration * static_cast<float>(k) / static_cast<float>(keys - 1);
            const float ph = 6.2831853f * t / duration + 0.3f * static_cast<float>(j);
            tr.translations.times.push_back(t);
            tr.translations.values.push_back(skeleton.rest_translations()[static_cast<size_t>(j)] +
                                             glm::vec3(0.01f * std::sin(ph), 0.0f, 0.01f * std::cos(ph)));
            tr.rotations.times.push_back(t);
            tr.rotations.values.push_back(glm::angleAxis(0.5f * std::sin(ph), glm::normalize(glm::vec3(1.0f, 0.3f, 0.2f))));
            tr.scales.times.push_back(t);
            tr.scales.values.push_back(glm::vec3(1.0f + 0.01f * std::sin(ph)));
        }
    }
    return anim;
}

}  // namespace aloha::test
