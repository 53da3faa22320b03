// A character type at run time: skeleton (BVH or glTF), joint limits, clips, walk rig, muscle layout,
// optional skinned mesh. Loaded once per scene from a CharacterTypeDesc; shared by all its characters.
#pragma once

#include "engine/anim/humanoid_map.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/assets/rig_normalise.hpp"
#include "engine/assets/surface_material.hpp"
#include "engine/core/result.hpp"
#include "host/scene/scene_desc.hpp"
#include "systems/geometry/controller/character_geometry.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/walk_rig.hpp"

#include <optional>
#include <string>
#include <vector>

namespace aloha {

/// Everything the systems need about one kind of character. Immutable after load.
struct CharacterType {
    std::string name;
    Skeleton skeleton;
    ClipLibrary clips;
    int mocap_clip = -1;            ///< the file's own motion ("<name>.mocap"), -1 when none
    int inplace_clip = -1;          ///< the same with horizontal root travel removed ("<name>.inplace")
    int idle_clip = -1;             ///< what idlers play and characters stand in: a file clip named like "Idle", else the
                                    ///< generated idle ("<prefix>.idle"), -1 when neither
    std::vector<ClipId> gait_clips; ///< the walk's clips: generated walk/run cycles slowest first, or the type's own
                                    ///< loops first (the impostors bake the first) and generated ones beyond their speeds
    std::optional<WalkRig> rig;     ///< leg rig for kinematic walking (none when legs are not found)
    MuscleSet muscles;
    std::optional<CharacterMesh> mesh;  ///< glTF skin, when the type has one
    std::vector<SurfaceMaterial> materials; ///< indexed by the mesh's vertex_material (the generated body's
                                            ///< one material for a type without a mesh)
    std::vector<TextureImage> textures;     ///< indexed by SurfaceMaterial::texture
    float height = 1.8f;            ///< standing height (m), for bounds
    float radius = 0.4f;            ///< horizontal radius (m), for bounds: the rest joints at load, widened
                                    ///< to every clip pose and the skin by CharacterRuntime::measure_bounds
    std::vector<std::string> notes; ///< what was skipped or assumed while loading
    HumanoidMap map;                ///< canonical humanoid joints in `skeleton` (map.humanoid: all required found)
    RigFrame frame;                 ///< axes and units the file was found in (or given)
};

/// Loads a character type. BVH and glTF skeletons are mapped to the canonical humanoid and
/// normalised (axes, units, rest frames); a mapped humanoid gets the canonical joint limits, muscle
/// layout (or muscles fitted to its mesh) and walk rig; a non-humanoid gets no muscles unless the
/// type names a layout (its mesh and rigid proxies only, noted). Errors name the file and the problem.
Result<CharacterType> load_character_type(const CharacterTypeDesc& desc);

/// Id of clip `name` in `type` ("" = the type's idle clip, else its in-place mocap clip), or -1.
int find_clip(const CharacterType& type, const std::string& name);

}  // namespace aloha
