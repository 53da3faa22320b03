// Best-loop cutting for takes that were not captured as cycles (a motion-capture "start, walk,
// stop" used as a walk loop): finds the pair of frames whose poses and joint velocities match best
// (in the root's own heading frame), cuts the take there, and spreads the heading drift over the
// loop so the seam does not turn the body. A take with no good loop is refused with a note.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <string>

namespace aloha {

/// Where the best loop of a take is and how well its ends match.
struct LoopCut {
    float start = 0.0f;          ///< seconds into the take
    float end = 0.0f;            ///< seconds into the take (end > start)
    float pose_error = 0.0f;     ///< mean joint distance between the end poses (m, root-relative)
    float velocity_error = 0.0f; ///< mean joint velocity difference between the ends (m/s)
};

/// Largest mean joint distance (m) and velocity difference (m/s) accepted at a loop's seam.
inline constexpr float kMaxLoopPoseError = 0.03f;
inline constexpr float kMaxLoopVelocityError = 0.25f;
/// Largest mean bend (m per joint, loop_seam.hpp seam_bend) closing may put on a clip played over and over (an
/// idle, a looping play) to remove the jump where it repeats: what closing a seam at kMaxLoopPoseError does to the
/// pose alone. A clip that repeats jumps there otherwise, so its velocities are matched whenever the bend allows,
/// without a bar of their own (the bars above choose walk loops, where a cut elsewhere may match better).
inline constexpr float kMaxSeamBend = 0.5f * kMaxLoopPoseError;

/// Finds the best loop of `take` (built for `skeleton`) at least `min_seconds` long whose root keeps
/// travelling at `min_speed` m/s or more throughout (a walk loop must walk; 0 for any loop), comparing poses sampled
/// every `step` seconds. The whole take is a candidate too (a cycle authored as one), its seam's velocity error the
/// excess of the velocity jump across the seam over the largest jump between steps inside the take. Errors (naming `source`) when the take is too short or no loop is within
/// kMaxLoopPoseError / kMaxLoopVelocityError (the message gives the best found).
Result<LoopCut> find_best_loop(const RawAnimation& take, const Skeleton& skeleton, float min_seconds, float min_speed,
                               const std::string& source, float step = 1.0f / 30.0f);

/// How well `take` loops as it is, its last pose back to its first: the whole take as a cut, judged as find_best_loop
/// judges a whole take (mean joint distance between the end poses; the velocity jump across the seam beyond the
/// largest jump between `step`s inside it). Errors (naming `source`) for a clip that does not build or is shorter
/// than three steps.
Result<LoopCut> whole_take_seam(const RawAnimation& take, const Skeleton& skeleton, const std::string& source,
                                float step = 1.0f / 30.0f);

/// The keys of `take` between cut.start and cut.end (at the take's own key rate, ends interpolated), re-timed from
/// 0, with the root's heading drift over the loop spread evenly so the last key faces like the first, and the seam
/// closed (close_loop_seam: the ends made equal, and their velocities matched to the take's own at the two cut
/// points, or for a whole take beyond the jumps inside it). Named `name`.
[[nodiscard]] RawAnimation cut_loop(const RawAnimation& take, const Skeleton& skeleton, const LoopCut& cut,
                                    const std::string& name);

}  // namespace aloha
