// The knowledge base in memory: geometric and animation levels, hysteresis and budget settings,
// tiers, and the ordered rules compiled to flat condition boxes (disjunctive normal form).
#pragma once

#include "components/lod.hpp"
#include "engine/core/result.hpp"
#include "systems/lod/significance.hpp"

#include <algorithm>
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
    Occluded = 7,
};

/// Number of testable attributes (slots 0..7 of a box).
inline constexpr int kLodAttributeCount = 8;
/// Slots per condition box (8 floats so the test vectorises).
inline constexpr int kBoxSlots = 8;

/// Level cap value meaning "no cap".
inline constexpr uint32_t kNoCap = 0xFFFFFFFFu;

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
    float geomorph_s = 0.0f;                ///< morph seconds when this level is entered
    float simplify_error = 0.0f;            ///< skinned_mesh: simplified triangles, error / height (0: the full list)
    float enter_after_s = 0.0f;             ///< seconds this level must be asked for without a break before
                                            ///< a character enters it (leaving it is not delayed)
    uint32_t max_characters = kNoCap;       ///< cap: at most this many characters here or richer
};

/// One animation level as declared in the rule file (index 0 = richest).
struct AnimLevelDef {
    std::string name;                       ///< unique name rules refer to
    WalkMethod walk = WalkMethod::ClipPlayback;
    IkSolver ik = IkSolver::None;
    uint8_t ik_iterations = 0;
    float ik_tolerance = 1e-3f;             ///< metres
    uint8_t update_interval = 1;            ///< animate every N frames
    float crossfade_s = 0.0f;               ///< pose cross-fade seconds when this level is entered
    uint32_t max_characters = kNoCap;       ///< cap: at most this many characters here or richer
};

/// Value and time hysteresis of the resolver.
struct HysteresisParams {
    float band = 0.1f;           ///< relative widening of the active rule's bounds (0.1 = 10%)
    float min_seconds = 0.15f;   ///< simulated seconds a character stays at a level before it may switch again
};

/// One separately budgeted part of the CPU systems (section "budget/animation" or "budget/geometry").
struct BudgetPartParams {
    float target_ms = 0.0f;      ///< the part's measured time the controller steers to; 0 = not budgeted
    float tolerance = 0.05f;     ///< no step while the smoothed time is within target * (1 +- tolerance)
    float gain = 0.7f;           ///< fraction of the predicted error corrected per step, in (0, 1]
    uint8_t max_demotion = 3;    ///< most levels this part may remove from one character
    /// With trimming on (BudgetParams::trim_smoothing > 0): the fast average acts only when it is
    /// outside target * (1 +- react_tolerance); inside, the slow trim average steers (tolerance band).
    float react_tolerance = 0.25f;
};

/// Frame-budget settings (section "budget" of a rule file). Either a single total (`target_ms`, the
/// original controller demoting both kinds of level together) or separate animation and geometry
/// parts, each steering on its own measured time with learned per-level costs.
struct BudgetParams {
    bool enabled = true;         ///< false: the settings are kept but the host runs no budget
    float target_ms = 0.0f;      ///< total CPU-systems time of the single-total controller; 0 = none
    float deadband = 0.15f;      ///< single total: no promotion unless smoothed < target * (1 - deadband)
    float smoothing = 0.25f;     ///< EMA weight of the newest measurement, in (0, 1]
    float demote_gain = 0.5f;    ///< single total: fraction of the relative overshoot applied per step
    float promote_gain = 0.2f;   ///< single total: fraction of the relative headroom applied per step
    uint16_t settle_frames = 4;  ///< frames to wait after a step before the next one
    uint8_t max_demotion = 3;    ///< single total: most levels the budget may remove from one character
    float cost_smoothing = 0.2f; ///< parts: EMA weight of each new per-level cost measurement, in (0, 1]
    /// Parts: EMA weight of the slow "trim" average (0 = off: the fast average alone steers). On, the
    /// fast average (`smoothing`) answers only errors beyond each part's react_tolerance and the slow
    /// one trims the rest, so cost swings faster than its window (gait cycles, thread partition) are
    /// averaged out instead of chased with level changes.
    float trim_smoothing = 0.0f;
    /// Parts: time constants of the smoothed time (1 / smoothing updates each) the prediction must stay
    /// outside the band on one side before a step is taken (0 = off: at once), however large the error.
    /// A burst of load shorter than this (another process took the core for a few frames) is not chased
    /// with level changes that its end would undo; a real change is answered that much later.
    float dwell = 0.0f;
    /// Parts: standard errors (k) by which a part's averaged time must be outside its tolerance band
    /// before a step (0, the default = off: the band test on the smoothed time). On, the part steers on the mean
    /// of its measured time since the time last changed (a step, or the smoothed time leaving that mean
    /// by k standard errors of their difference), whose standard error comes from the measured noise
    /// (BudgetNoise): noise alone steps with probability under that of a normal beyond k (3: 0.13%
    /// a look), and a mean held inside the band makes no more steps as its error shrinks.
    float confidence = 0.0f;
    BudgetPartParams animation;  ///< the motion system's time
    BudgetPartParams geometry;   ///< the muscle + spring_skin systems' time

