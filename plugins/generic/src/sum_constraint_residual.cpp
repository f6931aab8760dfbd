#include "ftsense/generic/sum_constraint_residual.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>

#include "ftsense/channel_values.hpp"

namespace ftsense::generic {

void SumConstraintResidual::Params::describe(ParamSchema<Params>& schema) {
  schema.add("group_size", &Params::group_size,
             "channels per reference g; the wired channels are the groups one after another (0: all of them, "
             "one reference)")
      .at_least(0)
      .at_most(64);
  schema.add("loadable", &Params::loadable,
             "adds input loadable (1 while a channel can carry load, by kinematics): a channel that cannot "
             "has virtual value 0 and is judged on its own reading");
  schema.add("correction", &Params::correction,
             "adds input correction c (per channel, the readings' unit): each virtual value takes the others' "
             "readings as corrected, x_i - c_i (a recovery's correction, one tick late through previous_tick), "
             "so a corrected fault of one channel leaves the others' virtual values; the residuals stay the "
             "readings' own");
  schema.add("virtual_min", &Params::virtual_min,
             "the least value the virtual sensor may take, in the signal's unit (a force sensor that only "
             "pushes: 0); empty: none; one value applies to all");
}

SumConstraintResidual::SumConstraintResidual(const Params& params, const StageContext& context)
    : loadable_(params.loadable), correction_(params.correction) {
  // Unwired (the docs' port table): one group of the given size, or of two.
  channels_ = context.wired_dim("signal", params.group_size > 0 ? static_cast<std::size_t>(params.group_size) : 2);
  group_size_ = params.group_size > 0 ? static_cast<std::size_t>(params.group_size) : channels_;
  if (channels_ % group_size_ != 0) {
    throw ConfigError("/params/group_size", " = " + std::to_string(group_size_) + " does not divide the " +
                                                std::to_string(channels_) + " wired channels into whole groups");
  }
  if (group_size_ < 2) {
    throw ConfigError("/params/group_size", ": a group of " + std::to_string(group_size_) +
                                                " channel leaves no other channel to estimate it from; give 2 or more");
  }
  groups_ = channels_ / group_size_;
  virtual_min_ = channel_values(params.virtual_min, channels_, "virtual_min", true);
  for (double& m : virtual_min_) {
    if (!std::isfinite(m)) m = -std::numeric_limits<double>::infinity();
  }
  ports_.add_input(PortSpec{"signal", channels_, std::string(kAnyUnit), "the readings x, group after group",
                            PortRole::measured}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"reference", groups_, std::string(kAnyUnit),
                            "R_G, what each group's readings sum to (e.g. the total vertical force)",
                            PortRole::virtual_estimate}
                       .sized_by("channels / group_size"));
  if (loadable_) {
    ports_.add_input(PortSpec{"loadable", channels_, std::string(kDimensionless),
                              "1 while channel j can carry load, 0 while it cannot (below 1/2: cannot; NaN: can)",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  if (correction_) {
    // A virtual estimate for the independence rule: a correction fed back from the readings'
    // recovery depends on them (docs/architecture.md, "The plugin contract").
    ports_.add_input(PortSpec{"correction", channels_, std::string(kAnyUnit),
                              "c_i, subtracted from reading i in the others' virtual values (non-finite: 0)",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"virtual", channels_, std::string(kAnyUnit),
                             "leave-one-out estimate R_G - sum of the group's other readings, less their "
                             "corrections with `correction` (0 while j cannot carry load)",
                             PortRole::signal, /*leave_one_out=*/true}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"residual", channels_, std::string(kAnyUnit),
                             "x_j - virtual_j: the group's sum residual while j can carry load, x_j while it cannot"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"signature", channels_ * group_size_, std::string(kDimensionless),
                             "each group's g x g signature S_ij = d residual_i / d x_j, row-major, group after group "
                             "(signature_isolator's input)"}
                        .sized_by("channels x group_size"));
  ports_.add_output(PortSpec{"sum_residual", groups_, std::string(kAnyUnit), "sum_G x - R_G per group"}
                        .sized_by("channels / group_size"));
  ports_.add_output(PortSpec{"row_weight", channels_, std::string(kDimensionless),
                             "w_i: 1 / L for the L residuals of a group's channels that can carry load (copies of one "
                             "sum), 1 for a channel judged on its own reading (signature_isolator's input)"}
                        .sized_by("as `signal`"));
}

void SumConstraintResidual::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto reference = io.in(kReference);
  const auto virtual_value = io.out(kVirtual);
  const auto residual = io.out(kResidual);
  const auto signature = io.out(kSignature);
  const auto sum_residual = io.out(kSumResidual);
  const auto row_weight = io.out(kRowWeight);
  const std::span<const double> loadable = loadable_ ? io.in(kLoadable) : std::span<const double>{};
  const std::span<const double> correction =
      correction_ ? io.in(loadable_ ? kCorrection : kCorrection - 1) : std::span<const double>{};
  const auto correction_of = [&](std::size_t i) {
    return correction_ && std::isfinite(correction[i]) ? correction[i] : 0.0;
  };
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t g = group_size_;
  for (std::size_t group = 0; group < groups_; ++group) {
    const std::size_t first = group * g;
    // The finite readings' sum, how many are not finite and which one (when one).
    double finite_sum = 0.0;
    double correction_total = 0.0;  // the finite readings' corrections
    std::size_t missing = 0, missing_index = first;
    for (std::size_t i = first; i < first + g; ++i) {
      if (std::isfinite(x[i])) {
        finite_sum += x[i];
        correction_total += correction_of(i);
      } else {
        ++missing;
        missing_index = i;
      }
    }
    const double r = reference[group];
    const bool reference_known = std::isfinite(r);
    sum_residual[group] = missing == 0 && reference_known ? finite_sum - r : kNaN;
    // NaN (unknown) counts as loadable: nothing is judged on a guess.
    const auto can_carry_load = [&](std::size_t i) { return !loadable_ || !(loadable[i] < 0.5); };
    std::size_t loaded = 0;
    for (std::size_t i = first; i < first + g; ++i) loaded += can_carry_load(i) ? 1 : 0;
    double* block = signature.data() + group * g * g;
    for (std::size_t i = first; i < first + g; ++i) {
      const bool can_carry = can_carry_load(i);
      row_weight[i] = can_carry ? 1.0 / static_cast<double>(loaded) : 1.0;  // loaded >= 1 here
      double v = 0.0;
      if (can_carry) {
        // The others' sum is known when nobody is missing, or when i is the one missing.
        const bool others_known = missing == 0 || (missing == 1 && missing_index == i);
        v = others_known && reference_known ? r - (finite_sum - (missing == 0 ? x[i] : 0.0)) : kNaN;
      }
      // The virtual value takes the others as corrected; the residual stays the readings' own, so
      // the detectors and the signatures see the faults as they are.
      // R - sum_{k != i} (x_k - c_k) = v + sum_{k != i} c_k.
      const double others_correction =
          can_carry ? correction_total - (std::isfinite(x[i]) ? correction_of(i) : 0.0) : 0.0;
      const double corrected_v = v + others_correction;
      virtual_value[i] = std::isnan(corrected_v) ? corrected_v : std::max(corrected_v, virtual_min_[i]);
      residual[i] = x[i] - v;
      double* row = block + (i - first) * g;
      for (std::size_t j = 0; j < g; ++j) row[j] = can_carry ? 1.0 : (j == i - first ? 1.0 : 0.0);
    }
  }
}

}  // namespace ftsense::generic
