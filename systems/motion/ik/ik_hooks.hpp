// Reach and look-at for the motion controller: MethodSlot::Reach and MethodSlot::LookAt hooks that
// build a chain from the request's effector, move the world target into the character's model
// space, run the solver the animation LOD asks for (CCD or DLS, its iteration cap and tolerance),
// warm-start from the previous frame's solution and ramp the result in over the request's
// cross-fade time so a reach does not pop.
#pragma once

#include "systems/motion/controller.hpp"
#include "systems/motion/ik/ik_types.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace aloha {

/// Chain length for an effector named `effector` (an optional "mixamorig:" prefix is ignored):
/// the chain is the effector and its `length - 1` nearest ancestors.
struct IkChainRule {
    std::string effector;  ///< joint name
    int length = 3;        ///< joints in the chain, effector included (1..kMaxIkChain)
};

/// Built-in reach rules: CMU BVH (LeftWrist -> LeftShoulder 3, lhand 4, LeftAnkle -> LeftHip 3,
/// LeftToe 4, and right), Mixamo/HumanIK (LeftHand 3, LeftFoot 3) and Unreal (hand_l 3, foot_l 3).
[[nodiscard]] const std::vector<IkChainRule>& default_ik_chain_rules();

/// Per-character IK state kept across frames by the hooks.
struct IkCharacterState {
    std::array<glm::quat, kMaxIkChain> base{};      ///< chain local rotations when the request started
    std::array<glm::quat, kMaxIkChain> solution{};  ///< last IK solution of the chain (warm start)
    int16_t effector = -1;                          ///< effector of the chain held (-1 = none)
    uint8_t length = 0;                             ///< joints in the chain held
    uint8_t has_base = 0;                           ///< base captured for the current request
    uint8_t warm = 0;                               ///< solution holds a previous solve
    uint32_t stalls = 0;                            ///< local minima escaped (chain swivelled)
    IkResult last;                                  ///< result of the last solve
};

/// Settings and state of the reach/look-at hooks. Must outlive the controller it is registered
/// with; tables are filled by register_ik_hooks (change settings before registering).
struct IkHookContext {
    std::vector<IkChainRule> rules = default_ik_chain_rules();  ///< reach chain lengths by effector name
    int reach_fallback_length = 3;        ///< reach chain length for effectors not in `rules`
    int look_fallback_length = 2;         ///< look-at chain length when the effector has no neck ancestors
    glm::vec3 look_axis{0.0f, 0.0f, 1.0f};///< forward axis of the look-at effector in its joint frame
    float look_orientation_weight = 1.0f; ///< metres per radian in E for look-at (tolerance / weight = angle bound)
    float damping = 0.05f;                ///< DLS damping (metres)

    // Filled by register_ik_hooks.
    const Skeleton* skeleton = nullptr;   ///< the controller's skeleton
    std::vector<int16_t> reach_base;      ///< per joint: base of the reach chain ending there
    std::vector<int16_t> look_base;       ///< per joint: base of the look-at chain ending there
    int default_reach_effector = -1;      ///< effector when MotionRequest::effector < 0 (right wrist/hand)
    int default_look_effector = -1;       ///< effector when MotionRequest::effector < 0 (head)
    std::vector<IkCharacterState> characters;  ///< per character (controller capacity): reach / look-at requests
    std::vector<IkCharacterState> overlays;    ///< per character: the overlay (MotionController::set_overlay); `last` is its status
};

/// Builds the chain tables of `context` for `controller`'s skeleton, sizes its per-character
/// state and registers the Reach and LookAt hooks (with release callbacks that drop the warm
/// start). Reach: the effector's position (and orientation when MotionRequest::use_orientation)
/// goes to the world target. LookAt: the effector's look_axis points at the world target.
/// IkSolver::None holds the base pose.
void register_ik_hooks(MotionController& controller, IkHookContext& context);

/// Base joint of the chain ending at `effector` (reach: rule table then fallback; look-at: the
/// effector plus its ancestors named *neck* / *head*, else the fallback). Skips the skeleton root
/// unless the effector is the root. Returns -1 for an out-of-range effector.
[[nodiscard]] int ik_chain_base(const Skeleton& skeleton, const IkHookContext& context, int effector, bool look_at);

}  // namespace aloha
