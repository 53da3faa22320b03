// Dynamic walk (top animation LOD): rigid links held together by point constraints whose forces
// are solved each step in the manner of Barzel & Barr, so the constraint error C obeys
// C'' + 2wC' + w^2 C = 0 (critical damping). Joints are driven toward the kinematic gait's local
// rotations by PD motors; feet touch the ground y = 0 with Coulomb friction; a balance aid holds
// the pelvis. Everything stiff (constraints, motors, contacts, balance aid) is solved implicitly
// in one linear system per substep, so 1/60 s frames are stable.
#pragma once

#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// A point that may touch the ground, fixed to a joint: `offset` in that joint's frame (metres).
struct DynamicContactPoint {
    int joint = 0;                    ///< skeleton joint the point moves with
    glm::vec3 offset{0.0f};           ///< point in the joint's frame
};

/// Tunables of the dynamic walk (defaults are for a ~1.7 m human in metres, kg, seconds).
struct DynamicWalkSettings {
    int substeps = 2;                        ///< solver substeps per step (h = dt / substeps)
    float constraint_frequency = 50.0f;      ///< w of C'' + 2wC' + w^2C = 0 (rad/s); keep w*h <= 0.5
    float motor_frequency = 40.0f;           ///< PD motor natural frequency (rad/s), gains scale with subtree inertia
    float motor_damping_ratio = 1.0f;        ///< PD motor damping ratio
    /// With contact_points: the leg joints' motors add this share of the rest of the body's inertia about
    /// them to their subtree's, so stance legs carry the body (not a foot whose sole points span under a
    /// tenth of its distance to the pelvis). 0: subtree only; 0.3 and up lost balance
    /// at 1.0-1.4 m/s (docs/PERFORMANCE.md 'Dynamic walker's skate').
    float stance_gain = 0.15f;
    float balance_frequency = 8.0f;          ///< balance aid natural frequency (rad/s) on pelvis position/orientation
    float balance_damping_ratio = 1.0f;      ///< balance aid damping ratio
    float friction = 0.9f;                   ///< Coulomb friction coefficient of feet on the ground
    float min_bone_length = 0.02f;           ///< joints closer than this to their parent are merged (welded)
    float density = 1000.0f;                 ///< kg/m^3 of the capsule links
    float contact_height = 0.12f;            ///< without contact_points: joints this close to the lowest start joint touch the ground
    /// The joint simulated as the root body (the pelvis); -1: the skeleton's root. Joints outside its
    /// subtree (an Unreal "root" joint on the ground and the IK helpers under it) are not simulated: they
    /// take the target's local rotations and translations (step_dynamic_walk), and the root body hangs
    /// under them wherever the simulation puts it.
    int root_joint = -1;
    /// The feet's sole points (dynamic_sole_contacts: heel and ball under the ankle and toe, toe tip),
    /// so the simulated feet stand on the ground where the kinematic gait puts its soles. Empty: the
    /// joints near the lowest start-pose joint (which stand the body lower than the gait by the sole's
    /// depth below those joints, and depend on the pose the walk starts from).
    std::vector<DynamicContactPoint> contact_points;
};

/// One rigid link (a joint that owns a body plus the zero-length/leaf joints welded to it).
struct DynamicBody {
    int joint = 0;                    ///< owning skeleton joint; the body frame is that joint's frame
    int parent = -1;                  ///< parent body index, -1 for the root (pelvis)
    float mass = 1.0f;                ///< kg
    glm::mat3 inv_inertia{1.0f};      ///< inverse inertia about the COM in the body frame
    glm::vec3 com{0.0f};              ///< COM in the body frame (relative to the joint)
    glm::vec3 anchor{0.0f};           ///< this body's joint position in the parent body frame
    float motor_k = 0.0f;             ///< motor stiffness (N m / rad)
    float motor_c = 0.0f;             ///< motor damping (N m s / rad)
    glm::vec3 x{0.0f};                ///< COM position (world)
    glm::vec3 v{0.0f};                ///< COM velocity (world)
    glm::quat q{1.0f, 0.0f, 0.0f, 0.0f}; ///< orientation of the joint frame (world)
    glm::vec3 w{0.0f};                ///< angular velocity (world)
};

