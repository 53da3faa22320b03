// Root motion for an in-place cycle, from its feet. Game packs and Mixamo's "In Place" export ship walks and runs
// whose body stays over the origin while the feet slide back and forth under it: played as a walk, such a cycle
// skates. The travel is in the feet: while a foot is on the ground it slides back exactly as far as the body would
// have gone. Moving the root by the opposite of the supporting foot's slide keeps that foot where it is in the
// world and gives the body its travel, so the cycle becomes a walk loop (loop_cut.hpp) played with planted feet.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <span>
#include <string>

namespace aloha {

/// What root_motion_from_feet found.
struct FootRootMotionReport {
    float speed = 0.0f;          ///< forward (+Z) travel over the clip's length, m/s
    float lateral = 0.0f;        ///< sideways (X) travel over the clip's length, m/s
    float flight_share = 0.0f;   ///< share of the clip with neither foot on the ground (a run's flight)
};

/// Root travel (mean horizontal speed, m/s) below which a clip counts as in place.
inline constexpr float kInPlaceSpeed = 0.1f;

/// `clip` (on `skeleton`, normalised: +Y up, facing +Z) with root motion from its feet: resampled at `rate` keys a
/// second, the root joint (joint 0) moved at each key by the opposite of the supporting joint's horizontal move in
/// model space since the key before. `contacts` are the joints that touch the ground (both ankles, and the toes
/// where the rig has them: a rolling foot stands on its heel, then flat, then on its toe); the supporting one over a
/// step is the one nearest the lowest it comes over the clip, while that is within 2 cm; with none on the ground (a
/// run's flight) the body keeps the velocity it had. So a supporting foot keeps its place on the ground. Errors,
/// naming `source` and the clip: a clip whose root already travels (mean horizontal speed kInPlaceSpeed or more: it
/// has root motion), feet that do not carry the body forward (+Z) at `min_speed` m/s or more (an idle, a jump on
/// the spot, a backward or sideways step), no contact joints, a clip that does not build.
[[nodiscard]] Result<RawAnimation> root_motion_from_feet(const RawAnimation& clip, const Skeleton& skeleton, std::span<const int> contacts,
                                                         float min_speed, const std::string& source, float rate = 60.0f,
                                                         FootRootMotionReport* report = nullptr);

}  // namespace aloha
