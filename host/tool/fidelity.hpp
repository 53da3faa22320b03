// Fidelity measurement for `aloha profile --fidelity`: how far the LOD picture is from the full-detail
// picture (screen-space deviation of the skin, image PSNR) and whether LOD switches pop.
#pragma once

#include "engine/core/result.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <vector>

namespace aloha::tool {

struct Session;

/// One measured frame.
struct FidelityFrame {
    double mean_deviation_px = 0;      ///< mean over visible mesh vertices of |LOD - full| on screen
    double max_deviation_px = 0;       ///< largest such distance
    std::vector<double> mean_deviation_per_level;  ///< by geometric level (-1 when no character there)
    std::vector<double> max_deviation_per_level;
    double psnr_db = 0;                ///< LOD render vs full-detail render
    double changed_fraction = 0;       ///< mean absolute RGB change from the previous LOD frame (0..1)
    uint32_t switches = 0;             ///< visible characters that changed geometric level this frame
};

/// Renders each frame a second time at full detail and compares. Lives inside a profile session.
class FidelityProbe {
public:
    /// Sets up the reference target and topologies. Requires the session to render.
    static Result<std::unique_ptr<FidelityProbe>> create(Session& session);
    virtual ~FidelityProbe() = default;
    /// Measures the frame the World just produced.
    virtual Result<FidelityFrame> measure() = 0;
};

/// Summary: per-level mean/max deviation, PSNR stats, popping (largest change at switch frames vs the
/// 95th percentile of ordinary frames) and whether the targets hold.
nlohmann::json fidelity_report(const std::vector<FidelityFrame>& frames);

}  // namespace aloha::tool
