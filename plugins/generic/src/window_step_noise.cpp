#include "ftsense/generic/window_step_noise.hpp"

#include <algorithm>
#include <cmath>

#include "ftsense/generic/sample_median.hpp"

namespace ftsense::generic {

std::size_t step_window_ticks(double sample_period_s) noexcept {
  if (!(sample_period_s > 0.0)) return 1;
  const double ticks = std::round(kStepWindowS / sample_period_s);
  return ticks >= 1.0 ? static_cast<std::size_t>(std::min(ticks, 1e6)) : 1;
}

WindowStepNoise::WindowStepNoise(double sample_period_s)
    : window_(step_window_ticks(sample_period_s)), run_(2 * window_, 0.0) {}

void WindowStepNoise::add(double s) {
  if (!std::isfinite(s)) {
    break_sequence();
    return;
  }
  run_[next_] = s;
  next_ = next_ + 1 == run_.size() ? 0 : next_ + 1;
  filled_ = std::min(filled_ + 1, run_.size());
  if (filled_ < run_.size()) return;
  // next_ is now the oldest sample: the first W are the window before, the last W the one after.
  double before = 0.0;
  double after = 0.0;
  for (std::size_t k = 0; k < window_; ++k) {
    before += run_[(next_ + k) % run_.size()];
    after += run_[(next_ + window_ + k) % run_.size()];
  }
  steps_.push_back(std::abs(after - before) / static_cast<double>(window_));
}

void WindowStepNoise::break_sequence() noexcept {
  filled_ = 0;
  next_ = 0;
}

double WindowStepNoise::standard_deviation() const {
  if (steps_.empty()) return std::nan("");
  return sample_median(steps_) / kMedianAbsStandardNormal;
}

}  // namespace ftsense::generic
