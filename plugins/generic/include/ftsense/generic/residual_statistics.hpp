#pragma once
// Fault-free statistics of a residual, as the generic detectors need them (cusum_detector's
// centre, noise_std and correlation_time_s), estimated from samples of period T.
//
//   centre  c = mean(r)
//   sigma   = sqrt(mean((r - c)^2))
//   rho1    = sum((r_k - c)(r_{k-1} - c)) / sum((r_k - c)^2)   over consecutive finite pairs
//   tau_c   = -T / ln(rho1) for 0 < rho1 < 1 (a first-order process exp(-|t| / tau_c)); 0 when
//             rho1 <= 0 (white or anticorrelated: no memory to whiten)
//
// Non-finite samples are left out and break the pairs they belong to (a gap in the log is not a
// lag of one tick). Accumulates one sample at a time: calibrating a long log needs no storage.

#include <cstddef>

namespace ftsense::generic {

class ResidualStatistics {
 public:
  explicit ResidualStatistics(double sample_period_s) noexcept : period_s_(sample_period_s) {}

  void add(double r) noexcept;
  // The next sample does not follow the previous one (a reset, a new log).
  void break_sequence() noexcept { has_previous_ = false; }

  [[nodiscard]] std::size_t count() const noexcept { return n_; }
  [[nodiscard]] double centre() const noexcept;
  [[nodiscard]] double standard_deviation() const noexcept;
  [[nodiscard]] double lag_one_correlation() const noexcept;
  [[nodiscard]] double correlation_time_s() const noexcept;

 private:
  double period_s_;
  // Sums about a shift (the first sample) so that a large mean does not cancel digits.
  double shift_ = 0.0;
  std::size_t n_ = 0;
  double sum_ = 0.0, sum2_ = 0.0;
  // Pairs: sums of x_k, x_{k-1}, x_k x_{k-1}, x_k^2, x_{k-1}^2 (shifted).
  std::size_t pairs_ = 0;
  double pair_a_ = 0.0, pair_b_ = 0.0, pair_ab_ = 0.0, pair_aa_ = 0.0, pair_bb_ = 0.0;
  double previous_ = 0.0;
  bool has_previous_ = false;
};

}  // namespace ftsense::generic
