#pragma once
// Guard after a change of state: 1 for hold_s after an input channel changes, else 0.
//
//   g_j = 1  on the h = round(hold_s / T) ticks from a tick t_c on which some channel i in
//            scope(j) changed (|s_i(t_c) - s_i(t_c - T)| > tolerance, or s_i(t_c) not finite:
//            unknown counts as a change, so nothing is judged on a guess); h >= 1 (a hold of
//            under half a tick is a config error)
//   g_j = 0  otherwise
//   scope(j) = every channel (`scope` any) or j alone (`scope` own).
//
// The input is a state that other signals follow abruptly: contact flags from kinematics, a gait
// phase. The output marks the ticks where a signal's own motion is not resolved by the sample
// rate (a foot's landing logged at 200 Hz is one sample off its neighbours, as a spike is, and
// every foot's load shifts when one lands), for a validator's `guard` input. hold_s is the time
// such a transient takes to die out, in seconds, so the same config holds at any rate.

#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class ChangeGuard {
 public:
  static constexpr std::string_view name = "change_guard";
  static constexpr std::string_view summary =
      "1 for hold_s after a state input (contact flags, a gait phase) changes: the transient's ticks";

  enum class Scope { any, own };
  struct Params {
    double hold_s = 0.15;
    double tolerance = 0.0;
    Scope scope = Scope::any;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kState };
  enum Output : std::size_t { kGuard };

  ChangeGuard(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  std::vector<double> previous_;
  std::vector<std::size_t> since_change_;  // ticks since the channel last changed, up to hold_ticks_
  bool started_ = false;
  std::size_t hold_ticks_ = 1;
  double tolerance_;
  Scope scope_;
};

}  // namespace ftsense::generic
