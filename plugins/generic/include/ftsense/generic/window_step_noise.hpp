#pragma once
// How much a fault-free signal s steps between two consecutive windows of W ticks, from a log:
//
//   Delta_n = mean(s[n-W+1 .. n]) - mean(s[n-2W+1 .. n-W])       (every n with 2W finite samples)
//   sigma   = median(|Delta_n|) / 0.67449                        (the standard deviation of a
//                                                                 normal Delta with that median)
//   W       = max(1, round(kStepWindowS / T))                    (step_window_ticks: 10 ms)
//
// The step a sensor fault makes is judged against this (step_isolator.hpp): white noise of std
// sigma_w gives sigma = sigma_w sqrt(2 / W), and a load or reference that moves adds its change
// over 2W ticks, which is the part a rate change alters little. The median, not the RMS: a
// landing's impact, a few ticks in a stride, would set an RMS and barely moves the median (the
// isolator does not judge those ticks: its guard). For calibration, not for the per-tick path:
// it keeps one |Delta| per tick and judges them at the end. Non-finite samples and a reset break
// the sequence (no window spans a break).

#include <cstddef>
#include <vector>

namespace ftsense::generic {

// The window of a step: long against a tick at 200 Hz (2 ticks) so one sample's noise averages
// down, short against a load's motion (a foot's load moves little in 10 ms outside a landing).
inline constexpr double kStepWindowS = 0.01;

// W for a sample period T > 0: max(1, round(kStepWindowS / T)), at most 10^6 (1 for T <= 0).
[[nodiscard]] std::size_t step_window_ticks(double sample_period_s) noexcept;

class WindowStepNoise {
 public:
  explicit WindowStepNoise(double sample_period_s);

  void add(double s);
  void break_sequence() noexcept;

  [[nodiscard]] std::size_t window_ticks() const noexcept { return window_; }
  // The steps measured so far.
  [[nodiscard]] std::size_t count() const noexcept { return steps_.size(); }
  // sigma; NaN when count() is 0.
  [[nodiscard]] double standard_deviation() const;

 private:
  std::size_t window_;
  std::vector<double> run_;    // the last 2W finite samples, oldest first once full (a ring)
  std::size_t next_ = 0;       // where the next sample goes in run_
  std::size_t filled_ = 0;     // finite samples since the last break, up to 2W
  std::vector<double> steps_;  // |Delta_n|
};

}  // namespace ftsense::generic
