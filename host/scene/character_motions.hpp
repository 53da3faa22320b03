// A character type's motion files (CharacterTypeDesc::motions): each file's skeleton mapped and normalised as a
// character's would be, its clips retargeted onto the type's skeleton (systems/motion/library/retarget.hpp) and
// added to the type's clips as "<prefix>.<name>".
#pragma once

#include "engine/core/result.hpp"
#include "host/scene/character_loops.hpp"
#include "host/scene/character_type.hpp"

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Adds the clips of desc.motions to `type` (loaded, with its humanoid map), each retargeted take also appended to
/// `takes` (named as its clip, with its file). Errors name the scene file and the motion's JSON pointer (a type that
/// is no mapped humanoid, a glTF animation not found, a clip name already used) or the motion file (what its loaders
/// and mapping refuse, a skeleton that is no humanoid).
Status add_motion_files(CharacterType& type, const CharacterTypeDesc& desc, std::vector<LoadedTake>& takes);

/// A take used as the type's walk: cut to its best loop (a walk of at least 0.5 m/s: library/loop_cut.hpp) and
/// added to type.gait_clips as "<type>.loop" (a second one "<type>.loop2", ...), with a note. An in-place take (no
/// travel of its own, as game packs ship walks) on a type with a walk rig gets root motion from its feet first
/// (library/foot_root_motion.hpp). A take that does not loop is left out of walking with a note (the type then
/// walks as it did) and the error says why; `file` names the take's file in both.
Status add_walk_loop(CharacterType& type, const RawAnimation& take, const std::string& file);

/// Each of `takes` tried as the type's walk (add_walk_loop): a file's animations, any of which may be a walk or a run
/// (those that loop as walks forward are added; a take travelling more than 45 degrees off the body's facing, a
/// backward walk or a strafe, is none). One note when none does, with the first take's reason.
void add_walk_loops(CharacterType& type, std::span<const RawAnimation> takes, const std::string& file);

}  // namespace aloha
