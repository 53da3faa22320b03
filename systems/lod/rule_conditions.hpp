// Internal to the rule loader: compiles a rule's "when" JSON into disjunctive normal form, a list
// of boxes (one closed interval per attribute slot), reporting every problem with its JSON path.
#pragma once

#include "engine/core/result.hpp"
#include "systems/lod/rule_table.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace aloha::lod_detail {

/// A conjunction of closed intervals [lo[k], hi[k]]; empty when some lo[k] > hi[k].
struct RawBox {
    std::array<float, kBoxSlots> lo;
    std::array<float, kBoxSlots> hi;
};

/// The box that accepts everything (every slot [-inf, +inf]).
[[nodiscard]] RawBox full_box();
/// True when `b` accepts nothing (some lo > hi).
[[nodiscard]] bool box_empty(const RawBox& b);
/// True when `b` accepts everything.
[[nodiscard]] bool box_full(const RawBox& b);
/// True when every point of `inner` is inside `outer`.
[[nodiscard]] bool box_contains(const RawBox& outer, const RawBox& inner);

/// Where compile_condition reports problems and how it names tiers.
struct ConditionContext {
    const std::string* source = nullptr;             ///< file name for errors
    const std::vector<std::string>* tiers = nullptr; ///< tier names (index = value)
    std::vector<Error>* errors = nullptr;            ///< problems are appended here
};

/// Most boxes one rule may expand to (guards against "not"/"any" blow-up).
inline constexpr size_t kMaxBoxesPerRule = 64;

/// Compiles condition object `when` at JSON path `path` into `out` (an OR of boxes, empty boxes
/// dropped). Returns false when a problem was reported; `out` is then unspecified.
bool compile_condition(const nlohmann::json& when, const std::string& path, const ConditionContext& ctx,
                       std::vector<RawBox>* out);

}  // namespace aloha::lod_detail
