#pragma once
// Constraint residual "a sensor that carries no load reads zero", per channel.
//
//   r_j = x_j - z_j   while channel j cannot carry load (input loadable_j < 1/2: a contact flag
//                     of 0, or a contact probability below one half) and has not been
//                     able to for at least settle_s (the load leaves with the contact, and the
//                     sensor's own dynamics settle)
//   r_j = NaN         otherwise: not judged (a loaded sensor's value is for other relations)
//
// x is the reading (any unit), z_j the reading of an unloaded healthy sensor (`zero`, default 0).
// Downstream, a detector that holds its state on NaN (cusum_detector) judges channel j only in
// the intervals where physics fixes its value: a foot's pad in swing, an unloaded insole cell.
// `loadable` comes from kinematics (heights above the ground) or a contact plan, never from the
// readings judged (the independence rule applies: it is a virtual estimate of the readings' state).

#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class UnloadedReadingResidual {
 public:
  static constexpr std::string_view name = "unloaded_reading_residual";
  static constexpr std::string_view summary =
      "reading - zero while a channel cannot carry load (settled), else NaN: not judged";

  struct Params {
    double settle_s = 0.02;
    std::vector<double> zero{0.0};
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kSignal, kLoadable };
  enum Output : std::size_t { kResidual };

  UnloadedReadingResidual(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  std::vector<double> zero_;
  std::vector<double> unloaded_for_s_;
  double settle_s_;
  double sample_period_s_;
};

}  // namespace ftsense::generic
