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

/// The frame as the profiler's fidelity check sees it (see reference_frame).
struct ReferenceFrame {
    std::vector<DeformableMesh> meshes;           ///< visible characters at the reference level
    std::vector<double> deviation_sum;            ///< per geometric level: summed screen deviation (px)
    std::vector<double> deviation_max;            ///< per geometric level: largest deviation (px)
    std::vector<uint64_t> deviation_count;        ///< per geometric level: vertices measured
    uint32_t switches = 0;                        ///< visible characters that switched level this frame
    std::vector<std::vector<glm::vec3>> positions, normals;     ///< storage behind `meshes`
    std::vector<glm::vec3> current_scratch, reference_scratch;  ///< reused per character
};

/// The richest Layered level of `table`: the full-detail picture the fidelity check renders.
[[nodiscard]] uint8_t reference_level(const RuleTable& table);

/// Fills `out` for `world`'s last frame: every visible character's surface at reference_level() (springs
/// at rest) as draw items, and per level the screen-space deviation of each mesh character's displayed
/// control surface from its level-0 control surface. Requires an attached renderer (its topology ids
/// are registered through the World's draw-list builder). Allocates.
Status reference_frame(World& world, ReferenceFrame& out);

}  // namespace aloha
