// The statistics a budget part steps on: how noisy its measured time is (the long-run standard
// deviation per frame, from batch means, so noise correlated over a few frames counts as much as it
// moves an average) and averages that carry their own standard error (the variance of the average
// as a fraction of one frame's). A part steps only when its time is outside the tolerance band by
// more than `confidence` standard errors of the average it steers on (part_budget.hpp).
#pragma once

#include <cstdint>

namespace aloha {

/// Long-run noise of a series, from the means of batches of `batch` frames: half the mean square
/// difference of successive batch means, times the batch length, is the variance one frame adds to
/// a long average (white noise: its variance; correlated over fewer frames than a batch: what it
/// really adds). Slower changes than two batches are not noise here: the controller follows them, and
/// its owner breaks the batches at a change it found (break_batches()).
class BudgetNoise {
public:
    /// Forgets everything.
    void reset();
    /// Feeds one frame's value `y` (ms); `batch` >= 1 frames a batch; the variance averages the
    /// batches with weight max(1 / batches seen, `weight`).
    void observe(double y, int batch, double weight);
    /// Moves everything fed so far by `ms` (a level switch's predicted effect: earlier frames are then
    /// compared as if measured with the new levels).
    void shift(double ms);
    /// Starts a new batch with no previous one: no difference spans a change of the time found
    /// elsewhere (a step, the smoothed time leaving the slow mean), which is not noise.
    void break_batches();
    /// Long-run standard deviation per frame (ms); 0 before two batches.
    [[nodiscard]] double sigma() const;
    /// Successive-batch differences seen.
    [[nodiscard]] int samples() const { return samples_; }

private:
    double sum_ = 0.0;       // this batch's sum
    int count_ = 0;          // frames in this batch
    int batch_ = 1;          // the batch length in use
    double last_mean_ = 0.0; // the previous batch's mean
    bool has_last_ = false;
    double var_ = 0.0;       // average of half squared successive differences (variance of one batch mean)
    int samples_ = 0;
};

/// A weighted average that knows its standard error: `factor` is its variance over one frame's
/// (white noise), 1 after one value, 1 / n for the plain mean of n values, a / (2 - a) for an EMA of
/// weight a in the long run.
struct TrackedMean {
    double mean = 0.0;    ///< the average (ms)
    double factor = 0.0;  ///< variance of `mean` / variance of one value; 0: empty
    /// True while it holds no value.
    [[nodiscard]] bool empty() const { return factor <= 0.0; }
    /// Takes `y` with weight `w` in (0, 1] (the first value with weight 1).
    void add(double y, double w);
    /// Takes `y` as one more value of a plain mean (weight factor / (1 + factor): 1 / (n + 1)).
    void add_to_mean(double y) { add(y, empty() ? 1.0 : factor / (1.0 + factor)); }
};

}  // namespace aloha
