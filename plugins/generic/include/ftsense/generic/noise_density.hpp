#pragma once
// Low-frequency noise density of a fault-free signal r (a residual e = measured - virtual):
//
//   q = sqrt(mean_i(n_i T m_i^2)),   m_i the mean of the n_i finite samples of r in the i-th
//                                    window of w seconds (n_i T = w for a whole window),
//
// so that the mean of r over w seconds has standard deviation q / sqrt(w) [unit sqrt(s)]; for
// white noise of standard deviation sigma sampled every T seconds, q = sigma sqrt(T). The means
// are taken about 0 (a fault-free residual is zero-mean; a bias counts as noise). Windows are
// consecutive, w / T samples each; non-finite samples are left out of their window (which then
// weighs by the time its samples cover), and a window without a finite sample does not count.
// One sample at a time, no storage.

#include <cstddef>

namespace ftsense::generic {

class NoiseDensity {
 public:
  NoiseDensity(double sample_period_s, double window_s) noexcept;

  void add(double r) noexcept;
  // The next sample starts a new window (a reset, a new log): a partial window is dropped.
  void break_sequence() noexcept;

  [[nodiscard]] std::size_t windows() const noexcept { return windows_; }
  // q; NaN before the first whole window.
  [[nodiscard]] double density() const noexcept;

 private:
  std::size_t samples_per_window_;
  double period_s_;
  std::size_t in_window_ = 0;  // samples (finite or not) in the current window
  std::size_t finite_ = 0;
  double sum_ = 0.0;
  std::size_t windows_ = 0;
  double sum_weighted_sq_means_ = 0.0;  // sum of n_i T m_i^2
};

}  // namespace ftsense::generic
