#pragma once
// The end of a flagged channel's fault, seen as its reading jumping onto its recovered value.
//
// Model. Channel j reads x_j (input `signal`); while it is flagged, the recovery hands on y_j
// (input `recovered`, fed from the tick before: previous_tick), x_j less the fault's estimate
// or the channel's virtual value. A fault that ends at tick t (an offset, a drift or a gain that
// stops, a frozen output that moves again) returns the reading to the true value at once, so
// x_j(t) leaves the line of its own last two samples and lands on the line of y_j's:
//
//   d0 = x(t) - 2 x(t-1) + x(t-2)     (H0: the fault goes on; white noise: variance 6 sigma^2 + q^2 / 2)
//   d1 = x(t) - 2 y(t-1) + y(t-2)     (H1: the reading rejoined what the recovery said it should be)
//
//   rejoined_j(t) = 1   when |d0| > b and |d1| <= b,   b = z sqrt(6 sigma_j^2 + q_j^2 / 2),
//
// judged only when j was flagged (input `fault`, from the tick before) on ticks t-1 and t-2, the
// five samples are finite, the tick is not guarded (input `guard`: a landing's transient, where
// loads themselves jump), and the tick before's d0 was within b (the two ticks after a jump hold
// it in their second differences, and y's line through it would match a jump that went on). z = Phi^-1(1 - alpha / 2), alpha = T / false_alarm_interval_s:
// a fault that goes on is called ended by a jump of the noise alone at about that rate, and
// only if the jump also lands on y's line. sigma and q are the reading's white noise and
// quantisation step (`ftsense calibrate`). d1's bound is the reading's own, which holds when y
// is the reading less a smooth estimate (an offset, a drift, a gain); where y is a virtual value
// (a frozen or unclassified fault, substituted), its own tick noise widens d1 and an end may be
// missed (left to the tests that flagged the channel: the conservative side). A fault whose estimate is smaller than b cannot be
// told ended from a noise jump, and an end within a guard is not seen: those are left to the
// tests that flagged the channel. The output is a one-tick pulse; a detector takes it as input
// `reset` (cusum_detector) to drop a flag it would otherwise hold until it could judge again
// (a pad's air row, held through its stance).
//
// With `residual` on (input `residual`: the channel's row of a constraint residual that its
// reading enters one for one, d r_j / d x_j = 1, as step_isolator takes it: sum_constraint_residual's
// rows, each loaded pad's row its group's sum residual), a jump onto y's line is the fault's end
// only if the row stepped with it: load that moves between channels (a foot rolling from heel to
// toe drops a pad by tens of newtons in a tick) moves the reading and leaves the sum. With
// W = step_window_ticks(T) (10 ms) and the row's window step D r = mean(r[t .. t+W-1]) -
// mean(r[t-W .. t-1]) over the jump at t,
//
//   rejoined_j(t+W-1) = 1   when the reading's test above held at t, |D r| > z s_r and
//                           |d0(t) - D r| <= z sqrt(6 sigma^2 + q^2 / 2 + s_r^2),
//
// s_r the row's fault-free window step (`residual_step_std`, `ftsense calibrate`'s window_step):
// the row moved, and by what the reading jumped (step_isolator's own test for a step). The pulse
// comes W - 1 ticks after the jump; the channel must stay flagged, and each window have at least
// half its samples of r finite and unguarded (each window's mean is over those: an end just after
// a landing's guard has the guard's last ticks in its window before). Each tick's jump is judged
// on its own windows, so a load's drop a few ticks before an end does not hide the end. Units: any, the reading's. Allocation-free: a ring of 2W residual
// samples per channel.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/calibration.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class RejoinDetector {
 public:
  static constexpr std::string_view name = "rejoin_detector";
  static constexpr std::string_view summary =
      "a flagged channel whose reading jumps onto its recovered value: its fault has ended (a one-tick pulse)";
  // For the config reference's port table and the schema (plugin.hpp): input guard is optional.
  static constexpr std::string_view example_params = R"([{}, {"guard": true, "residual": true}])";

  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
      {"residual_step_std", "residual", FaultFreeStatistic::window_step},
  });

  struct Params {
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    double false_alarm_interval_s = 86400.0;
    bool guard = false;
    bool residual = false;
    std::vector<double> residual_step_std{1.0};
    static void describe(ParamSchema<Params>& schema);
  };

  // Inputs guard and residual follow the three, in that order, when their params are on.
  enum Input : std::size_t { kSignal, kRecovered, kFault, kGuard };
  enum Output : std::size_t { kRejoined };

  RejoinDetector(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // b of the header, channel j.
  [[nodiscard]] double jump_bound(std::size_t j) const noexcept { return bound_[j]; }

 private:
  Ports ports_;
  bool guard_wired_;
  std::vector<double> bound_;
  // The tick before's reading and the one before it; the recovered value two ticks back; the
  // flag two ticks back (1 flagged).
  std::vector<double> x1_, x2_, y2_;
  std::vector<char> flagged2_;
  std::vector<char> smooth_before_;  // 1: the tick before's |d0| was within b
  // With `residual`: the row's last 2W samples per channel ([j * 2W + k], a ring; NaN where
  // guarded or not finite), and each channel's candidate jumps of the last W ticks ([j * W + k],
  // a ring: their d0, NaN where none), so a jump a few ticks after another is judged on its own
  // windows.
  bool residual_wired_ = false;
  std::size_t guard_input_ = kGuard, residual_input_ = kGuard;
  std::size_t window_ = 1;
  std::size_t ring_next_ = 0;
  std::vector<double> residual_ring_;
  std::vector<double> step_bound_, match_bound_;  // z s_r; z sqrt(6 sigma^2 + q^2 / 2 + s_r^2)
  std::size_t candidate_next_ = 0;
  std::vector<double> candidate_jump_;
};

}  // namespace ftsense::generic
