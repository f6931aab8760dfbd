#pragma once
// White measurement noise sigma and quantisation step q of a reading that also moves (a force
// under a walking load), from a fault-free log. For calibration, not for the per-tick path: it
// keeps every reading (one double per tick) and judges them at the end.
//
// Quantisation. The readings are on a lattice of step q when they have at least kMinLatticeSteps
// nonzero tick-to-tick changes |dx|, kOnLatticeShare of them or more whole multiples (within 1 %)
// of the smallest change that recurs (on 1 % of the changes or more; a driver's clamp to 0 puts a
// few changes off any lattice); q = sum |dx| / sum round(|dx| / that change) over those. Else
// q = 0: continuous, or quantised far finer than the noise (a log printed with fixed decimals,
// an ADC step under about sigma / 50), where no step recurs and quantisation does not matter.
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
// constant run that a reading in the middle of its step would leave before with probability
// 1 - kLongRunProbability (a foot clamped to 0 in the air) is left out of both statistics below.
// The bound follows r: from none (all pairs) to ln(kLongRunProbability) / ln P(stay in the
// middle), re-estimating r each time while it rises; at small r (under about 0.2) no run is that
// unlikely, none is left out, and a clamped foot pulls r low.
//   - Noise smaller than a step (r < 1/2): the second differences are mostly 0 and their median
//     says nothing. The noise shows in how often the reading changes from one tick to the next:
//     for a load whose place u within its step is uniform, two readings at the same u differ by
//     D = n_1 - n_2 ~ N(0, 2 r^2) steps and share a level with probability max(0, 1 - |D|) over
//     u, so P(change) = C(r) = 1 - erf(1 / (2 r)) + (2 r / sqrt(pi)) (1 - exp(-1 / (4 r^2))),
//     increasing from 0 (C ~ 2 r / sqrt(pi)) to 1 (1 - C ~ 1 / (2 r sqrt(pi))). r = C^-1(share of
//     changes). A load that moves adds changes (about |ds| / q per tick) and a steady load that
//     sits on a step boundary adds chatter: both make this estimate high (a clamped foot counted
//     at small r, below, makes it low).
//   - Noise of a step or more (that estimate >= 1/2): the second differences resolve it, and
//     quantisation adds its q^2 / 12 (Sheppard): sigma^2 = sigma_d2^2 - q^2 / 12, sigma_d2 from
//     the median of |d2| taken within its lattice bin (|d2| / q is a whole number: the median is
//     interpolated within the bin that holds it, [k - 1/2, k + 1/2) q, or [0, 1/2) q for k = 0).
//     The share of changes saturates there (1 - C ~ 0.28 / r), so a moving load would bias it.
// Non-finite readings and a reset break the sequence (no difference spans a break).

#include <cstddef>
#include <optional>
#include <vector>

namespace ftsense::generic {

class TickNoise {
 public:
  // Nonzero changes needed to call the readings a lattice (fewer: continuous).
  static constexpr std::size_t kMinLatticeSteps = 100;
  // A quantised reading at the middle of its step stays in one run this long with this chance.
  static constexpr double kLongRunProbability = 1e-3;
  // The share of the changes that must lie on the lattice.
  static constexpr double kOnLatticeShare = 0.95;

  void add(double x);
  void break_sequence();

  // The samples the noise estimate rests on: second differences (continuous) or consecutive
  // pairs outside long runs (quantised); 0 when there is nothing to judge.
  [[nodiscard]] std::size_t count() const;
  // sigma; NaN when count() is 0.
  [[nodiscard]] double standard_deviation() const;
  // q; 0 for continuous readings.
  [[nodiscard]] double resolution() const;

  // P(change) = C(r) of a quantised reading (header), in closed form; r > 0.
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
  [[nodiscard]] const Analysis& analysis() const;  // analyse(), kept until the next reading
  [[nodiscard]] double lattice_step() const;

  std::vector<double> readings_;  // finite readings; NaN marks a break
  mutable std::optional<Analysis> analysis_;
};

}  // namespace ftsense::generic