/// A body-fixed point that may touch the ground.
struct DynamicContact {
    int body = 0;                     ///< body index
    glm::vec3 local{0.0f};            ///< point in the body frame (relative to the joint)
};

/// Per-character simulation state; lives across frames (keep it in a component pool/context).
/// init_dynamic_walk sizes every buffer, so step_dynamic_walk allocates nothing.
struct DynamicWalkState {
    DynamicWalkSettings settings;
    std::vector<DynamicBody> bodies;
    std::vector<DynamicContact> contacts;
    std::vector<int> owner;                  ///< per joint: index of the body it belongs to, -1 outside the simulated subtree
    int root_joint = 0;                      ///< the joint of bodies[0] (settings.root_joint resolved)
    std::vector<glm::quat> welded_local;     ///< per joint: local rotation used when welded (start pose)
    std::vector<glm::vec3> translations;     ///< per joint: local translations for the output pose
    std::vector<glm::vec3> scales;           ///< per joint: local scales for the output pose
    glm::mat4 root_world{1.0f};              ///< character frame (world); targets are in this frame
    glm::vec3 prev_target_root{0.0f};        ///< last step's root target (for its velocity)
    bool has_prev_target = false;
    glm::vec3 pelvis_force{0.0f};            ///< external force on the pelvis link (N, world), applied every substep
    float total_mass = 0.0f;                 ///< kg
    float balance_inertia = 0.0f;            ///< composite inertia about the pelvis (kg m^2)
    // Solver scratch, sized at init.
    std::vector<glm::quat> target_world;     ///< per joint
    std::vector<glm::mat3> world_inv_inertia;///< per body
    std::vector<float> row_data;             ///< per row: 14 floats (two body Jacobian halves, rhs, gamma)
    std::vector<float> row_mj;               ///< per row: 12 floats, M^-1 J^T for both bodies
    std::vector<int> row_info;               ///< per row: body0, body1, kind, friction normal row
    std::vector<double> matrix;              ///< dense system
    std::vector<double> work;                ///< Schur complement / right-hand sides
    std::vector<double> lambda;              ///< impulses
    std::vector<glm::vec3> shift_position;   ///< per body: post-stabilisation displacement of the COM
    std::vector<glm::vec3> shift_rotation;   ///< per body: post-stabilisation rotation (world rotation vector)
    size_t last_rows = 0;                    ///< rows of the last substep (bilateral first, then 3 per touching contact)
    size_t last_bilateral = 0;               ///< bilateral rows of the last substep
    uint32_t failed_factorisations = 0;      ///< substeps whose constraint matrix was not positive definite (no impulses applied)
};

/// Builds the bodies from `start_pose` (valid local pose and model matrices) placed in the world
/// by `root_world` (rigid). Errors name the problem (pose size, non-finite values, no links).
Status init_dynamic_walk(const Skeleton& skeleton, ConstPoseView start_pose, const glm::mat4& root_world,
                         DynamicWalkState& state, const DynamicWalkSettings& settings = {});

/// Advances the simulation by dt toward the kinematic target (local rotations per joint and the
/// position of the root body's joint, state.root_joint, both in the character frame) and writes the simulated pose
/// (translations, rotations, scales, model matrices in the character frame). `out_root_world`
/// (optional) receives the character frame, which stays where init placed it. A substep whose
/// constraint matrix cannot be factorised applies no impulses and counts in
/// state.failed_factorisations (the divergence guard hands such a character back).
/// `target_local_translations` (empty, or one per joint): the target's local translations, which the joints
/// outside the simulated subtree take (an Unreal "root" carrying root motion); empty: their start-pose ones.
/// Requires init_dynamic_walk on the same skeleton, spans of the joint count, dt > 0.
void step_dynamic_walk(const Skeleton& skeleton, std::span<const glm::quat> target_local_rotations,
                       const glm::vec3& target_root_position, float dt, DynamicWalkState& state, PoseView out_pose,
                       glm::mat4* out_root_world, std::span<const glm::vec3> target_local_translations = {});

/// Largest separation (metres) between the two sides of any point constraint (the drift).
[[nodiscard]] float max_constraint_error(const DynamicWalkState& state);

/// World position of a body's joint.
[[nodiscard]] glm::vec3 body_joint_position(const DynamicBody& body);

}  // namespace aloha
