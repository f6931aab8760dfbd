#include "ftsense/generic/threshold_detector.hpp"

#include <cmath>

#include "ftsense/fault_type.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

void ThresholdDetector::Params::describe(ParamSchema<Params>& schema) {
  schema
      .add("thresholds", &Params::thresholds,
           "threshold tr_j per channel, in the unit of the signal; one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema.add("centers", &Params::centers,
             "centre c_j of channel j's fault-free band, in the unit of the signal (fault when "
             "|s_j - c_j| > tr_j); one value applies to all")
      .count_at_least(1);
  schema.add("on_delay_s", &Params::on_delay_s, "time |signal| must stay above tr_j to raise")
      .unit("s")
      .at_least(0.0).plausible(plausible::flag_delay_s());
  schema.add("off_delay_s", &Params::off_delay_s, "time |signal| must stay below tr_j to clear")
      .unit("s")
      .at_least(0.0).plausible(plausible::flag_delay_s());
  schema.add("warmup_s", &Params::warmup_s,
             "no threshold flags during this time after reset (initialisation transient)")
      .unit("s")
      .at_least(0.0).plausible(0.0, 600.0, "initial transients settle in seconds; ten minutes at most");
  schema.add("check_measured", &Params::check_measured,
             "also flag a channel invalid while its measured value is NaN or Inf (adds input measured)");
}

ThresholdDetector::ThresholdDetector(const Params& params, const StageContext& context)
    : sample_period_s_(context.sample_period_s()),
      on_delay_s_(params.on_delay_s),
      off_delay_s_(params.off_delay_s),
      warmup_s_(params.warmup_s),
      check_measured_(params.check_measured) {
  const std::size_t dim = context.wired_dim("signal", params.thresholds.size());
  if (params.thresholds.size() != 1 && params.thresholds.size() != dim) {
    throw ConfigError("/params/thresholds",
                      "has " + std::to_string(params.thresholds.size()) + " entries but the signal has " +
                          std::to_string(dim) + " channels; give one threshold per channel or one for all");
  }
  thresholds_.assign(dim, params.thresholds.front());
  if (params.thresholds.size() == dim) thresholds_ = params.thresholds;
  if (params.centers.size() != 1 && params.centers.size() != dim) {
    throw ConfigError("/params/centers",
                      "has " + std::to_string(params.centers.size()) + " entries but the signal has " +
                          std::to_string(dim) + " channels; give one centre per channel or one for all");
  }
  for (std::size_t j = 0; j < params.centers.size(); ++j) {
    if (!std::isfinite(params.centers[j])) {
      throw ConfigError("/params/centers/" + std::to_string(j), "is not a finite number");
    }
  }
  centers_.assign(dim, params.centers.front());
  if (params.centers.size() == dim) centers_ = params.centers;
  ports_.add_input(PortSpec{"signal", dim, std::string(kAnyUnit), "the evaluated signal s (e.g. filtered fault estimate)"}
                       .sized_by("as wired"));
  if (check_measured_) {
    ports_.add_input(PortSpec{"measured", dim, std::string(kAnyUnit), "the monitored sensor, checked for NaN/Inf (check_measured)"}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"fault", dim, std::string(kDimensionless), "1 when a fault is detected, else 0"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_type", dim, std::string(kDimensionless),
                     "fault type code (fault_type.hpp): none, unclassified or invalid"}.sized_by("as `signal`"));
  above_for_s_.assign(dim, 0.0);
  below_for_s_.assign(dim, 0.0);
  raised_.assign(dim, 0);
}

void ThresholdDetector::reset() noexcept {
  std::fill(above_for_s_.begin(), above_for_s_.end(), 0.0);
  std::fill(below_for_s_.begin(), below_for_s_.end(), 0.0);
  std::fill(raised_.begin(), raised_.end(), 0);
  started_ = false;
}

void ThresholdDetector::step(const StepIO& io) noexcept {
  const auto s = io.in(kSignal);
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  if (!started_) {
    start_time_s_ = io.time_s;
    started_ = true;
  }
  const bool warming_up = io.time_s - start_time_s_ < warmup_s_ - 0.5 * sample_period_s_;
  for (std::size_t j = 0; j < thresholds_.size(); ++j) {
    if (!std::isfinite(s[j]) || (check_measured_ && !std::isfinite(io.in(kMeasured)[j]))) {
      fault[j] = 1.0;
      type[j] = fault_code(FaultType::invalid);
      continue;
    }
    if (warming_up) {
      fault[j] = 0.0;
      type[j] = fault_code(FaultType::none);
      continue;
    }
    if (std::abs(s[j] - centers_[j]) > thresholds_[j]) {
      above_for_s_[j] += sample_period_s_;
      below_for_s_[j] = 0.0;
      // Half a tick of slack so that a delay of k ticks raises on the k-th tick, not the k+1-th.
      if (above_for_s_[j] >= on_delay_s_ - 0.5 * sample_period_s_) raised_[j] = 1;
    } else {
      below_for_s_[j] += sample_period_s_;
      above_for_s_[j] = 0.0;
      if (below_for_s_[j] >= off_delay_s_ - 0.5 * sample_period_s_) raised_[j] = 0;
    }
    fault[j] = raised_[j] ? 1.0 : 0.0;
    type[j] = fault_code(raised_[j] ? FaultType::unclassified : FaultType::none);
  }
}

}  // namespace ftsense::generic
