// Fidelity measurement for `aloha profile --fidelity`: how far the LOD picture is from the full-detail
// picture (screen-space deviation of the skin, image PSNR) and whether LOD switches pop.
#pragma once

#include "engine/core/result.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

namespace aloha::tool {

struct Session;

/// The part of a switch frame's image change inside the screen rectangles of the characters that made one
/// kind of switch (level `from` -> level `to`), each pixel counted once per kind, in the units of
/// FidelityFrame::changed_fraction (summed |RGB change| / (255 * 3 * every pixel of the frame)).
/// `change_before` is the same pixels' change one frame earlier (their ordinary motion): the excess
/// change - change_before estimates what the switch itself added.
struct SwitchPairChange {
    uint8_t from = 0;            ///< geometric level left
    uint8_t to = 0;              ///< geometric level entered
    uint32_t characters = 0;     ///< visible characters that made this switch this frame
    double change = 0;           ///< change inside their rectangles, this frame
    double change_before = 0;    ///< the same pixels' change on the frame before (0 on the first compared frame)
    std::vector<double> history; ///< the same pixels' change on up to kPopHistoryFrames frames before, most recent first
    std::vector<double> after;   ///< the same pixels' change on up to kPopHistoryFrames frames after, nearest first
                                 ///< (filled by fidelity_report from the later frames' later_changes)
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< the rectangle around those characters' rectangles (pixels)
};

/// How many frames before a switch its pixels' change is kept for the local pop test (pop_statistics.hpp).
inline constexpr size_t kPopHistoryFrames = 8;

/// One measured frame.
struct FidelityFrame {
    double mean_deviation_px = 0;      ///< mean over visible mesh vertices of |LOD - full| on screen
    double max_deviation_px = 0;       ///< largest such distance
    std::vector<double> mean_deviation_per_level;  ///< by geometric level (-1 when no character there)
    std::vector<double> max_deviation_per_level;
    /// The same vertices with the displayed level's springs at rest and no morph (ReferenceFrame's
    /// rest_deviation_sum): the levels' geometric error without the fat springs' own motion.
    double mean_rest_deviation_px = 0;
    std::vector<double> mean_rest_deviation_per_level;  ///< by geometric level (-1 when no character there)
    /// The displayed vertices against the full-detail body with its own fat springs moving (ReferenceFrame's
    /// moving_deviation_sum): the deviation with the fat motion on both sides. -1 when no character counted.
    double mean_moving_deviation_px = -1;
    std::vector<double> mean_moving_deviation_per_level;  ///< by geometric level (-1 when no character there)
    double psnr_db = 0;                ///< LOD render vs full-detail render
    /// The LOD render's character pixels over the reference's, and the shares covered within 1 px each way
    /// (image_compare.hpp's silhouette_coverage).
    double silhouette_ratio = 1.0, silhouette_covered = 1.0, silhouette_on_reference = 1.0;
    double changed_fraction = 0;       ///< mean absolute RGB change from the previous LOD frame (0..1)
    /// The same change in the full-detail reference picture (every visible character at the richest level,
    /// no switches): the picture's own motion on this frame, the control for the switch-frame tests.
    double reference_changed_fraction = 0;
    /// Mean over pixels and channels of |(lod - reference) now - (lod - reference) on the frame before|, as a
    /// fraction of full scale (image_compare.hpp's error_change); 0 on the first frame. What the camera and
    /// the characters' motion change in both pictures cancels: this is what the LOD alone changed.
    double error_change = 0;
    double error_change_in_switches = 0;  ///< the part of error_change inside this frame's switching characters' rectangles
    uint32_t switches = 0;             ///< visible characters that changed geometric level this frame
    uint32_t switches_without_rect = 0; ///< of those, the ones with no screen rectangle (crossing the near plane)
    std::vector<SwitchPairChange> by_pair;  ///< switch frames: the change attributed to each kind of switch
    /// This frame's change inside the rectangles of an earlier frame's switch: by_pair[pair] of the frame
    /// frames_back frames before (1..kPopHistoryFrames).
    struct LaterChange {
        uint32_t frames_back = 0;
        uint32_t pair = 0;
        double change = 0;
    };
    std::vector<LaterChange> later_changes;  ///< one per earlier switch kind still within kPopHistoryFrames
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
/// 95th percentile of ordinary frames, and the switch frames' change by kind of switch) and whether the
/// targets hold. `level_names` name the geometric levels in the by-kind figures (indices when short).
nlohmann::json fidelity_report(const std::vector<FidelityFrame>& frames, const std::vector<std::string>& level_names = {});

/// Console lines for a fidelity_report(): PSNR, deviation, the whole-frame and the local popping figures.
[[nodiscard]] std::string fidelity_summary(const nlohmann::json& report);

}  // namespace aloha::tool
