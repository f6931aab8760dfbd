#include "ftsense/generic/window_step_noise.hpp"

#include <algorithm>
#include <cmath>

namespace ftsense::generic {

namespace {
// The median of |N(0, 1)|: Phi^-1(3/4).
constexpr double kMedianOfAbsNormal = 0.6744897501960817;
}  // namespace

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
  std::vector<double> sorted = steps_;
  const std::size_t half = sorted.size() / 2;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(half), sorted.end());
  double median = sorted[half];
  if (sorted.size() % 2 == 0) {
    median = 0.5 * (median + *std::max_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(half)));
  }
  return median / kMedianOfAbsNormal;
}

}  // namespace ftsense::generic
