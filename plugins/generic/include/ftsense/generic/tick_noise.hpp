#pragma once
// White measurement noise of a reading that also moves (a force under a walking load), from
// its second differences, which remove the slow motion:
//
//   d2_k = x_k - 2 x_{k-1} + x_{k-2}        (variance 6 sigma^2 for white noise of std sigma)
//   sigma = median(|d2|) / (0.67449 sqrt(6))
//
// The median, not the RMS: the few ticks where the load itself turns sharply (a touchdown puts
// several newtons into d2 at 1 kHz) would inflate an RMS, and barely move the median. Three
// equal readings in a row give no d2: a reading that repeats exactly (an unloaded foot reading 0,
// a sensor quantised coarser than its noise) shows no noise there, and counting its zeros would
// pull the median down by the share of such stretches. A reading that only repeats has no d2 at
// all (sigma NaN: its noise is not seen).
// Non-finite readings and a reset break the sequence (the next two readings start it again).
// Stores |d2| (one double per tick): for calibration, not for the per-tick path.

#include <cstddef>
#include <vector>

namespace ftsense::generic {

class TickNoise {
 public:
  void add(double x);
  void break_sequence() noexcept { held_ = 0; }

  [[nodiscard]] std::size_t count() const noexcept { return abs_d2_.size(); }
  // sigma; NaN before the first second difference that counts.
  [[nodiscard]] double standard_deviation() const;

 private:
  double previous_ = 0.0, before_ = 0.0;  // x_{k-1}, x_{k-2}
  int held_ = 0;                          // consecutive finite readings held, up to 2
  std::vector<double> abs_d2_;
};

}  // namespace ftsense::generic
