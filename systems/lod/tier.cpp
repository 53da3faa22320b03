#include "systems/lod/tier.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {

std::string describe(const HardwareInfo& hw) {
    std::string gpu = hw.gpu_name.empty() ? "no GPU" : hw.gpu_name;
    if (hw.software_rasterizer) gpu = "software rasteriser (" + gpu + ")";
    else gpu += ", " + std::to_string(hw.gpu_memory_mb) + " MiB";
    return gpu + ", " + std::to_string(hw.cores) + " cores";
}

}  // namespace

TierChoice auto_tier(const RuleTable& table, const HardwareInfo& hw) {
    TierChoice c;
    const size_t n = std::max<size_t>(1, table.tiers.size());
    if (table.tier_requirements_given) {
        for (size_t t = 0; t < n && t < table.tier_requirements.size(); ++t) {
            const TierRequirements& r = table.tier_requirements[t];
            const bool ok = hw.cores >= r.min_cores && hw.gpu_memory_mb >= r.min_gpu_memory_mb &&
                            !(r.needs_hardware_gpu && hw.software_rasterizer);
            if (ok || t == 0) c.tier = static_cast<uint8_t>(t);
        }
        c.reason = "auto (the tiers' requirements): " + describe(hw);
        return c;
    }
    int score = 1;
    if (hw.software_rasterizer || hw.cores < 4) score = 0;
    else if (hw.cores >= 8 && hw.gpu_memory_mb >= 4096) score = 2;
    c.tier = static_cast<uint8_t>(std::lround(score / 2.0 * static_cast<double>(n - 1)));
    c.reason = "auto: " + describe(hw);
    return c;
}

TierChoice resolve_tier(const RuleTable& table, int named, const HardwareInfo* hw) {
    const size_t n = std::max<size_t>(1, table.tiers.size());
    if (named >= 0 && static_cast<size_t>(named) < n) return {static_cast<uint8_t>(named), "named by the host"};
    if (table.tier_auto && hw) return auto_tier(table, *hw);
    TierChoice c;
    c.tier = static_cast<uint8_t>(std::min<size_t>(table.default_tier, n - 1));
    c.reason = table.tier_auto ? "auto, but the host gave no hardware facts: the richest tier"
                               : "the rule file's default_tier";
    return c;
}

}  // namespace aloha
