// Level caps: at most N characters at a level or any richer one (a level's `max_characters`), the
// places filled by significance. Runs after the frame budget and before the resolver each frame and
// writes the richest level each character may have (LodState::cap_geom_level / cap_anim_level).
#pragma once

#include "components/lod.hpp"
#include "systems/lod/rule_table.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace aloha {

/// Scratch of the caps job that lives across frames (ranking, per-level counts).
struct LevelCapScratch {
    std::vector<std::pair<float, uint32_t>> ranked;  ///< (-score, index): most significant first
    std::vector<uint32_t> used;                      ///< characters placed at each level
    std::vector<std::vector<std::pair<float, uint32_t>>> blocks;  ///< candidates per block (run_chunks)
};

/// Places characters under the caps of `table`, most significant first.
///
/// Each character's starting point is where the resolver would put it without caps
/// (uncapped_outcome: a character held by time hysteresis counts where it is). Characters are taken
/// in order of significance (the table's expression, `always_full` characters first, ties by index),
/// those already at or above where they want to be getting a bonus of `keep_bonus` (relative) so two
/// nearly equal characters do not keep trading places; each gets the richest level at or below its
/// starting point where every cap at that level and below still has room. The resolver then never
/// puts a character richer than that (it leaves a level over its cap at once), so after it no cap is
/// exceeded. Characters wanting no capped level are not ranked. Allocates only when the crowd grows.
struct LevelCapJob {
    const RuleTable* table = nullptr;              ///< required, outlives Run()
    std::span<const LodRequest> requests;          ///< n entries (this frame's rule requests)
    std::span<const LodAttributes> attributes;     ///< n entries (significance)
    std::span<LodState> states;                    ///< n entries: levels read, cap_* written
    bool snap = false;                             ///< the resolver's snap flag this frame
    float dt = 0.0f;                               ///< the resolver's dt this frame (seconds, >= 0)
    float keep_bonus = 0.1f;                       ///< relative significance bonus of incumbents, >= 0
    LevelCapScratch* scratch = nullptr;            ///< required
    /// Optional: runs fn(begin, end) over [0, count) in chunks [k * grain, (k + 1) * grain), possibly
    /// concurrently (a host scheduler's parallel_for); empty = one serial pass. Results do not depend on it.
    std::function<void(size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn)> run_chunks{};

    /// Checks table, sizes and scratch; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Writes cap_geom_level / cap_anim_level of every state (0 everywhere when the table has no caps);
    /// returns how many characters the caps hold below their starting point. Requires Validate().
    size_t Run() const;
};

}  // namespace aloha
