#include "ftsense/generic/cusum_detector.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/cusum_design.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

namespace {
// The least CUSUM threshold, in noise standard deviations: S >= h means S > 0.
constexpr double kLeastThreshold = 1e-9;
}  // namespace

void CusumDetector::Params::describe(ParamSchema<Params>& schema) {
  schema
      .add("noise_std", &Params::noise_std,
           "standard deviation sigma_j of the fault-free residual, in its unit; one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema
      .add("min_change", &Params::min_change,
           "smallest shift delta_j of the residual's mean to detect, in its unit (reference value "
           "k = delta / (2 sigma)); one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema.add("centers", &Params::centers,
             "centre c_j of the fault-free residual, in its unit; one value applies to all")
      .count_at_least(1);
  schema.add("correlation_time_s", &Params::correlation_time_s,
             "time constant tau_c of the fault-free residual's autocorrelation (0: white; about "
             "1 / (2 pi f_c) after a low-pass of cut-off f_c)")
      .unit("s")
      .at_least(0.0)
      .plausible(0.0, 60.0, "residuals decorrelate within milliseconds to seconds");
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between false alarms on one fault-free channel")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("warmup_s", &Params::warmup_s,
             "no flags during this time after reset (initialisation transient)")
      .unit("s")
      .at_least(0.0)
      .plausible(0.0, 600.0, "initial transients settle in seconds; ten minutes at most");
  schema.add("reset", &Params::reset,
             "adds input reset (one per channel; nonzero and finite: the change ended, S+ = S- = 0, the flag drops)");
}

CusumDetector::CusumDetector(const Params& params, const StageContext& context)
    : sample_period_s_(context.sample_period_s()), warmup_s_(params.warmup_s), reset_wired_(params.reset) {
  const std::size_t dim = context.wired_dim("residual", params.noise_std.size());
  const std::vector<double> noise_std = channel_values(params.noise_std, dim, "noise_std");
  const std::vector<double> min_change = channel_values(params.min_change, dim, "min_change");
  centers_ = channel_values(params.centers, dim, "centers");

  rho_ = params.correlation_time_s > 0.0 ? std::exp(-sample_period_s_ / params.correlation_time_s) : 0.0;
  samples_per_tick_ = (1.0 - rho_) / (1.0 + rho_);
  inv_innovation_std_ = 1.0 / std::sqrt((1.0 - rho_) * (1.0 + rho_));
  // Two sides, each with twice the interval, give the asked mean time between false alarms.
  const double arl_per_side = 2.0 * params.false_alarm_interval_s / sample_period_s_;
  if (!(arl_per_side > 2.0 && std::isfinite(inv_innovation_std_))) {
    throw ConfigError("/params/false_alarm_interval_s",
                      " = " + format_number(params.false_alarm_interval_s) + " s with correlation_time_s = " +
                          format_number(params.correlation_time_s) +
                          " s: the interval must span more than a tick and the correlation time be finite");
  }
  inv_std_.resize(dim);
  reference_.resize(dim);
  threshold_.resize(dim);
  for (std::size_t j = 0; j < dim; ++j) {
    inv_std_[j] = 1.0 / noise_std[j];
    reference_[j] = std::sqrt(samples_per_tick_) * 0.5 * min_change[j] / noise_std[j];
    // h = 0 when even that keeps false alarms rarer than asked (a change of many noise deviations:
    // one sample beyond k is a change); S >= h must then mean S > 0, so h is the least positive.
    threshold_[j] = std::max(cusum_threshold_for_arl(reference_[j], arl_per_side, cusum_overshoot(1.0)),
                             kLeastThreshold);
    if (!std::isfinite(threshold_[j])) {
      throw ConfigError("/params/min_change/" + std::to_string(j),
                        " = " + format_number(min_change[j]) + " is " +
                            format_number(min_change[j] / noise_std[j]) +
                            " noise standard deviations and gives no finite CUSUM threshold; give a finite "
                            "min_change and noise_std");
    }
  }
  ports_.add_input(PortSpec{"residual", dim, std::string(kAnyUnit), "the residual r (zero-mean when fault-free)"}
                       .sized_by("as wired"));
  if (reset_wired_) {
    ports_.add_input(PortSpec{"reset", dim, std::string(kDimensionless),
                              "nonzero and finite: another test says the change ended (S+ = S- = 0, the flag drops)"}
                         .sized_by("as `residual`"));
  }
  ports_.add_output(PortSpec{"fault", dim, std::string(kDimensionless), "1 while the channel is raised, else 0"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"fault_type", dim, std::string(kDimensionless),
                     "fault type code (fault_type.hpp): none or unclassified"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"statistic", dim, std::string(kDimensionless),
                     "max(S+, S-) / h: the evidence of a change, 1 raises the channel"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"direction", dim, std::string(kDimensionless),
                     "+1 when S+ leads (residual above its centre), -1 when S- leads, 0 when both are 0"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"judged", dim, std::string(kDimensionless),
                     "1 when the residual was finite this tick, 0 when the channel could not be judged"}
                        .sized_by("as `residual`"));
  upper_.assign(dim, 0.0);
  lower_.assign(dim, 0.0);
  previous_z_.assign(dim, 0.0);
  has_previous_.assign(dim, 0);
  raised_.assign(dim, 0);
}

