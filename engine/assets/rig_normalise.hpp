// Rig normalisation, once at load: whatever a file's up and forward axes, units and joint rest
// frames, the skeleton the systems see stands +Y up, faces +Z with its left on +X, is measured in
// metres and has identity rest rotations and unit rest scales (every joint frame parallel to the
// model axes at rest, as in BVH and the built-in humanoid), so muscle layouts, joint limits, the
// walk rig and IK written for the canonical humanoid apply to it.
//
// The change is exact: new model matrix M'_j = G * M_j * C_j with G = units * axes (a similarity)
// and C_j a constant per-joint correction, so clips, skinned meshes (v' = G v, inverse bind
// C_j^-1 * IB_j * G^-1) and everything in model space follow. Rest scales are assumed uniform;
// a non-uniform one is replaced by its cube-root mean with a note.
#pragma once

#include "engine/anim/humanoid_map.hpp"
#include "engine/anim/raw_animation.hpp"
#include "engine/anim/raw_skeleton.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

namespace aloha {

/// Where a rig's file format puts its units.
enum class RigFormat : uint8_t { Bvh, Gltf };

/// Axes and units of a file's skeleton, found by detect_rig_frame or given.
struct RigFrame {
    glm::quat axes{1, 0, 0, 0};  ///< rotation from the file's model axes to +X left, +Y up, +Z forward
    float metres_per_unit = 1.0f;///< file length unit in metres
    std::string units;           ///< name of the unit ("metres", "centimetres", ..., "scale 0.01 (given)")
    std::string up;              ///< the file's up axis in words ("+Y", "+Z", ...), "" when not detected
    std::string forward;         ///< the file's forward axis in words, "" when not detected
    float height = 0.0f;         ///< standing height after normalisation (m), 0 when not a humanoid
    std::vector<std::string> notes;  ///< what was assumed
};

/// Finds the axes and units of `skeleton`. A humanoid (`map.humanoid`) is measured: up from the
/// ankles to the head, left from the right hip to the left (shoulders when the hips coincide),
/// each snapped to the nearest file axis within 30 degrees; units the first of the format's
/// candidates (glTF: metres, centimetres, millimetres; BVH also inches and CMU units of 0.056444 m)
/// giving a standing height in [0.9, 2.6] m, the one nearest 1.7 m when several do. Any other
/// skeleton keeps its axes; a glTF is in metres, a BVH in the first unit making its size
/// 0.2-5 m (noted). `scale` > 0 overrides the units (a result outside 0.3-5 m is noted).
/// Errors (naming `source`): no plausible unit, so the character would be silently giant or tiny.
Result<RigFrame> detect_rig_frame(const Skeleton& skeleton, const HumanoidMap& map, RigFormat format, float scale,
                                  const std::string& source);

/// The normalised skeleton and the per-joint corrections (runtime joint order is kept).
struct RigNormalisation {
    RawSkeleton skeleton;               ///< runtime order, identity rest rotations, unit scales, metres
    std::vector<glm::quat> rest_model;  ///< file rest model rotation R_j per joint
    std::vector<float> rest_scale;      ///< file rest model uniform scale s_j per joint
    glm::quat axes{1, 0, 0, 0};         ///< A
    float metres_per_unit = 1.0f;       ///< u
    std::vector<std::string> notes;     ///< non-uniform rest scales replaced

    /// G = u * A.
    [[nodiscard]] glm::mat4 global() const;
    /// C_j = (u s_j)^-1 * (A R_j)^-1 as a matrix.
    [[nodiscard]] glm::mat4 correction(int joint) const;
};

/// Normalises `skeleton` for `frame` (see the file comment).
[[nodiscard]] RigNormalisation normalise_rig(const Skeleton& skeleton, const RigFrame& frame);

/// Rewrites `clip` (tracks by runtime joint of the skeleton normalised into `n`) for the
/// normalised skeleton: rotations (A R_p) q (A R_j)^-1, translations u s_p A R_p t, scales over the
/// rest scale. Requires clip.tracks.size() == joint count (or empty tracks).
void normalise_clip(RawAnimation& clip, const Skeleton& original, const RigNormalisation& n);

}  // namespace aloha
