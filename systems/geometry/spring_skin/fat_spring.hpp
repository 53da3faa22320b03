// Fat layer: one stiff linear spring per muscle surface vertex, pointing outward along the
// muscle normal, rest length = the muscle's fat thickness. The outer spring ends are the skin.
//
// Dynamics (per spring, model space). The rest position of the outer end is y = p + h n (root p,
// normal n, thickness h). Over one frame y is taken to move linearly from last frame's y_prev to y
// (first-order hold, velocity w = (y - y_prev) / dt), so the deviation d = x - y obeys the
// homogeneous damped oscillator  d'' + 2 zeta w0 d' + w0^2 d = 0  inside the frame. Its normal
// component uses (normal_hz, normal_damping) and its lateral component (tangent plane) a
// critically damped follow (lateral_hz, damping 1). Each frame applies the EXACT solution of that
// linear ODE over dt (a 2x2 transition matrix per component), so any stiffness is stable at any dt
// and the spring energy E = 1/2 w0n^2 |d_n|^2 + 1/2 w0t^2 |d_t|^2 + 1/2 |d'|^2 never grows inside a
// frame; energy only enters through changes of the root velocity w between frames (inertia).
// Strain limiting (Provot-style) then keeps |d| <= max_strain * h (so the spring length stays
// within h * (1 +- max_strain) by the triangle inequality) with the outward relative velocity
// removed when clamped, and |d'| <= max_strain * h * w0n, so a one-frame joint snap cannot blow up.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Tuning of the fat springs. All values must be finite; frequencies and dt > 0.
struct FatSpringParams {
    float dt = 1.0f / 30.0f;        ///< frame time step (s)
    float normal_hz = 12.0f;        ///< natural frequency of the spring along the normal (Hz)
    float normal_damping = 0.6f;    ///< damping ratio along the normal (>= 0; 1 = critical)
    float lateral_hz = 8.0f;        ///< natural frequency of the critically damped lateral follow (Hz)
    float max_strain = 0.5f;        ///< strain limit: |end - rest end| <= max_strain * thickness
};

/// Most tunings one spring job mixes per vertex (BlendSpringJob::region_params).
inline constexpr size_t kMaxSpringTunings = 16;

/// The "initialised" flag's values. A spring restarts at its rest end (kSpringsRestart -> kSpringsStarted);
/// its first step then gives it its rest end's velocity, so it starts moving with the body rather than
/// from a standstill, which would jolt the fat of a walking character at every restart (a LOD switch)
/// by its walking speed (kSpringsStarted -> kSpringsRunning); after that it is stepped.
inline constexpr uint8_t kSpringsRestart = 0;
inline constexpr uint8_t kSpringsStarted = 2;
inline constexpr uint8_t kSpringsRunning = 1;

/// Mutable per-spring state (structure of arrays), one entry per muscle surface vertex, plus one
/// "initialised" flag per muscle. Views into a FatSpringPool (or any storage the caller owns).
struct FatSpringStateView {
    std::span<glm::vec3> end;          ///< outer end position (the skin vertex), model space
    std::span<glm::vec3> velocity;     ///< outer end velocity (m/s)
    std::span<glm::vec3> prev_rest;    ///< rest position of the end at the previous frame
    std::span<uint8_t> initialised;    ///< per muscle: kSpringsRestart / kSpringsStarted / kSpringsRunning (above)
};

/// Owns spring state for many characters laid out contiguously (character after character, each
/// its muscles after one another, each muscle V(T, P) springs), so a contiguous character range
/// is one contiguous span. Characters of one pool share (T, P) and the muscle count: keep one pool
/// per LOD bucket and reset() a character when it enters the bucket.
class FatSpringPool {
public:
    /// Creates state for `characters` x `muscles_per_character` muscles at (T, P), all uninitialised.
    /// Requires T >= 3, P >= 2.
    FatSpringPool(uint32_t characters, uint32_t muscles_per_character, uint32_t theta_steps,
                  uint32_t phi_steps);
    /// Number of characters.
    [[nodiscard]] uint32_t character_count() const { return characters_; }
    /// Muscles per character.
    [[nodiscard]] uint32_t muscles_per_character() const { return muscles_; }
    /// Springs per character (= muscle vertices = skin vertices = muscles * V(T, P)).
    [[nodiscard]] uint32_t springs_per_character() const;
    /// Total springs in the pool.
    [[nodiscard]] size_t spring_count() const { return end_.size(); }
    /// Tessellation of the pool.
    [[nodiscard]] uint32_t theta_steps() const { return theta_; }
    [[nodiscard]] uint32_t phi_steps() const { return phi_; }
    /// State of characters [first, first + count). Requires first + count <= character_count().
    FatSpringStateView view(uint32_t first, uint32_t count);
    /// Marks character `c` to restart at rest on its next step (after a LOD switch or a teleport).
    void reset(uint32_t c);

private:
    uint32_t characters_, muscles_, theta_, phi_;
    std::vector<glm::vec3> end_, velocity_, prev_rest_;
    std::vector<uint8_t> initialised_;
};

/// Advances the fat springs of a contiguous run of muscles (any number of characters sharing T, P)
/// by one frame. Inputs: muscle positions/normals (muscles x V(T, P), normals unit length) and the
/// fat thickness per muscle (>= 0). Writes state.end (the skin positions), velocity, prev_rest.
struct FatSpringJob {
    uint32_t theta_steps = 8;                          ///< grid steps around (T >= 3)
    uint32_t phi_steps = 6;                            ///< grid steps pole to pole (P >= 2)
    FatSpringParams params;                            ///< dynamics tuning
    std::span<const glm::vec3> muscle_positions;       ///< spring roots, muscles x V(T, P)
    std::span<const glm::vec3> muscle_normals;         ///< unit outward normals, same size
    std::span<const float> thickness;                  ///< fat thickness (m) per muscle
    FatSpringStateView state;                          ///< per-spring state, same size as positions

    /// Checks sizes and parameters; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Steps every spring. Requires Validate().
    void Run() const;
};

/// Spring energy per unit mass of one spring (the quantity the dynamics never increase inside a
/// frame): 1/2 w0n^2 |d_n|^2 + 1/2 w0t^2 |d_t|^2 + 1/2 |v - w|^2, with d = end - rest_end split by
/// the unit normal n, and `rest_velocity` w the velocity of the rest end.
float fat_spring_energy(const FatSpringParams& params, glm::vec3 end, glm::vec3 velocity, glm::vec3 rest_end,
                        glm::vec3 rest_velocity, glm::vec3 normal);

}  // namespace aloha
