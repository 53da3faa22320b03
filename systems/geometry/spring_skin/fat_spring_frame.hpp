// The fat springs in the world: the springs are stepped in the character's model space (the space of
// the muscles and the displayed skin), but their state (outer end, its velocity, the previous rest end)
// stands for world-space quantities. Before each step the previous frame's state is carried into this
// frame's model space as if it had stayed where it was in the world:
//     p' = A p + b,  v' = A v,   A = (s_prev / s_cur) R_cur^T R_prev,  b = R_cur^T (x_prev - x_cur) / s_cur
// (placement x, rotation R, uniform scale s of the root). The step (fat_spring.hpp) then sees the rest
// end's WORLD velocity (root motion included), so starting, stopping, turning and landing of the
// character drive the springs exactly as world-space integration would (the spring maths is invariant
// under a rigid change of frame), while the skin stays in model space for display.
// A teleport or snap (the root moving faster than kSnapSpeed or turning faster than kSnapTurnRate in
// one frame) is not motion: that frame's change is ignored (A = identity, b = 0), so the skin keeps its
// model-space state and is not flung. The strain limit bounds the springs whatever happens.
#pragma once

#include "components/transform.hpp"
#include "systems/geometry/spring_skin/fat_spring.hpp"

#include <glm/glm.hpp>

#include <span>

namespace aloha {

/// Root speed (m/s) beyond which one frame's move is a teleport, not motion (a sprint is ~10 m/s).
inline constexpr float kSnapSpeed = 15.0f;
/// Root turn rate (rad/s) beyond which one frame's turn is a snap (720 deg/s, faster than a human spin).
inline constexpr float kSnapTurnRate = 4.0f * 3.14159265f;

/// Rigid change from last frame's model space to this frame's for world-fixed points: p' = A p + b.
struct SpringFrameChange {
    glm::mat3 a{1.0f};      ///< rotation times the scale ratio
    glm::vec3 b{0.0f};      ///< translation (model units)
    bool snapped = false;   ///< the move was a teleport or snap: identity kept
    bool moved = true;      ///< false: the placement did not change (identity, nothing to carry)
};

/// The change from placement `previous` to `current` over `dt` seconds (> 0): identity (snapped) when
/// the root moved faster than kSnapSpeed or turned faster than kSnapTurnRate, or a scale is not positive.
[[nodiscard]] SpringFrameChange spring_frame_change(const Transform& previous, const Transform& current, float dt);

/// Carries one character's spring state into this frame's model space (p' = A p + b for ends and rest
/// ends, v' = A v for velocities). Spans of equal size.
struct SpringReframeJob {
    SpringFrameChange change;           ///< spring_frame_change of this frame
    FatSpringStateView state;           ///< end / velocity / prev_rest (initialised is not read)

    /// Checks the span sizes; one message per failure.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Transforms the state in place. Requires Validate().
    void Run() const;
};

}  // namespace aloha
