// The per-frame core of the blended skin (BlendSpringJob): each skin vertex's spring root r = sum w_m P_m and rest end
// y = sum w_m (P_m + F_m o_m) over its influences, with P_m and the frame F_m sampled by sample_grid_frame() in the
// influence's bind-time cell.
//
// Two forms with the same bits: blend_rest() (scalar, one vertex: the reference and the fallback) and blend_rest_x4()
// (four consecutive vertices in the four lanes of SSE2 registers). The lanes run exactly the scalar operations in the
// same order (bilinear mixes as x (1 - a) + y a, sqrt and true divides, dots summed x, y, then z, no FMA, zero weights
// skipped by a select rather than added), so vectorising changes no result: tests compare the two bit for bit. Where
// the build's baseline is older than AVX, an AVX-encoded copy of the same 128-bit code runs on CPUs that have it.
// spring_step_x4() is the same for the springs' step: SpringStepper::step() in four lanes, its branches as selects.
#pragma once

#include "systems/geometry/body_skin/blend_binding.hpp"
#include "systems/geometry/spring_skin/fat_spring_step.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>

namespace aloha {

/// Root and rest end of the skin vertex bound by `b` on `muscle_positions`/`muscle_normals` (muscles x `grid_vertices`
/// each), as BlendSpringJob defines them. Requires every active influence's muscle and cell inside the spans.
void blend_rest(std::span<const glm::vec3> muscle_positions, std::span<const glm::vec3> muscle_normals, uint32_t grid_vertices,
                const BlendBinding& b, glm::vec3& root, glm::vec3& rest);

/// blend_rest() of the four bindings b[0..3], written as root[axis][lane] and rest[axis][lane], bit-identical to it.
/// Returns false, with root and rest undefined, when an active influence's frame is degenerate (normal or tangent of
/// near-zero length: a pole or a collapsed cell), where the scalar form picks a fallback direction; the caller then
/// uses blend_rest() for these vertices. Requires the spans under 4 GiB (it addresses them with 32-bit byte offsets).
/// Without SSE2 it always returns false. `allow_avx` false keeps to the SSE2 encoding where an AVX one would be chosen
/// (tests compare both).
[[nodiscard]] bool blend_rest_x4(std::span<const glm::vec3> muscle_positions, std::span<const glm::vec3> muscle_normals,
                                 uint32_t grid_vertices, const BlendBinding* b, float root[3][4], float rest[3][4],
                                 bool allow_avx = true);

/// One frame of the fat springs of the four consecutive vertices whose roots and rest ends blend_rest_x4() gave
/// (root[axis][lane], rest[axis][lane]): lane i is stepped by *steppers[i] exactly as BlendSpringJob steps it one by
/// one (normal (rest - root) / h, or +z where h <= 1e-6, then SpringStepper::step()), bit for bit. end, velocity and
/// prev_rest point at the first of the four vertices' states. `allow_avx` as for blend_rest_x4().
void spring_step_x4(const float root[3][4], const float rest[3][4], const SpringStepper* const steppers[4], glm::vec3* end,
                    glm::vec3* velocity, glm::vec3* prev_rest, bool allow_avx = true);

}  // namespace aloha
