// Plain data for the level-of-detail pipeline: attributes -> request -> resolved state.
#pragma once

#include <cstddef>
#include <cstdint>

namespace aloha {

/// Per-character attributes the knowledge base tests (written by the lod_attributes system).
struct LodAttributes {
    float distance = 0.0f;            ///< metres from the camera to the character's centre
    float projected_height_px = 0.0f; ///< on-screen height in pixels (0 when behind the camera)
    float eccentricity = 0.0f;        ///< 0 at the view centre, 1 at the frustum edge (>1 outside)
    float speed = 0.0f;               ///< m/s
    float importance = 0.0f;          ///< copied from Importance
    uint8_t visible = 0;              ///< 1 when the bounds intersect the view frustum
    float occluded = 0.0f;            ///< 1: certainly hidden by nearer characters; below 1 (at most 0.99): the
                                      ///< estimated share of the body behind them (systems/lod/occlusion.hpp)
};

/// Bits of GeomLod::layers: which of the four layers are simulated/drawn.
enum LayerBits : uint8_t {
    kLayerSkeleton = 1u << 0,
    kLayerMuscle = 1u << 1,
    kLayerFat = 1u << 2,
    kLayerSkin = 1u << 3,
};

/// How the body surface is produced at a geometric level (from cheapest to richest).
enum class GeomMethod : uint8_t {
    Hidden = 0,       ///< not drawn (culled)
    RigidProxy = 1,   ///< one rigid box/capsule per bone
    SkinnedMesh = 2,  ///< linear-blend-skinned skin, no muscles or springs (layers peeled)
    Layered = 3,      ///< skeleton + muscles + fat springs + skin from spring ends
    Subdivided = 4,   ///< Layered, then OpenSubdiv Catmull-Clark refinement of the skin
    Impostor = 5,     ///< a camera-facing quad from the type's pre-rendered atlas (views x walk phases):
                      ///< no per-character geometry; cheaper to draw than RigidProxy (out of the cost order
                      ///< so that the values above keep their meaning)
};

/// Geometric LOD parameters marshalled to the geometric controller.
struct GeomLod {
    uint8_t level = 0;           ///< 0 = richest; index into the rule file's geometric levels
    GeomMethod method = GeomMethod::RigidProxy;
    uint8_t layers = kLayerSkeleton;
    uint8_t subdiv_level = 0;    ///< Catmull-Clark levels when method == Subdivided
    uint16_t theta_steps = 8;    ///< super-ellipsoid steps around (theta), the one tessellation parameter
    uint16_t phi_steps = 6;      ///< steps from pole to pole (phi)
    float geomorph_s = 0.0f;     ///< seconds to morph from the previous surface when this level is entered
    float simplify_error = 0.0f; ///< SkinnedMesh: triangle list simplified within this fraction of the height (0: not)
    /// SkinnedMesh standing in for a layered or subdivided level (a character type without muscles): lit per
    /// pixel as the level it stands in for, so close characters keep their normal maps and smooth light.
    bool lit_per_pixel = false;
};

/// How cyclic locomotion is produced at an animation level (from cheapest to richest).
enum class WalkMethod : uint8_t {
    ClipPlayback = 0, ///< motion-capture clip, forward kinematics only
    Kinematic = 1,    ///< procedural/interpolated cycle with planted feet
    Dynamic = 2,      ///< constraint-based rigid-body simulation tracking the kinematic gait
};

/// Inverse-kinematics solver choice.
enum class IkSolver : uint8_t { None = 0, Ccd = 1, Dls = 2 };

/// Kinds of animation work whose cost the animation budget learns apart at each level: a character
/// that is not walking (clip, reach, look-at: no walk method runs; cost class 0) and one that walks.
inline constexpr size_t kAnimCostClasses = 2;
/// Index of (animation `level`, `walking`) in arrays kept per level and cost class.
constexpr size_t anim_cost_slot(size_t level, bool walking) { return level * kAnimCostClasses + (walking ? 1 : 0); }

/// Animation LOD parameters marshalled to the motion controller.
struct AnimLod {
    uint8_t level = 0;            ///< 0 = richest
    WalkMethod walk = WalkMethod::ClipPlayback;
    IkSolver ik = IkSolver::Ccd;
    uint8_t ik_iterations = 4;
    uint8_t update_interval = 1;  ///< animate every N frames (time still advances every frame)
    float ik_tolerance = 1e-3f;   ///< metres
    float crossfade_s = 0.0f;     ///< seconds to cross-fade poses when the method changes
};

/// What the knowledge base wants for a character this frame (written by the rules system).
struct LodRequest {
    uint8_t geom_level = 0;
    uint8_t anim_level = 0;
    uint16_t rule_id = 0;          ///< index of the rule that fired
};

/// Resolver state that lives across frames: current levels, hysteresis timers, transitions.
struct LodState {
    uint8_t geom_level = 0;
    uint8_t anim_level = 0;
    uint8_t prev_geom_level = 0;    ///< level being morphed from while geomorph_left_s > 0
    uint8_t prev_anim_level = 0;    ///< level being cross-faded from while crossfade_left_s > 0
    float seconds_at_geom = 0.0f;   ///< simulated seconds since the last geometric switch (0 on the switch frame)
    float seconds_at_anim = 0.0f;   ///< simulated seconds since the last animation switch (0 on the switch frame)
    float geomorph_left_s = 0.0f;   ///< seconds of geomorph remaining
    float crossfade_left_s = 0.0f;  ///< seconds of pose cross-fade remaining
    uint16_t rule_id = 0;           ///< rule that produced the current levels
    uint8_t budget_demotion = 0;    ///< geometric levels removed by the frame budget (0 = none)
    uint8_t anim_demotion = 0;      ///< animation levels removed by the frame budget (0 = none)
    uint8_t cap_geom_level = 0;     ///< richest geometric level the level caps allow this frame (0 = any)
    uint8_t cap_anim_level = 0;     ///< richest animation level the level caps allow this frame (0 = any)
    uint8_t always_full = 0;        ///< 1: set by the scene; the frame budget never demotes this character
    uint8_t geom_wanted = 0;        ///< geometric level the rules (after demotion and caps) asked for last frame
    float seconds_geom_wanted = 0.0f;  ///< simulated seconds geom_wanted has been asked for without a break
};

}  // namespace aloha
