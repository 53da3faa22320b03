#include "systems/motion/library/gait_model.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {
constexpr float kGravity = 9.81f;
constexpr float kDeg = 3.14159265358979f / 180.0f;
}  // namespace

GaitCycle gait_cycle(float speed, float hip_height) {
    GaitCycle g;
    const float v = std::clamp(speed, kMinGaitSpeed, kMaxGaitSpeed);
    const float h = hip_height;
    const float scale = h / 0.93f;  // amplitudes below are written for a 1.75 m adult (hip height 0.93 m)
    g.speed = v;
    g.froude = v * v / (kGravity * h);
    // Alexander (1984), "Stride length and speed for adults, children, and fossil hominids",
    // Am. J. Phys. Anthropol. 63:23-27: relative stride length = 2.3 * Froude^0.3, walk and run.
    g.stride = 2.3f * h * std::pow(g.froude, 0.3f);
    g.period = g.stride / v;
    // Alexander & Jayes (1983): people change from walking to running near Froude 0.5.
    g.running = g.froude > 0.5f;
    if (!g.running) {
        // Walking duty factor falls from ~0.65 when slow to ~0.56 at the transition.
        g.duty = 0.66f - 0.2f * g.froude;
        g.bob = scale * (0.008f + 0.013f * v);  // ~2.6 cm at 1.4 m/s
        g.sway = scale * std::max(0.008f, 0.028f - 0.007f * v);
        g.pelvis_yaw = (3.0f + 2.0f * v) * kDeg;
        g.pelvis_roll = 4.0f * kDeg;
        g.lean = (1.0f + 1.5f * v) * kDeg;
        g.arm_swing = std::min(30.0f, 6.0f + 12.0f * v) * kDeg;
        g.elbow = (12.0f + 6.0f * v) * kDeg;
        g.clearance = scale * (0.045f + 0.015f * v);
        g.heel_strike = std::min(18.0f, 6.0f + 6.0f * v) * kDeg;
        g.toe_off = std::min(45.0f, 25.0f + 8.0f * v) * kDeg;
    } else {
        // Running duty factor ~0.42 at the transition, ~0.35 fast (flight phases in between).
        g.duty = std::max(0.3f, 0.42f - 0.1f * (g.froude - 0.5f));
        g.bob = scale * 0.035f;
        g.sway = scale * 0.008f;
        g.pelvis_yaw = 6.0f * kDeg;
        g.pelvis_roll = 3.0f * kDeg;
        g.lean = (5.0f + 1.5f * v) * kDeg;
        g.arm_swing = std::min(45.0f, 20.0f + 7.0f * v) * kDeg;
        g.elbow = 80.0f * kDeg;
        g.clearance = scale * (0.10f + 0.04f * v);
        g.heel_strike = 6.0f * kDeg;
        g.toe_off = 40.0f * kDeg;
    }
    return g;
}

}  // namespace aloha
