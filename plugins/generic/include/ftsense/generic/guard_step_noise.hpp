#pragma once
// How much a fault-free signal r steps across a guard, from a log. A guard is a run of ticks on
// which a guard input is nonzero (change_guard over a landing's transient: the readings and the
// reference move within a tick as no model of them says); what a fault that begins inside it
// leaves is judged afterwards, by how far r moved from before the guard to after it:
//
//   Delta_g = mean(r over the W finite unguarded ticks after the guard)
//           - mean(r over the W finite unguarded ticks just before it began)
//   sigma_g = median(|Delta_g|) / 0.67449      (the standard deviation of a normal Delta_g)
//   W       = step_window_ticks(T)             (10 ms, as window_step_noise.hpp)
//
// On a walk, sigma_g measures how much the total force's error (the reference of a sum residual)
// differs before and after a landing: larger than a window step inside a stance (window_step),
// whose two windows are 10 ms apart, and it is that difference a fault's onset inside a guard
// must exceed (step_isolator.hpp). A guard is counted when W finite unguarded ticks precede it
// and W follow it before the next guard; a non-finite sample inside a guard is skipped (no
// sample there is used), one outside it, or a reset, breaks the sequence (the guard next to it is
// not counted). For calibration, not for the per-tick path:
// it keeps one |Delta_g| per guard and judges them at the end.

#include <cstddef>
#include <vector>

namespace ftsense::generic {

class GuardStepNoise {
 public:
  explicit GuardStepNoise(double sample_period_s);

  // One tick: the sample and whether the guard holds it.
  void add(double r, bool guarded);
  void break_sequence() noexcept;

  [[nodiscard]] std::size_t window_ticks() const noexcept { return window_; }
  // The guards measured so far.
  [[nodiscard]] std::size_t count() const noexcept { return steps_.size(); }
  // sigma_g; NaN when count() is 0.
  [[nodiscard]] double standard_deviation() const;

 private:
  enum class Phase { outside, inside, after };
  std::size_t window_;
  std::vector<double> before_;  // the last W finite unguarded samples (a ring)
  std::size_t next_ = 0;        // where the next sample goes in before_
  std::size_t filled_ = 0;      // finite unguarded samples in a row, up to W
  Phase phase_ = Phase::outside;
  bool before_known_ = false;   // W samples preceded the guard being measured
  double before_mean_ = 0.0;
  double after_sum_ = 0.0;
  std::size_t after_count_ = 0;
  std::vector<double> steps_;   // |Delta_g|
};

}  // namespace ftsense::generic
