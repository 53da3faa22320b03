// Clips that repeat: a type's clip played over and over (a looping `play` request, an idlers' idle) jumps where it
// wraps by however far its last pose and motion are from its first. A clip whose ends nearly meet gets a looped
// version with the seam closed (systems/motion/library/loop_seam.hpp), which the motion controller samples when the
// clip is played looping (ClipLibrary::find_looped); played once, the clip is as loaded. One whose ends are too far
// apart to close is faded by the controller where it wraps (AnimationClip::ends_meet).
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "host/scene/character_type.hpp"

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// An animation as loaded (before the 16-bit clip store), a clip of the type by its name, and the file it came from.
struct LoadedTake {
    RawAnimation take;
    std::string file;
};

/// Gives clip `id` of `type`, built from `take`, a looped version with its seam closed when its ends nearly meet:
/// when closing bends it by at most kMaxSeamBend (library/loop_cut.hpp; the seam as whole_take_seam measures it,
/// the bend as loop_seam.hpp seam_bend bounds it). Returns what to say of
/// the clip after its name: the seam closed, with its figures, or the figures it jumps by where it repeats (which the
/// motion controller fades over the level's cross-fade time: AnimationClip::ends_meet);
/// "" for a clip under 0.1 s (a held pose: nothing repeats). `file` names the take's file in a message.
std::string close_clip_seam(CharacterType& type, ClipId id, const RawAnimation& take, const std::string& file);

/// close_clip_seam for each of `takes` that is a clip of `type` (by its name) other than the type's idle (whose note
/// says it itself), with one note for all of them: the clips closed where they repeat and those faded there.
void close_clip_seams(CharacterType& type, std::span<const LoadedTake> takes);

}  // namespace aloha
