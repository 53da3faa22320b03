// Test helper: the project's own humanoid (data/characters/humanoid.json) built for a body, with
// its leg rig standing on the rest ground. Fails the calling test on any load error.
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "systems/motion/walk_rig.hpp"

#include <gtest/gtest.h>

#include <string>

namespace aloha::test {

/// Path of the shipped humanoid definition in the source tree.
inline std::string humanoid_definition_path() { return std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid.json"; }

/// The humanoid skeleton for `body` (empty skeleton and a test failure when loading fails).
inline Skeleton humanoid_skeleton_for(const HumanoidBody& body = {}) {
    auto def = load_humanoid_definition(humanoid_definition_path());
    EXPECT_TRUE(def.ok()) << (def.ok() ? "" : def.error().to_string());
    if (!def.ok()) return {};
    auto s = build_skeleton(humanoid_skeleton(def.value(), body), "humanoid.json");
    EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().to_string());
    return s.ok() ? std::move(s.value()) : Skeleton{};
}

/// Its leg rig, ankles measured from the ground the rest pose stands on.
inline WalkRig humanoid_rig(const Skeleton& skeleton) {
    auto rig = resolve_walk_rig(skeleton, "humanoid.json");
    EXPECT_TRUE(rig.ok()) << (rig.ok() ? "" : rig.error().to_string());
    if (!rig.ok()) return {};
    stand_rig_on_rest_ground(rig.value(), skeleton);
    return rig.value();
}

}  // namespace aloha::test
