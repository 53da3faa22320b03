// Hardware tiers: which of a rule file's tiers a host runs at. A file names one ("default_tier") or
// says "auto", and then the tier follows from the hardware: the rasteriser (software or not), the CPU
// core count and the GPU memory, by the tiers' own requirements or a built-in policy.
#pragma once

#include "systems/lod/rule_table.hpp"

#include <cstdint>
#include <string>

namespace aloha {

/// What the host knows about its hardware.
struct HardwareInfo {
    unsigned cores = 0;                 ///< logical CPU cores the systems may use
    uint64_t gpu_memory_mb = 0;         ///< device-local memory of the GPU (0 = unknown / none)
    bool software_rasterizer = true;    ///< rendering on the CPU (lavapipe/llvmpipe) or no GPU at all
    std::string gpu_name;               ///< device name, for messages ("" = none)
};

/// The tier chosen and why.
struct TierChoice {
    uint8_t tier = 0;                   ///< index into RuleTable::tiers
    std::string reason;                 ///< e.g. "auto: software rasteriser (llvmpipe), 2 cores"
};

/// Richest tier of `table` that `hw` qualifies for. With requirements in the file (tiers written as
/// objects), the richest whose min_cores, min_gpu_memory_mb and needs_hardware_gpu all hold (the first
/// tier always qualifies). Without: a score of 0 (software rasteriser, or fewer than 4 cores), 1, or 2
/// (at least 8 cores and 4 GiB of GPU memory) mapped onto the tier list evenly.
[[nodiscard]] TierChoice auto_tier(const RuleTable& table, const HardwareInfo& hw);

/// The tier a host runs at: `named` (an index from the command line or scene, when >= 0) first, then
/// the file's named default_tier, then auto_tier() when the file says "auto" and `hw` is given, else
/// the file's fallback (the richest tier for "auto").
[[nodiscard]] TierChoice resolve_tier(const RuleTable& table, int named, const HardwareInfo* hw);

}  // namespace aloha
