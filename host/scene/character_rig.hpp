// A character file's skeleton made ready for the layers: mapped to the canonical humanoid,
// normalised (axes, units, rest frames: engine/assets/rig_normalise.hpp), and given the canonical
// humanoid's joint limits, muscle layout and walk rig through the map.
#pragma once

#include "engine/anim/humanoid_map.hpp"
#include "engine/assets/rig_normalise.hpp"
#include "host/scene/character_type.hpp"

#include <string>

namespace aloha {

/// A file skeleton after mapping and normalisation.
struct NormalisedRig {
    Skeleton skeleton;       ///< normalised (same joint order and names as the file's runtime skeleton)
    HumanoidMap map;         ///< canonical joints in it
    RigFrame frame;          ///< axes and units found or given
    RigNormalisation change; ///< what was done to the file's skeleton (apply to clips and meshes)
};

/// Maps `original` (the file's runtime skeleton) with the file's `declared` humanoid (VRM) and
/// desc.humanoid_map over it, detects its frame (desc.scale overrides the units) and normalises it.
/// Errors name the file or, for the explicit map, the scene file and JSON pointer.
Result<NormalisedRig> normalise_file_rig(const Skeleton& original, const CharacterTypeDesc& desc, RigFormat format,
                                         const std::string& file, const DeclaredHumanoid& declared = {});

/// A BVH file's skeleton and motion, both normalised.
struct NormalisedBvh {
    NormalisedRig rig;               ///< the skeleton mapped and normalised
    RawAnimation clip;               ///< the file's motion on rig.skeleton (named as the loader names it)
    std::vector<std::string> notes;  ///< the BVH loader's notes
};

/// Loads the BVH at `file` in its own units (detected from the skeleton's height unless desc.scale gives them),
/// maps and normalises its skeleton (normalise_file_rig with `desc`) and its motion to match. Errors name the file
/// or, for the explicit map, the scene file and JSON pointer.
Result<NormalisedBvh> load_normalised_bvh(const std::string& file, const CharacterTypeDesc& desc);

/// Moves a mesh skinned to the file's skeleton onto the normalised one: v' = G v, n' = A n,
/// inverse bind C_j^-1 IB_j G^-1.
void normalise_mesh(CharacterMesh& mesh, const RigNormalisation& change);

/// Gives a mapped humanoid type (type.map.humanoid, normalised skeleton) the canonical layers:
/// joint limits (desc.limits, else the built-in humanoid's) on the joints whose rest bone agrees
/// with the reference's, the muscle layout (desc.muscles, else the built-in one unless the type
/// has a mesh to fit muscles to) retargeted to the skeleton, and notes for what was skipped.
/// Requires desc.canonical (the built-in humanoid definition). Errors name the file at fault.
Status add_canonical_layers(CharacterType& type, const CharacterTypeDesc& desc, const std::string& file);

}  // namespace aloha
