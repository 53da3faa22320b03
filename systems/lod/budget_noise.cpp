#include "systems/lod/budget_noise.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

void BudgetNoise::reset() { *this = BudgetNoise(); }

void BudgetNoise::observe(double y, int batch, double weight) {
    if (!std::isfinite(y)) return;
    batch = std::max(1, batch);
    if (batch != batch_) sum_ = 0.0, count_ = 0, has_last_ = false, batch_ = batch;  // a new length: new batches
    sum_ += y;
    if (++count_ < batch_) return;
    const double mean = sum_ / batch_;
    sum_ = 0.0, count_ = 0;
    if (has_last_) {
        // Independent batch means of variance v differ with variance 2 v.
        const double d = mean - last_mean_;
        ++samples_;
        var_ += std::max(1.0 / samples_, weight) * (0.5 * d * d - var_);
    }
    last_mean_ = mean, has_last_ = true;
}

void BudgetNoise::break_batches() {
    sum_ = 0.0, count_ = 0, has_last_ = false;
}

void BudgetNoise::shift(double ms) {
    sum_ += ms * count_;
    last_mean_ += ms;
}

double BudgetNoise::sigma() const { return samples_ > 0 ? std::sqrt(std::max(0.0, var_) * batch_) : 0.0; }

void TrackedMean::add(double y, double w) {
    if (empty()) w = 1.0;
    mean += w * (y - mean);
    factor = (1.0 - w) * (1.0 - w) * factor + w * w;
}

}  // namespace aloha
