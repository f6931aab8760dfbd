#include "ftsense/generic/physical_range_detector.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/generic/quantity_bounds.hpp"

namespace ftsense::generic {

void PhysicalRangeDetector::Params::describe(ParamSchema<Params>& schema) {
  schema.add("floor", &Params::floor,
             "the least value the measured quantity can take (0 for a force pad that is pressed, never pulled), "
             "in the reading's unit; empty: none; one value applies to all");
  schema.add("ceiling", &Params::ceiling,
             "the greatest value the measured quantity can take, in the reading's unit; empty: none; one value "
             "applies to all");
  describe_reading_noise(schema);
  schema.add("noise_margin", &Params::noise_margin,
             "a healthy noise is known within this factor: the bound is taken at noise_margin sigma")
      .at_least(1.0)
      .plausible(1.0, 5.0, "1 (the noise known exactly) to a few");
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between false alarms on one healthy channel that sits at a bound (sets z)")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
}

void PhysicalRangeDetector::Params::validate(Diagnostics& diag, std::string_view path) const {
  if (floor.empty() && ceiling.empty()) {
    diag.error(std::string(path) + "/floor",
               "neither floor nor ceiling is given, so no reading is out of range; give the least value the "
               "quantity can take (0 N for a pressed force pad), its greatest, or both");
  }
}

PhysicalRangeDetector::PhysicalRangeDetector(const Params& params, const StageContext& context) {
  const std::size_t dim = context.wired_dim("signal", params.noise_std.size());
  const QuantityBounds bounds = quantity_bounds(params.floor, params.ceiling, dim);
  const auto noise = channel_values(params.noise_std, dim, "noise_std");
  const auto resolution = channel_values(params.resolution, dim, "resolution");
  check_noise_margin(params.noise_margin);
  const double z = two_sided_z(false_alarm_per_tick(context.sample_period_s(), params.false_alarm_interval_s));
  lowest_.resize(dim);
  highest_.resize(dim);
  for (std::size_t j = 0; j < dim; ++j) {
    const double b = reading_margin(z, params.noise_margin, noise[j], resolution[j]);
    lowest_[j] = bounds.floor[j] - b;  // -inf where none
    highest_[j] = bounds.ceiling[j] + b;
  }
  ports_.add_input(
      PortSpec{"signal", dim, std::string(kAnyUnit), "the readings x_j", PortRole::measured}.sized_by("as wired"));
  ports_.add_output(PortSpec{"fault", dim, std::string(kDimensionless),
                             "1 on a tick whose reading is beyond floor - b or ceiling + b, else 0"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_type", dim, std::string(kDimensionless),
                             "fault type code (fault_type.hpp): unclassified while flagged, else none"}
                        .sized_by("as `signal`"));
}

void PhysicalRangeDetector::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto fault = io.out(kFault);
  const auto fault_type = io.out(kFaultType);
  for (std::size_t j = 0; j < lowest_.size(); ++j) {
    // NaN fails both comparisons: not flagged here.
    const bool beyond = x[j] < lowest_[j] || x[j] > highest_[j];
    fault[j] = beyond ? 1.0 : 0.0;
    fault_type[j] = fault_code(beyond ? FaultType::unclassified : FaultType::none);
  }
}

}  // namespace ftsense::generic
