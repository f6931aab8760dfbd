#pragma once
// Fault-free statistics of a residual, as the generic detectors need them (cusum_detector's
// centre, noise_std and correlation_time_s), estimated from samples of period T.
//
//   centre  c = mean(r)
//   sigma   = sqrt(mean((r - c)^2))
//   rho_L   = sum((r_k - c)(r_{k-L} - c)) / sum((r_k - c)^2)   over pairs L ticks apart within one
//             run of consecutive finite samples (the denominator over the same pairs), at the
//             dyadic lags L = 1, 2, 4, ... up to max_lag_s
//   tau_c   the e-folding time of the autocorrelation: with L1 < L2 the dyadic lags around the
//           first rho_L at or below 1/e, ln rho interpolated linearly in L between them gives
//           tau_c = L* T where ln rho(L*) = -1; when rho_1 is already at or below 1/e,
//           tau_c = -T / ln(rho_1) (0 when rho_1 <= 0: white or anticorrelated, no memory to
//           whiten); when no usable lag falls to 1/e, tau_c = -L T / ln(rho_L) at the largest
//           usable lag (a lower bound). A lag is usable once it has at least 2 L pairs.
//
// Why not -T / ln(rho_1) alone: it is exact for a first-order process (rho_L = exp(-L T / tau_c)
// at every lag, so every lag gives the same tau_c), but a smooth residual (a force residual
// low-passed: its samples change little from one tick to the next) has rho_1 near 1 however
// short its memory, and -T / ln(rho_1) then measures its smoothness, not its memory: a 0.1 Hz
// low-pass of a 100 Hz insole residual gave 17-160 s from lag one. A CUSUM whitened with that
// tau_c divides the residual's tick-to-tick changes by the sqrt(1 - rho^2) of a far smoother
// process and alarms many times as often as its target (CusumDetector.SmoothResidual... in
// tests/test_cusum_detector.cpp: 18 times). The e-folding time is the time the residual's memory lasts (for two
// cascaded first-order lags of tau it is 2.15 tau, against the 2 tau of the integral time scale
// that sets the false-alarm rate), and equals tau_c exactly for a first-order process.
//
// Non-finite samples are left out and break the pairs they belong to (a gap in the log is not a
// lag of L ticks). Accumulates one sample at a time with a ring of the last max_lag_s of samples
// (sized at construction; max_lag_s = 0: lag one only, no ring beyond it).

#include <array>
#include <cstddef>
#include <vector>

namespace ftsense::generic {

class ResidualStatistics {
 public:
  // Longest lag the correlation time looks at by default: cusum_detector's plausible range of
  // correlation_time_s ends there.
  static constexpr double kDefaultMaxLagS = 60.0;

  explicit ResidualStatistics(double sample_period_s, double max_lag_s = kDefaultMaxLagS);

  void add(double r) noexcept;
  // The next sample does not follow the previous one (a reset, a new log).
  void break_sequence() noexcept { run_ = 0; }

  [[nodiscard]] std::size_t count() const noexcept { return n_; }
  [[nodiscard]] double centre() const noexcept;
  [[nodiscard]] double standard_deviation() const noexcept;
  [[nodiscard]] double lag_one_correlation() const noexcept { return lag_correlation(0); }
  // rho_L at the dyadic lag L = 2^i (NaN when i is beyond max_lag_s or has fewer than 2 pairs).
  [[nodiscard]] double lag_correlation(std::size_t i) const noexcept;
  [[nodiscard]] double correlation_time_s() const noexcept;

 private:
  // Sums over the pairs (x_k, x_{k-L}) of one lag (shifted samples).
  struct LagSums {
    std::size_t pairs = 0;
    double a = 0.0, b = 0.0, ab = 0.0, aa = 0.0, bb = 0.0;
  };

  double period_s_;
  // Sums about a shift (the first sample) so that a large mean does not cancel digits.
  double shift_ = 0.0;
  std::size_t n_ = 0;
  double sum_ = 0.0, sum2_ = 0.0;
  std::vector<LagSums> lags_;      // lag 2^i at index i
  std::vector<double> history_;    // ring of the last samples (shifted); size a power of two
  std::size_t next_ = 0;           // where the next sample goes
  std::size_t run_ = 0;            // consecutive finite samples in the current sequence
};

}  // namespace ftsense::generic
