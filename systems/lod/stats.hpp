// Explainability: per-frame LOD statistics (histograms by level, method and rule) and a per-
// character explanation (attributes, rule fired, levels, budget demotion, transitions), as structs
// and as JSON for the profiler's report and the viewer's overlay.
#pragma once

#include "components/lod.hpp"
#include "systems/lod/rule_table.hpp"

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// Rule-file name of a geometric method ("hidden", "rigid_proxy", ...).
[[nodiscard]] std::string_view to_string(GeomMethod m);
/// Rule-file name of a walk method ("clip", "kinematic", "dynamic").
[[nodiscard]] std::string_view to_string(WalkMethod m);
/// Rule-file name of an IK solver ("none", "ccd", "dls").
[[nodiscard]] std::string_view to_string(IkSolver s);

/// Counts of characters for one frame.
struct LodStats {
    uint32_t characters = 0;                  ///< states counted
    uint32_t visible = 0;                     ///< with attributes.visible (0 when no attributes given)
    uint32_t demoted = 0;                     ///< with budget_demotion or anim_demotion > 0
    uint32_t occluded = 0;                    ///< visible but fully occluded (attributes.occluded >= 1)
    std::array<uint32_t, 5> occlusion_histogram{};  ///< visible characters by occluded: 0, <0.5, <0.9, <1, 1
    uint32_t in_geomorph = 0;                 ///< with geomorph_left_s > 0
    uint32_t in_crossfade = 0;                ///< with crossfade_left_s > 0
    std::vector<uint32_t> per_geom_level;     ///< index = geometric level
    std::vector<uint32_t> per_anim_level;     ///< index = animation level
    std::vector<uint32_t> per_rule;           ///< index = rule id (rule that produced the levels)
    std::array<uint32_t, 6> per_geom_method{};///< index = GeomMethod
    std::array<uint32_t, 3> per_walk_method{};///< index = WalkMethod
};

/// Fills a LodStats from states (and optionally attributes) of a range of characters.
struct LodStatsJob {
    const RuleTable* table = nullptr;          ///< required
    std::span<const LodState> states;          ///< n entries
    std::span<const LodAttributes> attributes; ///< n entries, or empty (visible stays 0)
    LodStats* output = nullptr;                ///< required; vectors resized to the table's counts

    /// Checks table, output and sizes; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Overwrites *output. Allocates only when the table's level/rule counts grow.
    void Run() const;
};

/// Why one character has the levels it has.
struct LodExplanation {
    uint32_t index = 0;                 ///< character index in the spans given
    LodAttributes attributes;           ///< what the rules saw
    float noticeability = 0.0f;         ///< significance: the budget's and the caps' ranking score
    uint16_t rule_id = 0;               ///< rule that produced the current levels
    std::string rule_name;              ///< its name ("" when out of range)
    uint8_t rule_geom_level = 0;        ///< what that rule asks for (before budget demotion)
    uint8_t rule_anim_level = 0;
    uint8_t budget_demotion = 0;        ///< geometric levels removed by the frame budget
    uint8_t anim_demotion = 0;          ///< animation levels removed by the frame budget
    uint8_t cap_geom_level = 0;         ///< richest geometric level the caps allow (0 = any)
    uint8_t cap_anim_level = 0;         ///< richest animation level the caps allow (0 = any)
    bool always_full = false;           ///< never demoted by the budget (scene flag)
    GeomLod geom;                       ///< marshalled geometric parameters of the current level
    std::string geom_level_name;
    AnimLod anim;                       ///< marshalled animation parameters of the current level
    std::string anim_level_name;
    uint8_t prev_geom_level = 0;        ///< level morphed from while geomorph_left_s > 0
    float geomorph_left_s = 0.0f;       ///< seconds of geomorph left
    uint8_t prev_anim_level = 0;        ///< level cross-faded from while crossfade_left_s > 0
    float crossfade_left_s = 0.0f;      ///< seconds of pose cross-fade left
    float seconds_at_geom = 0.0f;       ///< seconds since the last geometric switch
    float seconds_at_anim = 0.0f;       ///< seconds since the last animation switch
};

/// Explains character `i` from its attributes and state. Requires i < both sizes.
[[nodiscard]] LodExplanation explain(const RuleTable& table, uint32_t i, std::span<const LodAttributes> attributes,
                                     std::span<const LodState> states);

/// JSON of an explanation (names as in the rule file).
[[nodiscard]] nlohmann::json to_json(const LodExplanation& e);
/// JSON of frame statistics, histograms keyed by level, method and rule names of `table`.
[[nodiscard]] nlohmann::json to_json(const LodStats& s, const RuleTable& table);

}  // namespace aloha
