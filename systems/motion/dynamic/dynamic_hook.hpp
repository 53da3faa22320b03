// Dynamic walk for the motion controller: the MethodSlot::DynamicWalk hook. Each character whose
// AnimLod::walk is Dynamic gets a DynamicWalkState (initialised from its pose when it enters the
// method, freed when it leaves) that is stepped toward the kinematic gait pose the controller
// computed (local rotations + root), and the simulated pose replaces the kinematic one.
#pragma once

#include "systems/motion/controller.hpp"
#include "systems/motion/dynamic/dynamic_walk.hpp"

#include <cstdint>
#include <vector>

namespace aloha {

/// One character's simulation slot.
struct DynamicCharacter {
    DynamicWalkState state;              ///< the simulation (buffers sized at initialisation)
    std::vector<glm::quat> target;       ///< scratch: target local rotations (joint count)
    uint8_t initialised = 0;             ///< 1 while the character is simulated
    uint8_t failed = 0;                  ///< 1 when initialisation failed (the kinematic pose is kept)
    uint32_t steps = 0;                  ///< simulation steps taken since initialisation
    glm::vec3 push_force{0.0f};          ///< force (N, world) of a push on the pelvis under way
    float push_left = 0.0f;              ///< seconds the push still lasts
    uint8_t diverged = 0;                ///< 1 once the divergence guard handed the character back to kinematic walking
    float fallback_elapsed = 0.0f;       ///< seconds since the hand-back (the offset decays over DynamicHookContext::fallback_seconds)
    std::vector<glm::quat> shown_rotations;     ///< local rotations of the last simulated pose shown (joint count)
    std::vector<glm::vec3> shown_translations;  ///< local translations of the last simulated pose shown
    std::vector<glm::quat> offset_rotations;    ///< after a hand-back: shown * inverse(kinematic) per joint
    std::vector<glm::vec3> offset_translations; ///< after a hand-back: shown - kinematic per joint
    std::vector<glm::vec3> kinematic_translations;  ///< scratch: the kinematic pose's translations before a step
};

/// Divergence guard of the dynamic walk (a safety net, not part of the simulation): after every step
/// the simulated pose is checked, and a character whose simulation has come apart is handed back to
/// the kinematic walk it was tracking, with the pose it showed last inertialized into it.
struct DynamicGuard {
    float max_joint_gap = 0.02f;     ///< m: a point constraint pulled further apart than this (a healthy step keeps it under 1 mm)
    float max_pelvis_tilt = 0.7854f; ///< rad: pelvis orientation further than this from the gait's (45 degrees)
    float max_body_speed = 12.0f;    ///< m/s: any link faster than this (a swing foot at a brisk walk moves about 5 m/s)
};

/// True when `state` has come apart against the guard's bounds: a non-finite value, a joint gap, a
/// pelvis tilted from `pelvis_target` (world rotation of the gait's pelvis), a link too fast, or a
/// constraint matrix that could not be factorised (state.failed_factorisations).
[[nodiscard]] bool dynamic_walk_diverged(const DynamicWalkState& state, const glm::quat& pelvis_target,
                                         const DynamicGuard& guard);

/// Settings and per-character state of the dynamic walk hook. Must outlive the controller it is
/// registered with; change settings before registering.
struct DynamicHookContext {
    DynamicWalkSettings settings;        ///< passed to init_dynamic_walk
    float max_step = 1.0f / 60.0f;       ///< longest simulation step (s); longer posed intervals are split
    DynamicGuard guard;                  ///< bounds of the divergence guard
    float fallback_seconds = 0.2f;       ///< inertialization time of a hand-back to the kinematic walk
    std::vector<DynamicCharacter> characters;  ///< per character (controller capacity), filled by registration
    /// Number of characters simulated now.
    [[nodiscard]] size_t simulated() const;
    /// Number of characters the divergence guard handed back to the kinematic walk (while at the dynamic level).
    [[nodiscard]] size_t diverged() const;
};

/// Seconds over which push_dynamic_walker spreads its impulse (a shove, not a bullet: the joint
/// constraints carry it to the rest of the body).
inline constexpr float kDynamicPushSeconds = 0.1f;

/// Pushes the pelvis of a dynamically walking `character` with `impulse` (N s, world), as a constant
/// force over the next kDynamicPushSeconds of simulation; the simulation absorbs it and the balance aid (a critically damped spring on
/// the pelvis, DynamicWalkSettings::balance_frequency) brings it back to the gait's path. Returns false
/// (and does nothing) when the character is not simulated now: kinematic and clip walkers have no
/// body to push. Not during an update.
bool push_dynamic_walker(DynamicHookContext& context, uint32_t character, const glm::vec3& impulse);

/// Sole points of the feet of `rig` (per foot: heel and ball on the ground fixed to the ankle, the toes'
/// tip fixed to the toe joint when it has a child ahead of it), ground being rig.ankle_height below the
/// rest ankles: the points the kinematic gait stands on, for DynamicWalkSettings::contact_points.
[[nodiscard]] std::vector<DynamicContactPoint> dynamic_sole_contacts(const Skeleton& skeleton, const WalkRig& rig);

/// Sizes `context` for `controller` and registers the DynamicWalk hook and its release callback.
/// The controller then runs WalkMethod::Dynamic (it requires a walk rig: set_walk_rig) instead of
/// falling back to Kinematic. The simulation frame is the character's Transform without scale. Without
/// contact points in context.settings, the feet's sole points of the controller's walk rig (set it first)
/// become them.
void register_dynamic_walk_hook(MotionController& controller, DynamicHookContext& context);

}  // namespace aloha
