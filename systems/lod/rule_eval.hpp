// The rules system: evaluates the compiled knowledge base for a range of characters. The first rule
// whose condition holds fires; the rule a character is currently on is tested with its bounds
// widened by the hysteresis band (value hysteresis), so leaving it takes crossing by the band.
#pragma once

#include "components/lod.hpp"
#include "systems/lod/rule_table.hpp"

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// LodAttributes (+ current LodState for value hysteresis) -> LodRequest with the rule that fired.
struct RuleEvalJob {
    const RuleTable* table = nullptr;             ///< required, outlives Run()
    std::span<const LodAttributes> attributes;    ///< n entries
    std::span<const LodState> states;             ///< n entries, or empty (no value hysteresis)
    uint8_t tier = 0;                             ///< value of the "tier" attribute, < table->tiers.size()
    std::span<LodRequest> output;                 ///< n entries, written

    /// Checks table, sizes and tier; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Writes output[i] for every i (the last, unconditional rule fires when nothing else does,
    /// NaN attributes included). Requires Validate().
    void Run() const;
};

}  // namespace aloha
