// One humanoid map: the project's canonical humanoid joints (the names of the built-in humanoid,
// data/characters/humanoid.json) and the alias tables that find them in a skeleton named in a
// common rig convention (CMU BVH, Mixamo/HumanIK, Unity Humanoid/VRM, VRoid, Unreal mannequin,
// Poser/DAZ, Blender Rigify), plus an explicit canonical -> file name map for anything else.
// Every layer that needs a body part (muscle layouts, joint limits, the walk rig, IK effectors)
// asks this map, never the file's names. docs/CHARACTERS.md lists the tables.
//
// Name matching ignores case and the separators '_', '.', '-' and ' ', drops a namespace prefix
// ("mixamorig:", "Armature|") and Rigify's "DEF-", and reads the side of a sided joint from any of
// Left/Right prefix or suffix, L/R with a separator before or after ("thigh.L", "L_Thigh",
// "J_Bip_L_Hand"), or a one-letter l/r prefix before a capital ("lThigh", "RHipJoint").
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// One joint of the canonical humanoid. Canonical joints are listed parents first.
struct CanonicalJoint {
    const char* name;   ///< canonical name (the built-in humanoid's joint name)
    int parent;         ///< canonical parent index, -1 for Hips
    bool required;      ///< a skeleton missing it is not a humanoid (no muscles, limits, walk or reach)
    int side;           ///< 0 left, 1 right, -1 centre
};

/// The 31 canonical joints: Hips; per side HipJoint, Hip (thigh), Knee, Ankle, Toe; lowerback,
/// Chest, Chest2, lowerneck, Neck, Head; per side Collar, Shoulder (upper arm), Elbow, Wrist,
/// hand, Fingers, Thumb.
[[nodiscard]] std::span<const CanonicalJoint> canonical_humanoid();

/// Index of the canonical joint `name` (exact, case-sensitive), or -1.
[[nodiscard]] int canonical_index(std::string_view name);

/// Where the canonical joints are in one skeleton.
struct HumanoidMap {
    std::string convention;              ///< naming convention matched ("" when none matched)
    std::vector<int> joint;              ///< per canonical joint: skeleton joint index or -1
    std::vector<bool> from_explicit;     ///< per canonical joint: set by the explicit humanoid_map
    std::vector<bool> from_declared;     ///< per canonical joint: set by the file's own declaration (VRM)
    std::vector<std::string> missing;    ///< required canonical joints not found
    bool humanoid = false;               ///< every required canonical joint is mapped

    /// Skeleton joint of canonical joint `canonical_name`, or -1 (unknown or unmapped).
    [[nodiscard]] int find(std::string_view canonical_name) const;
    /// Skeleton joint of canonical joint `c`, else of its nearest mapped canonical ancestor, or -1.
    [[nodiscard]] int fold(int c) const;
    /// Canonical index mapped to skeleton joint `j`, or -1.
    [[nodiscard]] int canonical_of(int j) const;
};

/// A humanoid map the character file itself declares (VRM's humanoid bones): canonical joint
/// name -> skeleton joint name. The loader guarantees canonical names, existing joints and one
/// canonical joint per skeleton joint.
struct DeclaredHumanoid {
    std::string origin;                          ///< who declared it, for reports ("VRM 1.0 humanoid")
    std::map<std::string, std::string> joints;   ///< canonical name -> joint name
};

/// Maps `skeleton` to the canonical humanoid: the convention matching most joints, then the file's
/// `declared` map, then the entries of `explicit_map` (canonical name -> skeleton joint name) on
/// top; a later layer's joint replaces an earlier layer's use of it. Errors (naming `source` and
/// `where` + "/<canonical name>"): an unknown canonical name, a file name that is not a joint, one
/// joint given for two canonical joints in `explicit_map`. A skeleton matching no convention gives
/// an empty map (not a humanoid), never an error; a declared entry naming no joint is skipped.
Result<HumanoidMap> map_humanoid(const Skeleton& skeleton, const std::map<std::string, std::string>& explicit_map = {},
                                 const std::string& source = "", const std::string& where = "",
                                 const DeclaredHumanoid& declared = {});

/// Canonical joint name of a humanoid bone named in Unity's / VRM's bone vocabulary ("hips",
/// "leftUpperLeg", "rightLowerArm", "leftMiddleProximal"; any case), or "" for bones the canonical
/// humanoid does not have (eyes, jaw, most finger bones). `vrm1` selects VRM 1.0's thumb names
/// (thumbMetacarpal is the thumb's first bone; in VRM 0.x and Unity it is thumbProximal).
[[nodiscard]] std::string canonical_of_humanoid_bone(std::string_view bone, bool vrm1);

/// Names of the skeleton joints no canonical joint maps to (carried along, ignored by the layers).
[[nodiscard]] std::vector<std::string> unmapped_joints(const Skeleton& skeleton, const HumanoidMap& map);

/// A joint named by a user (scene effectors): the canonical joint `name` if the map has it, else
/// the skeleton joint of that name, or -1.
[[nodiscard]] int find_joint(const Skeleton& skeleton, const HumanoidMap& map, std::string_view name);

/// The name-matching key of a joint name: namespace and "DEF-" prefix dropped, lower case,
/// separators removed ("mixamorig:Left_Up.Leg" -> "leftupleg").
[[nodiscard]] std::string joint_name_key(std::string_view name);

}  // namespace aloha
