#include "ftsense/generic/noise_density.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ftsense::generic {

NoiseDensity::NoiseDensity(double sample_period_s, double window_s) noexcept
    : samples_per_window_(static_cast<std::size_t>(std::max(1.0, std::round(window_s / sample_period_s)))),
      period_s_(sample_period_s) {}

void NoiseDensity::add(double r) noexcept {
  if (std::isfinite(r)) {
    sum_ += r;
    ++finite_;
  }
  if (++in_window_ < samples_per_window_) return;
  if (finite_ > 0) {
    const double mean = sum_ / static_cast<double>(finite_);
    sum_weighted_sq_means_ += static_cast<double>(finite_) * period_s_ * mean * mean;
    ++windows_;
  }
  break_sequence();
}

void NoiseDensity::break_sequence() noexcept {
  in_window_ = 0;
  finite_ = 0;
  sum_ = 0.0;
}

double NoiseDensity::density() const noexcept {
  if (windows_ == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(sum_weighted_sq_means_ / static_cast<double>(windows_));
}

}  // namespace ftsense::generic
