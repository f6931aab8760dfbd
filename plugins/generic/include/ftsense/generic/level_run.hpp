#pragma once
// How long a healthy quantised reading may stay on one level: a sensor of white noise sigma and
// quantisation step q keeps a reading at its level's centre (where it stays most) on that level
// with probability p = erf(q / (2 sqrt(2) sigma)) per tick, so a run of n ticks on one level has
// probability p^n, and the run a healthy reading makes with probability alpha is
//
//   n = ln alpha / ln p       (0 for a continuous reading, p = 0: no noise repeats a value)
//
// (5 N steps under 2 N of noise: p = 0.79, 77 ticks at alpha = 1e-3 / 86400). A run longer than n
// is a stuck output's, not noise's: contact_force_fdi's and signal_validator's frozen tests.
// Where q is far coarser than sigma, p -> 1 and n grows without bound (p is held below 1 so the
// logarithm stays finite): the reading alone cannot tell a stuck sensor from a steady load.

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ftsense::generic {

// n for resolution q >= 0, noise sigma > 0 and 0 < alpha < 1.
[[nodiscard]] inline double healthy_level_run_ticks(double resolution, double noise_std, double alpha) noexcept {
  const double stay = std::erf(resolution / (2.0 * std::numbers::sqrt2 * noise_std));
  return stay > 0.0 ? std::log(alpha) / std::log(std::min(stay, 1.0 - 1e-15)) : 0.0;
}

}  // namespace ftsense::generic
