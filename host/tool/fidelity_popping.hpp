// The popping part of the fidelity report: the switch frames' change by kind of switch, the local pop
// tests (pop_statistics.hpp) over the switches' own pixels, and the switch frames' change of the LOD's
// error against the reference.
#pragma once

#include "host/tool/fidelity.hpp"
#include "host/tool/stats.hpp"
#include "host/tool/switch_frames.hpp"

#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <vector>

namespace aloha::tool {

/// `measured` with each switch's change in the frames after it (SwitchPairChange::after, nearest first)
/// gathered from those frames' later_changes; entries pointing before the first frame are ignored.
[[nodiscard]] std::vector<FidelityFrame> with_changes_after(const std::vector<FidelityFrame>& measured);

/// The switch frames' change by kind of switch: per kind, the frames and characters, the change inside
/// its rectangles and the excess over the frame before (summed and largest); and the worst switch frame's
/// own breakdown. Levels are named by `names` where it has them.
[[nodiscard]] nlohmann::json popping_by_kind(const std::vector<FidelityFrame>& frames, const std::vector<std::string>& names);

/// The local pop tests over every kind of switch on every switch frame, one event each: against the
/// frames before (the object's own figures) and, under "centred", against the frames before and after.
/// Requires each SwitchPairChange's `after` filled (fidelity_report does it).
[[nodiscard]] nlohmann::json local_popping(const std::vector<FidelityFrame>& frames, const std::vector<std::string>& names);

/// A whole-frame switch bar over one per-frame series (`series[k]` frame k's change from frame k - 1,
/// `switch_frame[k]` whether frame k holds a switch; frame 0, with no change, is left out): the ordinary
/// and switch frames' statistics and the detrended, ranked test (switch_frames.hpp).
struct SwitchBar {
    SeriesStats ordinary, at_switch;
    SwitchFrameTest detrended;
};
[[nodiscard]] SwitchBar switch_bar(std::span<const double> series, std::span<const uint8_t> switch_frame);
/// The bar's verdict: the switch frames' largest no more than the ordinary p95; null when there are switch
/// frames but no ordinary one to compare with.
[[nodiscard]] nlohmann::json switch_bar_verdict(const SwitchBar& bar);
/// The detrended test as JSON: frames on each side, the residuals' largest and p95, p, and the verdict
/// (p >= 0.05; null when one side is empty).
[[nodiscard]] nlohmann::json detrended_json(const SwitchFrameTest& test);

/// The switch frames whose whole change is over `ordinary_p95`, and how many of them stay over with the
/// change inside their switching characters' rectangles taken out (every kind's rectangles, overlaps
/// subtracted twice: never less than the switches' own share). A frame still over without those pixels
/// is over for something else than its switches (the camera, the crowd's own motion); a frame with a
/// switching character that has no rectangle (switches_without_rect) never counts so. Lists the frames over
/// (index, change, the change in the switching rectangles), at most 20. Frame 0 is left out.
[[nodiscard]] nlohmann::json switch_frames_over_p95(const std::vector<FidelityFrame>& frames, double ordinary_p95);

/// The whole-frame switch bar read on the change of the LOD's error against the full-detail reference
/// (FidelityFrame::error_change), where the camera's and the characters' own motion cancel: the switch
/// frames' largest error change against the ordinary frames' 95th percentile (null when one side is
/// empty), the same detrended and ranked (switch_frames.hpp), and the share of the switch frames' error
/// change that lies inside the switching characters' rectangles. Frame 0, with no frame before, is left out.
[[nodiscard]] nlohmann::json error_change_popping(const std::vector<FidelityFrame>& frames);

/// The control for the whole-frame switch bar: the same bar and detrended test read on the full-detail
/// reference picture's own change (FidelityFrame::reference_changed_fraction) with the LOD run's switch
/// frames, where no switch happens. Switch frames that rank high there too coincide with the picture's own
/// motion (say the occlusion rule switching a character as the one in front walks across it), not with
/// anything a switch drew. Also the detrended test on the LOD picture's change less the reference's
/// ("raw_less_control"): what the LOD picture changed beyond the picture's own motion, frame by frame.
/// Frame 0, with no frame before, is left out.
[[nodiscard]] nlohmann::json reference_change_control(const std::vector<FidelityFrame>& frames);

}  // namespace aloha::tool
