#pragma once
// White measurement noise sigma and quantisation step q of a reading that also moves (a force
// under a walking load), from a fault-free log. For calibration, not for the per-tick path: it
// keeps every reading (one double per tick) and judges them at the end.
//
// Quantisation. The readings are on a lattice of step q when at least kMinLatticeSteps of their
// nonzero tick-to-tick changes |dx| are, 99 % of them or more, whole multiples of the smallest
// (within 1 % of it); q = sum |dx| / sum round(|dx| / min |dx|). Else q = 0 (continuous; a log
// printed with a fixed number of decimals is a lattice of that decimal, far finer than its noise,
// which changes nothing below).
//
// Continuous readings (q = 0): from the second differences, which remove the slow motion:
//   d2_k = x_k - 2 x_{k-1} + x_{k-2}        (variance 6 sigma^2 for white noise of std sigma)
//   sigma = median(|d2|) / (0.67449 sqrt(6))
// The median, not the RMS: the few ticks where the load itself turns sharply (a touchdown puts
// several newtons into d2 at 1 kHz) would inflate an RMS, and barely move the median. Three
// equal readings in a row give no d2: a continuous reading that repeats exactly (an unloaded foot
// clamped to 0) shows no noise there.
//
// Quantised readings (q > 0): x = q round((s + n) / q), n ~ N(0, sigma^2), r = sigma / q. A
// reading that stays in one constant run for kLongRunTicks or more (a foot clamped to 0 in the
// air, a quiet sensor on a steady load) is left out of both statistics below: it is no evidence
// of the noise either way.
//   - Noise smaller than a step (r < 1/2): the second differences are mostly 0 and their median
//     says nothing. The noise shows in how often the reading changes from one tick to the next:
//     for a load whose place u within its step is uniform, P(change) = C(r) = 1 - E_u[sum_l
//     p_l(u)^2], p_l(u) = Phi((l + 1/2 - u) / r) - Phi((l - 1/2 - u) / r) the chance to read
//     level l; C increases from 0 (C ~ 2 r / sqrt(pi) for small r) to 1. r = C^-1(share of
//     changes). A load that moves adds changes (about |ds| / q per tick) and a steady load that
//     sits on a step boundary adds chatter: both make this estimate high, up to twice sigma on a
//     simulated walk at r = 0.1, never low.
//   - Noise of a step or more (that estimate >= 1/2): the second differences resolve it, and
//     quantisation adds its q^2 / 12 (Sheppard): sigma^2 = sigma_d2^2 - q^2 / 12, sigma_d2 from
//     the median of |d2| taken within its lattice bin (|d2| / q is a whole number: the median is
//     interpolated within the bin that holds it, [k - 1/2, k + 1/2) q, or [0, 1/2) q for k = 0).
//     The share of changes saturates there (1 - C ~ 0.28 / r), so a moving load would bias it.
// Non-finite readings and a reset break the sequence (no difference spans a break).

#include <cstddef>
#include <vector>

namespace ftsense::generic {

class TickNoise {
 public:
  // Nonzero changes needed to call the readings a lattice (fewer: continuous).
  static constexpr std::size_t kMinLatticeSteps = 100;
  // A quantised reading at the middle of its step stays in one run this long with this chance.
  static constexpr double kLongRunProbability = 1e-3;

  void add(double x);
  void break_sequence();

  // The samples the noise estimate rests on: second differences (continuous) or consecutive
  // pairs outside long runs (quantised); 0 when there is nothing to judge.
  [[nodiscard]] std::size_t count() const;
  // sigma; NaN when count() is 0.
  [[nodiscard]] double standard_deviation() const;
  // q; 0 for continuous readings.
  [[nodiscard]] double resolution() const;

  // P(change) = C(r) of a quantised reading (header), by midpoint quadrature over u; r > 0.
  [[nodiscard]] static double change_probability(double noise_over_step);
  // r = C^-1(p), p in [0, 1): by bisection on log r within [1e-4, 1e4].
  [[nodiscard]] static double noise_over_step(double change_probability);

 private:
  struct Analysis {
    double resolution = 0.0;
    double sigma = 0.0;
    std::size_t count = 0;
  };
  [[nodiscard]] Analysis analyse() const;
  [[nodiscard]] double lattice_step() const;

  std::vector<double> readings_;  // finite readings; NaN marks a break
};

}  // namespace ftsense::generic
