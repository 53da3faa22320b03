// Published gait relations that set a gait cycle from speed and leg length: stride length from
// the Froude number (Alexander 1984), the walk-run transition near Froude 0.5 (Alexander & Jayes
// 1983), and duty factors and body motion amplitudes in the ranges reported for adult gait.
// Shared by the generated gait clips and the kinematic walk so both walk with the same stride.
#pragma once

namespace aloha {

/// One gait cycle (two steps, starting at the left foot's touchdown).
struct GaitCycle {
    float speed = 0.0f;      ///< m/s, forward
    float stride = 0.0f;     ///< m travelled per cycle (two steps)
    float period = 0.0f;     ///< s per cycle (stride / speed)
    float duty = 0.6f;       ///< fraction of the cycle each foot is on the ground
    bool running = false;    ///< true above the walk-run transition (flight phases, duty < 0.5)
    float froude = 0.0f;     ///< v^2 / (g * hip height)
    float bob = 0.0f;        ///< vertical pelvis excursion amplitude (m, half peak to peak)
    float sway = 0.0f;       ///< lateral pelvis excursion amplitude (m)
    float pelvis_yaw = 0.0f; ///< pelvis rotation amplitude about the vertical (rad)
    float pelvis_roll = 0.0f;///< pelvic obliquity amplitude (rad)
    float lean = 0.0f;       ///< forward trunk lean (rad)
    float arm_swing = 0.0f;  ///< shoulder flexion amplitude (rad)
    float elbow = 0.0f;      ///< mean elbow flexion (rad)
    float clearance = 0.0f;  ///< swing ankle lift above the straight line between footholds (m)
    float heel_strike = 0.0f;///< foot pitch at touchdown, toes up (rad)
    float toe_off = 0.0f;    ///< foot pitch at lift-off, heel up (rad, positive)
};

/// Slowest and fastest speeds the gait relations are used for (m/s).
inline constexpr float kMinGaitSpeed = 0.3f;
inline constexpr float kMaxGaitSpeed = 4.0f;

/// The gait cycle for `speed` m/s (clamped to [kMinGaitSpeed, kMaxGaitSpeed]) of a body whose hip
/// joints stand `hip_height` metres above the ground. Requires hip_height > 0.
[[nodiscard]] GaitCycle gait_cycle(float speed, float hip_height);

}  // namespace aloha
