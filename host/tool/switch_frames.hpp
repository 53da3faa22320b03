// The whole-frame switch comparison with the scene's own trend taken out, and judged over all switch
// frames at once.
//
// The fidelity report's whole-frame bar compares the largest switch frame's image change with the
// ordinary frames' 95th percentile. Two things make it fail when switches add nothing: a trend (a camera
// coming down raises every frame's change; crowd_10k frames 140-179 rise from 0.0249 to 0.0290 while the
// ordinary frames are the first nine), and the largest of many (the largest of 20 switch frames exceeds
// the p95 of 19 others in about 64% of runs). Here each frame's change is taken relative to its own
// neighbours (the median of up to `half_window` frames each side), which a smooth trend cancels, and the
// switch frames' residuals as a whole are compared with the ordinary frames' by a one-sided rank test:
// if the switches add nothing, the labels are exchangeable, and the chance that the switch frames' mean
// rank is at least the one seen is the p-value (from random relabellings, a fixed seed).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace aloha::tool {

/// Each value's difference from the median of its neighbours, as many on each side (up to `half_window`,
/// fewer near the ends), itself left out: a linear trend gives 0 everywhere. The first and last values,
/// with no neighbour on one side, give NaN (left out of the test).
[[nodiscard]] std::vector<double> detrended(std::span<const double> values, size_t half_window);

/// P(the mean rank of `x` among x and y together >= the one seen) when the labels are exchangeable,
/// estimated from `relabellings` random relabellings drawn with `seed` (ties share their mean rank); the
/// estimate counts the observed labelling, so it is never below 1 / (relabellings + 1). 1 when x or y
/// is empty.
[[nodiscard]] double rank_test_greater(std::span<const double> x, std::span<const double> y, size_t relabellings = 20000,
                                       uint64_t seed = 1);

/// The whole-frame comparison over a run's frames (`change[k]` the image change of frame k from k - 1,
/// `switch_frame[k]` whether frame k holds a switch; frame 0, with no change, is left out, and so are the
/// first and last compared frames, which detrended() cannot centre).
struct SwitchFrameTest {
    size_t switch_frames = 0, ordinary_frames = 0;
    double switch_residual_max = 0;    ///< largest detrended change of a switch frame
    double ordinary_residual_p95 = 0;  ///< the ordinary frames' 95th percentile of the same
    double p_value = 1;                ///< rank_test_greater(switch residuals, ordinary residuals)
    bool no_worse = true;              ///< p_value >= 0.05 (or nothing to compare)
};
[[nodiscard]] SwitchFrameTest switch_frame_test(std::span<const double> change, std::span<const uint8_t> switch_frame,
                                                size_t half_window = 4);

}  // namespace aloha::tool
