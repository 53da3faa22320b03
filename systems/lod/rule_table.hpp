// The knowledge base in memory: geometric and animation levels, hysteresis and budget settings,
// tiers, and the ordered rules compiled to flat condition boxes (disjunctive normal form).
#pragma once

#include "components/lod.hpp"
#include "engine/core/result.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// The attributes a rule condition can test, in the order of a condition box's slots.
enum class LodAttribute : uint8_t {
    Distance = 0,
    ProjectedHeightPx = 1,
    Eccentricity = 2,
    Speed = 3,
    Visible = 4,
    Importance = 5,
    Tier = 6,
};

/// Number of testable attributes (slots 0..6 of a box; slot 7 is padding that always passes).
inline constexpr int kLodAttributeCount = 7;
/// Slots per condition box (padded to 8 floats so the test vectorises).
inline constexpr int kBoxSlots = 8;

/// The rule-file name of attribute `a` ("distance", "projected_height_px", ...).
[[nodiscard]] std::string_view attribute_name(LodAttribute a);

/// One geometric level as declared in the rule file (index 0 = richest).
struct GeomLevelDef {
    std::string name;                       ///< unique name rules refer to
    GeomMethod method = GeomMethod::RigidProxy;
    uint16_t theta_steps = 8;               ///< super-ellipsoid steps around
    uint16_t phi_steps = 6;                 ///< super-ellipsoid steps pole to pole
    uint8_t subdiv_level = 0;               ///< Catmull-Clark levels (Subdivided only)
    uint8_t layers = kLayerSkeleton;        ///< LayerBits
    uint16_t geomorph_frames = 0;           ///< morph frames when this level is entered
};

/// One animation level as declared in the rule file (index 0 = richest).
struct AnimLevelDef {
    std::string name;                       ///< unique name rules refer to
    WalkMethod walk = WalkMethod::ClipPlayback;
    IkSolver ik = IkSolver::None;
    uint8_t ik_iterations = 0;
    float ik_tolerance = 1e-3f;             ///< metres
    uint8_t update_interval = 1;            ///< animate every N frames
    uint8_t crossfade_frames = 0;           ///< pose cross-fade frames when this level is entered
};

/// Value and time hysteresis of the resolver.
struct HysteresisParams {
    float band = 0.1f;           ///< relative widening of the active rule's bounds (0.1 = 10%)
    uint16_t min_frames = 10;    ///< frames a character stays at a level before it may switch again
};

/// Frame-budget controller settings (section "budget" of a rule file).
struct BudgetParams {
    float target_ms = 12.0f;     ///< CPU-systems time the controller aims under
    float deadband = 0.15f;      ///< no promotion unless the smoothed time < target * (1 - deadband)
    float smoothing = 0.25f;     ///< EMA weight of the newest measurement, in (0, 1]
    float demote_gain = 0.5f;    ///< fraction of the relative overshoot applied per step
    float promote_gain = 0.2f;   ///< fraction of the relative headroom applied per step
    uint16_t settle_frames = 4;  ///< frames to wait after a step before the next one
    uint8_t max_demotion = 3;    ///< most levels the budget may remove from one character
};

/// One rule as written (name, where it is in the file, what it selects).
struct RuleDef {
    std::string name;            ///< rule name (unique)
    std::string json_path;       ///< "/rules/3", for messages
    uint8_t geom_level = 0;      ///< index into geom_levels
    uint8_t anim_level = 0;      ///< index into anim_levels
    bool unconditional = false;  ///< true when the rule has no conditions (a fallback)
};

/// A conjunction of closed intervals, one per attribute slot: passes when lo[k] <= v[k] <= hi[k]
/// for every k. `*_wide` are the bounds widened by the hysteresis band (used for the active rule).
struct alignas(32) ConditionBox {
    std::array<float, kBoxSlots> lo;
    std::array<float, kBoxSlots> hi;
    std::array<float, kBoxSlots> lo_wide;
    std::array<float, kBoxSlots> hi_wide;
};

/// A rule's compiled form: its boxes are boxes[first_box, first_box + box_count) (an OR of them).
struct CompiledRule {
    uint32_t first_box = 0;
    uint32_t box_count = 0;
    uint8_t geom_level = 0;
    uint8_t anim_level = 0;
};

/// A loaded, validated rule file. Invariants: at least one level of each kind, at least one rule,
/// the last rule is unconditional, every level index in range, compiled.size() == rules.size().
struct RuleTable {
    std::string source;                      ///< file (or source name) it was parsed from
    std::vector<GeomLevelDef> geom_levels;   ///< richest first
    std::vector<AnimLevelDef> anim_levels;   ///< richest first
    HysteresisParams hysteresis;
    std::optional<BudgetParams> budget;      ///< absent: no frame budget
    std::vector<std::string> tiers;          ///< tier names, index = value of the "tier" attribute
    uint8_t default_tier = 0;                ///< tier used when the host names none
    std::vector<RuleDef> rules;              ///< evaluation order
    std::vector<CompiledRule> compiled;      ///< parallel to rules
    std::vector<ConditionBox> boxes;         ///< all rules' boxes, contiguous per rule
    std::vector<Error> warnings;             ///< non-fatal findings (e.g. shadowed rules)

    /// Index of the geometric level named `name`, or -1.
    [[nodiscard]] int find_geom_level(std::string_view name) const;
    /// Index of the animation level named `name`, or -1.
    [[nodiscard]] int find_anim_level(std::string_view name) const;
    /// Index of the rule named `name`, or -1.
    [[nodiscard]] int find_rule(std::string_view name) const;
    /// Index of the tier named `name`, or -1.
    [[nodiscard]] int find_tier(std::string_view name) const;
    /// The GeomLod marshalled for level `level` (clamped to the last level).
    [[nodiscard]] GeomLod geom_lod(uint8_t level) const;
    /// The AnimLod marshalled for level `level` (clamped to the last level).
    [[nodiscard]] AnimLod anim_lod(uint8_t level) const;
};

/// Parses rule-file JSON `text`; `source_name` names it in errors. On failure the Error is the first
/// problem and, when `all_errors` is given, every problem found is appended there. Warnings go to
/// RuleTable::warnings. Comments (// and /* */) are allowed.
Result<RuleTable> parse_rules(std::string_view text, const std::string& source_name,
                              std::vector<Error>* all_errors = nullptr);

/// Reads the file at `path` and parses it with parse_rules (errors name `path`).
Result<RuleTable> load_rules(const std::string& path, std::vector<Error>* all_errors = nullptr);

}  // namespace aloha
