#include "ftsense/generic/guard_step_noise.hpp"

#include <algorithm>
#include <cmath>

#include "ftsense/generic/sample_median.hpp"
#include "ftsense/generic/window_step_noise.hpp"

namespace ftsense::generic {

GuardStepNoise::GuardStepNoise(double sample_period_s)
    : window_(step_window_ticks(sample_period_s)), before_(window_, 0.0) {}

void GuardStepNoise::add(double r, bool guarded) {
  if (!std::isfinite(r)) {
    // Inside a guard no sample is used: a gap there leaves the guard measurable (as the
    // isolator still judges it); before or after it, it breaks the window.
    if (phase_ != Phase::inside || !guarded) break_sequence();
    return;
  }
  if (guarded) {
    if (phase_ == Phase::outside) {
      before_known_ = filled_ >= window_;
      if (before_known_) {
        double sum = 0.0;
        for (const double s : before_) sum += s;
        before_mean_ = sum / static_cast<double>(window_);
      }
    } else if (phase_ == Phase::after) {
      before_known_ = false;  // a guard again before W ticks after the last: neither is measured
    }
    phase_ = Phase::inside;
    filled_ = 0;
    return;
  }
  if (phase_ == Phase::inside) {
    phase_ = Phase::after;
    after_sum_ = 0.0;
    after_count_ = 0;
  }
  before_[next_] = r;
  next_ = next_ + 1 == window_ ? 0 : next_ + 1;
  filled_ = std::min(filled_ + 1, window_);
  if (phase_ == Phase::after) {
    after_sum_ += r;
    if (++after_count_ == window_) {
      if (before_known_) steps_.push_back(std::abs(after_sum_ / static_cast<double>(window_) - before_mean_));
      phase_ = Phase::outside;
    }
  }
}

void GuardStepNoise::break_sequence() noexcept {
  filled_ = 0;
  next_ = 0;
  phase_ = Phase::outside;
  before_known_ = false;
}

double GuardStepNoise::standard_deviation() const {
  if (steps_.empty()) return std::nan("");
  return sample_median(steps_) / kMedianAbsStandardNormal;
}

}  // namespace ftsense::generic