void CusumDetector::reset() noexcept {
  std::fill(upper_.begin(), upper_.end(), 0.0);
  std::fill(lower_.begin(), lower_.end(), 0.0);
  std::fill(previous_z_.begin(), previous_z_.end(), 0.0);
  std::fill(has_previous_.begin(), has_previous_.end(), 0);
  std::fill(raised_.begin(), raised_.end(), 0);
  started_ = false;
}

void CusumDetector::step(const StepIO& io) noexcept {
  const auto r = io.in(kResidual);
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  const auto statistic = io.out(kStatistic);
  const auto direction = io.out(kDirection);
  const auto judged = io.out(kJudged);
  if (!started_) {
    start_time_s_ = io.time_s;
    started_ = true;
  }
  const bool warming_up = io.time_s - start_time_s_ < warmup_s_ - 0.5 * sample_period_s_;
  for (std::size_t j = 0; j < threshold_.size(); ++j) {
    const double h = threshold_[j];
    if (reset_wired_) {
      const double reset = io.in(kReset)[j];
      if (std::isfinite(reset) && reset != 0.0) {
        upper_[j] = lower_[j] = 0.0;
        raised_[j] = 0;
      }
    }
    if (!std::isfinite(r[j])) {
      judged[j] = 0.0;
      has_previous_[j] = 0;  // the whitening restarts with the next finite sample
    } else {
      judged[j] = 1.0;
      const double z = (r[j] - centers_[j]) * inv_std_[j];
      // A white residual needs no previous sample; a correlated one skips its first.
      const bool whitened = rho_ == 0.0 || has_previous_[j];
      const double e = (z - rho_ * previous_z_[j]) * inv_innovation_std_;
      previous_z_[j] = z;
      has_previous_[j] = 1;
      if (warming_up) {
        upper_[j] = lower_[j] = 0.0;
      } else if (whitened) {
        upper_[j] = std::max(0.0, upper_[j] + e - reference_[j]);
        lower_[j] = std::max(0.0, lower_[j] - e - reference_[j]);
        if (upper_[j] >= h || lower_[j] >= h) raised_[j] = 1;
        if (raised_[j]) {
          upper_[j] = std::min(upper_[j], h);
          lower_[j] = std::min(lower_[j], h);
          if (upper_[j] == 0.0 && lower_[j] == 0.0) raised_[j] = 0;
        }
      }
    }
    statistic[j] = std::max(upper_[j], lower_[j]) / h;
    direction[j] = upper_[j] > lower_[j] ? 1.0 : (lower_[j] > upper_[j] ? -1.0 : 0.0);
    fault[j] = raised_[j] ? 1.0 : 0.0;
    type[j] = fault_code(raised_[j] ? FaultType::unclassified : FaultType::none);
  }
}

}  // namespace ftsense::generic
