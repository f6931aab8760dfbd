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
             "adds inputs correction c (per channel, the readings' unit) and substituted: each virtual value "
             "takes the others' readings as corrected, x_i - c_i, and a substituted one's load as unknown (a "
             "recovery's correction and substituted, one tick late through previous_tick), so a corrected fault "
             "of one channel leaves the others' virtual values; the residuals stay the readings' own");
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
                              "c_i, subtracted from reading i in the others' virtual values (not finite: as substituted)",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
    ports_.add_input(PortSpec{"substituted", channels_, std::string(kDimensionless),
                              "1 where reading i stands for nothing (its recovery is the virtual value): its load is "
                              "unknown to the others while it can carry load, 0 while it cannot",
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

bool SumConstraintResidual::load_known(std::span<const double> x, std::span<const double> correction,
                                       std::span<const double> substituted, std::size_t i,
                                       bool can_carry) const noexcept {
  // A reading that stands for nothing: 0 off the ground, else unknown (NaN counts as standing).
  if (!std::isfinite(correction[i]) || !(substituted[i] < 0.5)) return !can_carry;
  return std::isfinite(x[i]);
}

double SumConstraintResidual::load_of(std::span<const double> x, std::span<const double> correction,
                                      std::span<const double> substituted, std::size_t i) const noexcept {
  return std::isfinite(correction[i]) && substituted[i] < 0.5 ? x[i] - correction[i] : 0.0;
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
  const std::span<const double> substituted =
      correction_ ? io.in(loadable_ ? kSubstituted : kSubstituted - 1) : std::span<const double>{};
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t g = group_size_;
  for (std::size_t group = 0; group < groups_; ++group) {
    const std::size_t first = group * g;
    // NaN (unknown) counts as loadable: nothing is judged on a guess.
    const auto can_carry_load = [&](std::size_t i) { return !loadable_ || !(loadable[i] < 0.5); };
    // The finite readings' sum, how many are not finite and which one (when one): the residuals'.
    double finite_sum = 0.0;
    std::size_t missing = 0, missing_index = first;
    // What each channel carries as the others' virtual values take it: its reading less its
    // correction; unknown for a reading that is not finite or a correction that is not (its
    // reading stands for nothing), 0 for the latter while it cannot carry load.
    double known_loads = 0.0;
    std::size_t unknown = 0, unknown_index = first;
    for (std::size_t i = first; i < first + g; ++i) {
      if (std::isfinite(x[i])) {
        finite_sum += x[i];
      } else {
        ++missing;
        missing_index = i;
      }
      if (!correction_) continue;  // the virtual values are then the residuals' v
      if (load_known(x, correction, substituted, i, can_carry_load(i))) {
        known_loads += load_of(x, correction, substituted, i);
      } else {
        ++unknown;
        unknown_index = i;
      }
    }
    const double r = reference[group];
    const bool reference_known = std::isfinite(r);
    sum_residual[group] = missing == 0 && reference_known ? finite_sum - r : kNaN;
    std::size_t loaded = 0;
    for (std::size_t i = first; i < first + g; ++i) loaded += can_carry_load(i) ? 1 : 0;
    double* block = signature.data() + group * g * g;
    for (std::size_t i = first; i < first + g; ++i) {
      const bool can_carry = can_carry_load(i);
      row_weight[i] = can_carry ? 1.0 / static_cast<double>(loaded) : 1.0;  // loaded >= 1 here
      double v = 0.0;          // from the readings as they are: the residual's
      double corrected = 0.0;  // from the others' loads as corrected: the virtual value
      if (can_carry) {
        // The others' sum is known when nobody is missing, or when i is the one missing.
        const bool others_known = missing == 0 || (missing == 1 && missing_index == i);
        v = others_known && reference_known ? r - (finite_sum - (missing == 0 ? x[i] : 0.0)) : kNaN;
        const bool others_loads_known = unknown == 0 || (unknown == 1 && unknown_index == i);
        corrected = !correction_ ? v
                    : others_loads_known && reference_known
                        ? r - (known_loads - (unknown == 0 ? load_of(x, correction, substituted, i) : 0.0))
                        : kNaN;
      }
      virtual_value[i] = std::isnan(corrected) ? corrected : std::max(corrected, virtual_min_[i]);
      residual[i] = x[i] - v;
      double* row = block + (i - first) * g;
      for (std::size_t j = 0; j < g; ++j) row[j] = can_carry ? 1.0 : (j == i - first ? 1.0 : 0.0);
    }
  }
}

}  // namespace ftsense::generic
