#pragma once
// Isolation of a single-channel fault by its signature on a family of residuals (analytical
// redundancy: which residuals a fault excites, and how much).
//
// Model. Channels are grouped (`group_size` g channels each, as wired: a foot's sensors), and each
// group has one residual per channel, r_i (any unit, zero-mean when fault-free, standard deviation
// sigma_i, `residual_noise_std`). A fault of size f on channel j of the group shifts the group's
// residuals by f s_j, s_j the j-th column of the group's signature matrix S (g x g, input
// `signature`, row i = residual i, S_ij = d r_i / d x_j; it may change tick by tick: a
// leave-one-out regression gives S = I - C while its relations hold, the identity of a sensor's
// own residual when they do not). On the whitened residual z_i = r_i / sigma_i and columns
// t_j = s_j / sigma, the least-squares fault size and what it leaves are
//
//   f_j = <t_j, z> / <t_j, t_j>,      E_j = |z|^2 - <t_j, z>^2 / <t_j, t_j>    (the GLR of "channel j").
//
// While any residual of the group is raised (input `alarm`, from a detector on r), the channel
// with the least E_j is blamed when the runner-up leaves at least chi^2_1(1 - alpha) more
// (alpha = T / false_alarm_interval_s: the single-fault hypotheses are told apart as surely as a
// detector keeps its false-alarm rate); otherwise nobody is blamed and the group's channels are
// reported `cannot_judge` (collinear sensors, whose signatures are nearly parallel, are not
// told apart by guessing). A blamed channel stays blamed while any residual of its group is
// raised, and is released when none is: the healthy neighbours whose residuals its fault
// excites are never blamed for it. Columns with <t_j, t_j> below 1e-12 (a channel no residual
// sees this tick) are not candidates.
//
// Outputs per channel: fault (1 blamed), fault_type (unclassified when blamed: the type is a
// classifier's work), fault_estimate f_j of the blamed channel in the residual's unit (0
// otherwise), cannot_judge (1 while its group is raised and no channel is singled out).
// Allocation-free: the work vectors are sized at construction.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class SignatureIsolator {
 public:
  static constexpr std::string_view name = "signature_isolator";
  static constexpr std::string_view summary =
      "blames the one channel whose fault signature explains the raised residuals (GLR), else cannot judge";
  static constexpr std::string_view example_params = R"({"group_size": 1})";

  // `ftsense calibrate` measures each fault-free residual's RMS.
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"residual_noise_std", "residual", FaultFreeStatistic::rms},
  });

  struct Params {
    int group_size = 1;
    std::vector<double> residual_noise_std{1.0};
    double false_alarm_interval_s = 86400.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kResidual, kAlarm, kSignature };
  enum Output : std::size_t { kFault, kFaultType, kFaultEstimate, kCannotJudge };

  SignatureIsolator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // chi^2_1(1 - alpha): how much more the runner-up must leave unexplained.
  [[nodiscard]] double isolation_margin() const noexcept { return margin_; }

 private:
  Ports ports_;
  std::size_t group_size_;
  std::size_t groups_;
  std::vector<double> inv_std_;
  double margin_;
  std::vector<long> blamed_;  // per group: the blamed channel within it, -1 for none
  std::vector<double> estimate_;  // per group: the blamed channel's fault size
};

}  // namespace ftsense::generic