    /// True when at least one part has a target (the per-part controller is used).
    [[nodiscard]] bool has_parts() const { return animation.target_ms > 0.0f || geometry.target_ms > 0.0f; }
};

/// What a tier needs of the hardware to be chosen automatically (entries of "tiers" given as objects).
struct TierRequirements {
    uint32_t min_cores = 0;              ///< logical CPU cores
    uint64_t min_gpu_memory_mb = 0;      ///< device-local GPU memory
    bool needs_hardware_gpu = false;     ///< a software rasteriser (lavapipe) does not qualify
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

/// True when value hysteresis widens `bound` (a condition's bound on `a`): finite bounds of the measured
/// attributes; not the discrete visible and tier; for occluded only bounds strictly between 0 and 1 (the
/// estimate), not 1 (certainly hidden: a character must not stay hidden while part of it shows).
[[nodiscard]] bool gets_value_band(LodAttribute a, float bound);

/// Sets box.lo_wide / hi_wide from lo / hi: the bounds that get a band (gets_value_band) move out by
/// `band` times their magnitude (the rule a character is on holds until it is crossed by the band).
void widen_box(ConditionBox& box, float band);

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
    SignificanceExpr significance;           ///< ranking for the budget and the caps (default formula)
    std::vector<std::string> tiers;          ///< tier names, index = value of the "tier" attribute
    std::vector<TierRequirements> tier_requirements;  ///< parallel to tiers
    bool tier_requirements_given = false;    ///< some tier of the file states requirements
    uint8_t default_tier = 0;                ///< tier used when the host names none (and hardware is unknown)
    bool tier_auto = false;                  ///< "default_tier": "auto": the host picks from its hardware
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
    /// True when some level (geometric or animation) has a cap.
    [[nodiscard]] bool has_caps() const;
    /// The GeomLod marshalled for level `level` (clamped to the last level).
    [[nodiscard]] GeomLod geom_lod(uint8_t level) const {
        const size_t i = std::min<size_t>(level, geom_levels.size() - 1);
        const GeomLevelDef& d = geom_levels[i];
        GeomLod g;
        g.level = static_cast<uint8_t>(i);
        g.method = d.method;
        g.layers = d.layers;
        g.subdiv_level = d.subdiv_level;
        g.theta_steps = d.theta_steps;
        g.phi_steps = d.phi_steps;
        g.geomorph_s = d.geomorph_s;
        g.simplify_error = d.simplify_error;
        return g;
    }
    /// The AnimLod marshalled for level `level` (clamped to the last level).
    [[nodiscard]] AnimLod anim_lod(uint8_t level) const {
        const size_t i = std::min<size_t>(level, anim_levels.size() - 1);
        const AnimLevelDef& d = anim_levels[i];
        AnimLod a;
        a.level = static_cast<uint8_t>(i);
        a.walk = d.walk;
        a.ik = d.ik;
        a.ik_iterations = d.ik_iterations;
        a.update_interval = d.update_interval;
        a.crossfade_s = d.crossfade_s;
        a.ik_tolerance = d.ik_tolerance;
        return a;
    }
};

/// Parses rule-file JSON `text`; `source_name` names it in errors. On failure the Error is the first
/// problem and, when `all_errors` is given, every problem found is appended there. Warnings go to
/// RuleTable::warnings. Comments (// and /* */) are allowed.
Result<RuleTable> parse_rules(std::string_view text, const std::string& source_name,
                              std::vector<Error>* all_errors = nullptr);

/// Reads the file at `path` and parses it with parse_rules (errors name `path`).
Result<RuleTable> load_rules(const std::string& path, std::vector<Error>* all_errors = nullptr);

}  // namespace aloha
