// Why characters switched level: the rules (the resolver's target moved with the budget's demotion
// unchanged since the character's last switch) or the frame budget (its demotion edit sent the
// character elsewhere), and for the budget's switches their way and whether one undid the character's
// previous budget switch. A profiling aid: it reads the resolver's output, it changes nothing.
#pragma once

#include "components/lod.hpp"
#include "systems/lod/rule_table.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// One character's history for SwitchCauseJob, per kind ([0] geometric, [1] animation).
struct SwitchRecord {
    std::array<uint8_t, 2> demotion{};        ///< the budget demotion in force at the last switch of that kind
    std::array<int8_t, 2> last_budget_way{};  ///< +1 demoted, -1 promoted by the budget at its last budget switch, 0 none
    std::array<uint64_t, 2> last_budget_frame{};  ///< frame of that budget switch
};

/// Switches of one frame by cause, per kind ([0] geometric, [1] animation).
struct SwitchCauseCounts {
    std::array<uint32_t, 2> rules{};        ///< the rules moved the target; the budget's demotion did not matter
    std::array<uint32_t, 2> budget_down{};  ///< the budget's demotion sent the character to a poorer level
    std::array<uint32_t, 2> budget_up{};    ///< the budget's promotion gave it a richer level back
    /// Budget switches that reversed the same character's previous budget switch of that kind within
    /// undo_frames (demoted, then promoted back, or the reverse).
    std::array<uint32_t, 2> undone{};
    /// Adds `o` to these counts.
    void add(const SwitchCauseCounts& o);
};

/// Classifies the switches the resolver made this frame. A switch of character i is the budget's when
/// the level it switched to differs from where lod_targets() would send it with the demotion recorded
/// at its last switch of that kind (the budget's edits since then changed where it went; way: the sign
/// of the demotion's change), else the rules' (request or caps moved). Then the record takes the
/// demotion in force. A switch is recognised by seconds_at_geom / seconds_at_anim == 0 after the
/// resolve (the resolver zeroes them on a switch); run after LodResolveJob, not on a snap frame.
struct SwitchCauseJob {
    const RuleTable* table = nullptr;           ///< required, outlives Run()
    std::span<const LodRequest> requests;       ///< this frame's requests (after caps), n entries
    std::span<const LodState> states;           ///< after the resolve, n entries
    std::span<const uint32_t> changed;          ///< indices (< n) of characters that switched a level this frame
    std::span<const uint32_t> keys;             ///< one per `changed` entry: that character's index into records (stable across frames)
    std::span<SwitchRecord> records;            ///< one per character, by key, read and written
    uint64_t frame = 0;                         ///< this frame's number (undo windows)
    uint64_t undo_frames = 60;                  ///< a budget switch that reverses the previous one within this many frames is `undone`
    SwitchCauseCounts* out = nullptr;           ///< required: this frame's counts are added to it

    /// Checks table, sizes, indices and keys; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Classifies every changed character. Requires Validate().
    void Run() const;
};

}  // namespace aloha
