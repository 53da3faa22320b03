// Diagnostics over a World, outside the host itself: the determinism hash, the stability check, memory
// per level and the fidelity check's full-detail reference frame. They read the World through its
// public accessors (group spans, per-type runtimes, draw-list builder) and change nothing it simulates.
#pragma once

#include "host/scene/world.hpp"

#include <cstdint>
#include <vector>

namespace aloha {

/// Memory the system reports as available (MemAvailable), 0 when unknown.
uint64_t available_memory_bytes();

/// Hash of every character's placement, LOD state and pose, in spawn order: equal across runs and
/// thread counts for the same scene and options.
[[nodiscard]] uint64_t state_hash(const World& world);

/// Counts NaN/Inf values in every character's placement, pose matrices and displayed surface (0 when
/// healthy): the long-run stability check.
[[nodiscard]] uint64_t nonfinite_count(const World& world);

/// Approximate bytes of per-character state per geometric level (for the profiler).
[[nodiscard]] std::vector<uint64_t> memory_per_level(const World& world);

/// A visible character that switched geometric level this frame, for attributing a switch frame's image
/// change to level pairs: its levels and the screen rectangle of its bounds box (pixels, clamped to the
/// viewport, x0 <= x < x1, y0 <= y < y1).
struct SwitchRect {
    uint8_t from = 0;                 ///< the level it left (LodState::prev_geom_level)
    uint8_t to = 0;                   ///< the level it entered
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< pixel rectangle; empty when it crosses the near plane or is off screen
};

/// The frame as the profiler's fidelity check sees it (see reference_frame).
struct ReferenceFrame {
    std::vector<DeformableMesh> meshes;           ///< visible characters at the reference level
    std::vector<double> deviation_sum;            ///< per geometric level: summed screen deviation (px)
    std::vector<double> deviation_max;            ///< per geometric level: largest deviation (px)
    std::vector<uint64_t> deviation_count;        ///< per geometric level: vertices measured
    /// Per geometric level, the same vertices with the displayed level's own springs at rest and no
    /// morph: the level's geometric error alone (summed px). deviation_sum less this is roughly what
    /// the fat springs' motion adds, which the full-detail body has as well.
    std::vector<double> rest_deviation_sum;
    std::vector<uint64_t> rest_deviation_count;   ///< per geometric level: vertices in rest_deviation_sum
    /// Per geometric level, the displayed vertices against level 0 with its own fat springs moving (the
    /// characters' reference springs, World::set_reference_springs): the full-detail body as it would move,
    /// fat motion included (summed px). Only characters carrying reference springs count.
    std::vector<double> moving_deviation_sum;
    std::vector<uint64_t> moving_deviation_count;  ///< per geometric level: vertices in moving_deviation_sum
    uint32_t switches = 0;                        ///< visible characters that switched level this frame
    std::vector<SwitchRect> switch_rects;         ///< those characters, one each
    std::vector<std::vector<glm::vec3>> positions, normals;     ///< storage behind `meshes`
    std::vector<glm::vec3> current_scratch, reference_scratch, rest_scratch, moving_scratch;  ///< reused per character
};

/// The richest Layered level of `table`: the full-detail picture the fidelity check renders.
[[nodiscard]] uint8_t reference_level(const RuleTable& table);

/// Fills `out` for `world`'s last frame: every visible character's surface at reference_level() (springs
/// at rest) as draw items, and per level the screen-space deviation of each mesh character's displayed
/// control surface from its level-0 control surface. Requires an attached renderer (its topology ids
/// are registered through the World's draw-list builder). Allocates.
Status reference_frame(World& world, ReferenceFrame& out);

}  // namespace aloha
