// The generated motion library on a character from a file: the gaits, idle, turn and wave the project makes for
// its own humanoid (systems/motion/library/motion_library.hpp), made for a built-in body as tall in the hips as the
// character and retargeted onto its skeleton (systems/motion/library/retarget.hpp). So a mapped humanoid brought
// without motion (a glTF character in its bind pose, a BVH rig with one take) walks at any speed, idles, turns
// and waves like the built-in humanoid, arms down whatever its rest pose (T, A).
#pragma once

#include "engine/core/result.hpp"
#include "host/scene/character_type.hpp"
#include "host/scene/scene_desc.hpp"

namespace aloha {

/// Adds the generated motion library to `type` (loaded from desc.bvh or desc.gltf, its clips and motion files in):
/// clips "<prefix>.walk_0.50" ... "<prefix>.run_3.00", "<prefix>.idle", "<prefix>.turn", "<prefix>.wave", made for
/// the built-in humanoid of desc.canonical at the type's rest hip height (its height clamped to [0.5, 2.5] m) and
/// retargeted onto type.skeleton. The gaits become the type's walk clips (type.gait_clips) when it has none (no loop
/// cut from its file or a motion file's `walk`); otherwise its own loops stay its walk for the speeds within a
/// quarter of theirs and the gaits beyond join them, after them (a file's walk alone would be warped to run); the
/// rest play by name (noted). The idle becomes type.idle_clip (what idlers play) when it has none. A generated
/// clip whose name the type already has is left out (noted). One note sums it up. Does nothing when
/// desc.generated_motion is false, the type is no mapped humanoid (type.map.humanoid) or desc.canonical is empty.
/// Errors: the built-in definition's (naming its file), a clip that does not retarget or build (naming the type's
/// file).
[[nodiscard]] Status add_generated_motion(CharacterType& type, const CharacterTypeDesc& desc);

}  // namespace aloha
