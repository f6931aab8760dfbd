#include "ftsense/generic/signature_isolator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

namespace {
// A column this small (in whitened units squared) sees no fault: not a candidate.
constexpr double kMinColumnNorm = 1e-12;
}  // namespace

void SignatureIsolator::Params::describe(ParamSchema<Params>& schema) {
  schema.add("group_size", &Params::group_size,
             "channels per group g (one residual each); the wired channels are the groups one after another")
      .at_least(1)
      .at_most(64)
      .required();
  schema
      .add("residual_noise_std", &Params::residual_noise_std,
           "standard deviation sigma_i of each fault-free residual, in its unit; one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between wrong isolations the margin chi^2_1(1 - T / interval) aims at")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
}

SignatureIsolator::SignatureIsolator(const Params& params, const StageContext& context)
    : group_size_(static_cast<std::size_t>(params.group_size)) {
  const std::size_t dim = context.wired_dim("residual", group_size_);
  if (dim % group_size_ != 0) {
    throw ConfigError("/params/group_size", " = " + std::to_string(group_size_) + " does not divide the " +
                                                std::to_string(dim) + " wired residuals into whole groups");
  }
  groups_ = dim / group_size_;
  const std::vector<double> noise = channel_values(params.residual_noise_std, dim, "residual_noise_std");
  inv_std_.resize(dim);
  for (std::size_t i = 0; i < dim; ++i) inv_std_[i] = 1.0 / noise[i];
  const double alpha = context.sample_period_s() / params.false_alarm_interval_s;
  if (!(alpha > 0.0 && alpha < 1.0)) {
    throw ConfigError("/params/false_alarm_interval_s", " = " + format_number(params.false_alarm_interval_s) +
                                                            " s must be longer than the sample period");
  }
  const double z = normal_quantile(1.0 - 0.5 * alpha);
  margin_ = z * z;
  ports_.add_input(PortSpec{"residual", dim, std::string(kAnyUnit), "the residuals r, group after group"}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"alarm", dim, std::string(kDimensionless),
                            "1 while a detector raises residual i (nonzero: raised; 0 or NaN: not)"}
                       .sized_by("as `residual`"));
  ports_.add_input(PortSpec{"signature", dim * group_size_, std::string(kDimensionless),
                            "each group's g x g signature S (row i: residual i, S_ij = d r_i / d x_j), row-major, "
                            "group after group"}
                       .sized_by("residuals x group_size"));
  ports_.add_output(PortSpec{"fault", dim, std::string(kDimensionless), "1 while the channel is blamed, else 0"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"fault_type", dim, std::string(kDimensionless),
                             "fault type code (fault_type.hpp): unclassified when blamed, else none"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"fault_estimate", dim, std::string(kAnyUnit),
                             "f_j, the blamed channel's fault size in the residuals' unit; 0 otherwise"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"cannot_judge", dim, std::string(kDimensionless),
                             "1 while the channel's group is raised and no channel is singled out"}
                        .sized_by("as `residual`"));
  blamed_.assign(groups_, -1);
  estimate_.assign(groups_, 0.0);
}

void SignatureIsolator::reset() noexcept {
  std::fill(blamed_.begin(), blamed_.end(), -1);
  std::fill(estimate_.begin(), estimate_.end(), 0.0);
}

void SignatureIsolator::step(const StepIO& io) noexcept {
  const auto r = io.in(kResidual);
  const auto alarm = io.in(kAlarm);
  const auto signature = io.in(kSignature);
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  const auto estimate = io.out(kFaultEstimate);
  const auto cannot = io.out(kCannotJudge);
  const std::size_t g = group_size_;
  for (std::size_t group = 0; group < groups_; ++group) {
    const std::size_t first = group * g;
    bool raised = false;
    bool known = true;
    double zz = 0.0;
    for (std::size_t i = first; i < first + g; ++i) {
      raised = raised || (std::isfinite(alarm[i]) && alarm[i] != 0.0);
      const double z = r[i] * inv_std_[i];
      known = known && std::isfinite(z);
      zz += std::isfinite(z) ? z * z : 0.0;
    }
    if (!raised) blamed_[group] = -1;  // nothing raised: every channel of the group is free again
    // The GLR of each channel: what its best fault size leaves of |z|^2.
    long best = -1, second = -1;
    double best_left = std::numeric_limits<double>::infinity(), second_left = best_left, best_size = 0.0;
    if (raised && known) {
      const double* block = signature.data() + group * g * g;
      for (std::size_t j = 0; j < g; ++j) {
        double tt = 0.0, tz = 0.0;
        bool finite = true;
        for (std::size_t i = 0; i < g; ++i) {
          const double t = block[i * g + j] * inv_std_[first + i];
          finite = finite && std::isfinite(t);
          tt += t * t;
          tz += t * r[first + i] * inv_std_[first + i];
        }
        if (!finite || !(tt > kMinColumnNorm)) continue;
        const double left = zz - tz * tz / tt;
        if (static_cast<long>(j) == blamed_[group]) estimate_[group] = tz / tt;
        if (left < best_left) {
          second = best;
          second_left = best_left;
          best = static_cast<long>(j);
          best_left = left;
          best_size = tz / tt;
        } else if (left < second_left) {
          second = static_cast<long>(j);
          second_left = left;
        }
      }
      // A new verdict only when nobody is blamed yet: once a channel explains the group, its
      // fault excites the neighbours' residuals and they are not blamed for it.
      if (blamed_[group] < 0 && best >= 0 && (second < 0 || second_left - best_left >= margin_)) {
        blamed_[group] = best;
        estimate_[group] = best_size;
      }
    }
    for (std::size_t j = 0; j < g; ++j) {
      const bool is_blamed = blamed_[group] == static_cast<long>(j);
      fault[first + j] = is_blamed ? 1.0 : 0.0;
      type[first + j] = fault_code(is_blamed ? FaultType::unclassified : FaultType::none);
      estimate[first + j] = is_blamed ? estimate_[group] : 0.0;
      cannot[first + j] = raised && blamed_[group] < 0 ? 1.0 : 0.0;
    }
  }
}

}  // namespace ftsense::generic
