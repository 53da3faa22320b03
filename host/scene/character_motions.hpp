// A character type's motion files (CharacterTypeDesc::motions): each file's skeleton mapped and normalised as a
// character's would be, its clips retargeted onto the type's skeleton (systems/motion/library/retarget.hpp) and
// added to the type's clips as "<prefix>.<name>".
#pragma once

#include "engine/core/result.hpp"
#include "host/scene/character_type.hpp"

namespace aloha {

/// Adds the clips of desc.motions to `type` (loaded, with its humanoid map). Errors name the scene file and
/// the motion's JSON pointer (a type that is no mapped humanoid, a glTF animation not found, a clip name already
/// used) or the motion file (what its loaders and mapping refuse, a skeleton that is no humanoid).
Status add_motion_files(CharacterType& type, const CharacterTypeDesc& desc);

}  // namespace aloha
