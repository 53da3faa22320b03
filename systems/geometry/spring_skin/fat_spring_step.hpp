// The per-spring update shared by the grid fat springs (FatSpringJob) and the blended skin springs
// (BlendSpringJob): exact transition of the damped oscillator over one frame plus strain limiting
// (the maths is described in fat_spring.hpp).
#pragma once

#include "systems/geometry/spring_skin/fat_spring.hpp"

#include <glm/glm.hpp>

namespace aloha {

/// Transition matrix of d'' + 2 zeta w d' + w^2 d = 0 over dt: d1 = a d0 + b u0, u1 = c d0 + e u0.
struct SpringTransition {
    float a = 1.0f, b = 0.0f, c = 0.0f, e = 1.0f;
};

/// The exact transition for natural angular frequency `omega`, damping ratio `zeta`, step `dt`.
[[nodiscard]] SpringTransition exact_transition(double omega, double zeta, double dt);

/// Everything one frame's step needs, computed once per job from FatSpringParams.
struct SpringStepper {
    SpringTransition normal, lateral;
    float inv_dt = 30.0f;
    float normal_omega = 1.0f;
    float max_strain = 0.5f;

    /// An identity stepper (to fill arrays before assigning).
    SpringStepper() = default;
    /// Stepper for `params` (valid parameters).
    explicit SpringStepper(const FatSpringParams& params);
    /// Advances one spring whose rest end is `rest` with unit normal `n` and rest length `h`:
    /// updates end, velocity and prev_rest (restarting at rest on non-finite results).
    void step(glm::vec3 rest, glm::vec3 n, float h, glm::vec3& end, glm::vec3& velocity, glm::vec3& prev_rest) const;
};

}  // namespace aloha
