#include "ftsense/generic/rejoin_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/generic/jump_noise.hpp"

namespace ftsense::generic {

void RejoinDetector::Params::describe(ParamSchema<Params>& schema) {
  describe_jump_noise(schema);
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between jumps of the noise alone beyond the bound (sets z)")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("guard", &Params::guard,
             "adds input guard (nonzero: the tick is not judged, e.g. change_guard over a landing's transient)");
}

RejoinDetector::RejoinDetector(const Params& params, const StageContext& context) : guard_wired_(params.guard) {
  const std::size_t dim = context.wired_dim("signal", params.noise_std.size());
  const double alpha = false_alarm_per_tick(context.sample_period_s(), params.false_alarm_interval_s);
  const double z = two_sided_z(alpha);
  const auto noise = channel_values(params.noise_std, dim, "noise_std");
  const auto resolution = channel_values(params.resolution, dim, "resolution");
  bound_.resize(dim);
  for (std::size_t j = 0; j < dim; ++j) {
    bound_[j] = z * std::sqrt(second_difference_variance(noise[j], resolution[j]));
  }
  ports_.add_input(PortSpec{"signal", dim, std::string(kAnyUnit), "the readings x_j"}.sized_by("as wired"));
  ports_.add_input(PortSpec{"recovered", dim, std::string(kAnyUnit),
                            "the recovery's value y_j of the tick before (previous_tick), in the readings' unit"}
                       .sized_by("as `signal`"));
  ports_.add_input(PortSpec{"fault", dim, std::string(kDimensionless),
                            "1 while the channel was flagged on the tick before (previous_tick; nonzero and "
                            "finite: flagged)"}
                       .sized_by("as `signal`"));
  if (guard_wired_) {
    ports_.add_input(PortSpec{"guard", dim, std::string(kDimensionless),
                              "nonzero on ticks not judged (a landing's transient)"}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"rejoined", dim, std::string(kDimensionless),
                             "1 on the tick the reading jumped onto its recovered value, else 0"}
                        .sized_by("as `signal`"));
  x1_.assign(dim, std::numeric_limits<double>::quiet_NaN());
  x2_ = x1_;
  y2_ = x1_;
  flagged2_.assign(dim, 0);
  smooth_before_.assign(dim, 0);
}

void RejoinDetector::reset() noexcept {
  std::fill(x1_.begin(), x1_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(x2_.begin(), x2_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(y2_.begin(), y2_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(flagged2_.begin(), flagged2_.end(), 0);
  std::fill(smooth_before_.begin(), smooth_before_.end(), 0);
}

void RejoinDetector::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto y1 = io.in(kRecovered);  // y(t-1)
  const auto fault = io.in(kFault);   // the flag of t-1
  const auto rejoined = io.out(kRejoined);
  for (std::size_t j = 0; j < bound_.size(); ++j) {
    const bool flagged1 = std::isfinite(fault[j]) && fault[j] != 0.0;
    const bool guarded = guard_wired_ && io.in(kGuard)[j] != 0.0;  // NaN is nonzero: unknown is guarded
    const double d0 = x[j] - 2.0 * x1_[j] + x2_[j];
    const double d1 = x[j] - 2.0 * y1[j] + y2_[j];
    // NaN in any sample fails both comparisons: not judged.
    const bool jumped = std::abs(d0) > bound_[j];
    const bool judged = flagged1 && flagged2_[j] && !guarded && smooth_before_[j];
    rejoined[j] = judged && jumped && std::abs(d1) <= bound_[j] ? 1.0 : 0.0;
    // The tick after a jump (and the one after that) holds it in its second difference, and y's
    // line through it: judged only after a tick whose d0 stayed within the bound.
    smooth_before_[j] = std::isfinite(d0) && !jumped ? 1 : 0;
    x2_[j] = x1_[j];
    x1_[j] = x[j];
    y2_[j] = y1[j];
    flagged2_[j] = flagged1 ? 1 : 0;
  }
}

}  // namespace ftsense::generic
