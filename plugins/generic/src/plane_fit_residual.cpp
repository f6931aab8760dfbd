#include "ftsense/generic/plane_fit_residual.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/generic/quantity_bounds.hpp"
#include "ftsense/generic/unmeasured_contact_loads.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

void PlaneFitResidual::Params::describe(ParamSchema<Params>& schema) {
  schema.add("points_per_foot", &Params::points_per_foot,
             "channels per foot, foot after foot in `signal` (4 or more: three points fix a plane and leave no "
             "relation)")
      .at_least(1)
      .plausible(4.0, 64.0, "four to a few dozen pads a sole");
  schema.add("points", &Params::points,
             "the contact points (x, y) of one foot's channels on a rigid sole, foot frame, every foot alike")
      .unit("m")
      .count_at_most(64)
      .plausible(plausible::foot_point_m());
  schema.add("loadable", &Params::loadable,
             "adds input loadable (1 while a channel can carry load, by kinematics): a foot with a pad that "
             "cannot is not in full contact");
  schema.add("correction", &Params::correction,
             "adds input correction c (the recovery's correction of each reading on the tick before, through "
             "previous_tick): the rows and the full-contact test take the readings as corrected, x - c, so a fault "
             "already found leaves the plane's level (not finite: the foot is not judged)");
  schema.add("substituted", &Params::substituted,
             "adds input substituted (1 where a reading stood for nothing on the tick before, a recovery's "
             "through previous_tick): its foot's rows are not judged");
  schema.add("floor", &Params::floor,
             "the least load a pad carries (0 for a pad that is pressed, never pulled), in the readings' unit; a "
             "pad counts as loaded beyond the noise margin above it; one value applies to all");
  describe_reading_noise(schema);
  schema.add("noise_margin", &Params::noise_margin,
             "a healthy noise is known within this factor: a pad counts as loaded above the floor plus "
             "noise_margin sigma times z")
      .at_least(1.0)
      .plausible(1.0, 5.0, "1 (the noise known exactly) to a few");
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between a pad at rest taken for a loaded one (sets z)")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
}

void PlaneFitResidual::Params::validate(Diagnostics& diag, std::string_view path) const {
  if (points.size() != static_cast<std::size_t>(std::max(1, points_per_foot))) {
    diag.error(std::string(path) + "/points",
               "gives " + std::to_string(points.size()) + " contact points for a foot of " +
                   std::to_string(points_per_foot) + " channels (points_per_foot); give one (x, y) per channel of a foot");
  }
}

PlaneFitResidual::PlaneFitResidual(const Params& params, const StageContext& context)
    : loadable_wired_(params.loadable),
      correction_wired_(params.correction),
      substituted_wired_(params.substituted),
      points_per_foot_(static_cast<std::size_t>(std::max(1, params.points_per_foot))) {
  const std::size_t n = context.wired_dim("signal", 2 * points_per_foot_);
  if (n == 0 || n % points_per_foot_ != 0) {
    throw ConfigError("/params/points_per_foot", " = " + std::to_string(points_per_foot_) +
                                                     " does not divide the " + std::to_string(n) +
                                                     " wired channels into whole feet");
  }
  if (params.points.size() != points_per_foot_) {
    throw ConfigError("/params/points", " gives " + std::to_string(params.points.size()) +
                                            " contact points for a foot of " + std::to_string(points_per_foot_) +
                                            " channels; give one (x, y) per channel of a foot");
  }
  feet_ = n / points_per_foot_;
  // Pi = W W^T from the layout's relations; row j scaled by 1 / Pi_jj (the leave-one-out residual).
  const UnmeasuredContactLoads layout(params.points, points_per_foot_, 1);
  const std::size_t relations = layout.relations_per_foot();
  if (relations == 0) {
    throw ConfigError("/params/points", ": these points leave no relation (a plane fits any loads on three "
                                        "points not on a line); give four points or more");
  }
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  row_.assign(points_per_foot_ * points_per_foot_, kNaN);
  for (std::size_t j = 0; j < points_per_foot_; ++j) {
    double diagonal = 0.0;
    for (std::size_t r = 0; r < relations; ++r) diagonal += layout.relation_weight(j, r) * layout.relation_weight(j, r);
    // A point no relation involves (Pi_jj ~ 0, numerically: W is orthonormal) has no row.
    if (!(diagonal > 1e-9)) continue;
    for (std::size_t k = 0; k < points_per_foot_; ++k) {
      double pi = 0.0;
      for (std::size_t r = 0; r < relations; ++r) pi += layout.relation_weight(j, r) * layout.relation_weight(k, r);
      row_[j * points_per_foot_ + k] = k == j ? 1.0 : pi / diagonal;
    }
  }
  loads_.assign(points_per_foot_, 0.0);
  const auto floor = channel_values(params.floor, n, "floor");
  const auto noise = channel_values(params.noise_std, n, "noise_std");
  const auto resolution = channel_values(params.resolution, n, "resolution");
  check_noise_margin(params.noise_margin);
  const double z = two_sided_z(false_alarm_per_tick(context.sample_period_s(), params.false_alarm_interval_s));
  loaded_above_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    loaded_above_[k] = floor[k] + reading_margin(z, params.noise_margin, noise[k], resolution[k]);
  }
  ports_.add_input(PortSpec{"signal", n, std::string(kAnyUnit), "the readings x, foot after foot",
                            PortRole::measured}
                       .sized_by("as wired"));
  if (loadable_wired_) {
    ports_.add_input(PortSpec{"loadable", n, std::string(kDimensionless),
                              "1 while channel j can carry load, 0 while it cannot (below 1/2: cannot; NaN: can)",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  if (correction_wired_) {
    // A virtual estimate for the independence rule: fed back from the readings' recovery.
    ports_.add_input(PortSpec{"correction", n, std::string(kAnyUnit),
                              "c_j, the recovery's correction of reading j on the tick before: the foot's rows take "
                              "x_j - c_j (not finite: the foot is not judged)",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  if (substituted_wired_) {
    // A virtual estimate for the independence rule: fed back from the readings' recovery.
    ports_.add_input(PortSpec{"substituted", n, std::string(kDimensionless),
                              "1 where reading j stood for nothing on the tick before: its foot is not judged",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"residual", n, std::string(kAnyUnit),
                             "r_j = x_j less the plane through its foot's other points at point j (NaN while the "
                             "foot is not in full contact)"}
                        .sized_by("as `signal`"));
}

void PlaneFitResidual::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  // Optional inputs follow signal in the order loadable, correction, substituted.
  std::size_t next_input = kSignal + 1;
  const std::span<const double> loadable_in = loadable_wired_ ? io.in(next_input++) : std::span<const double>{};
  const std::span<const double> correction = correction_wired_ ? io.in(next_input++) : std::span<const double>{};
  const std::span<const double> substituted = substituted_wired_ ? io.in(next_input++) : std::span<const double>{};
  const auto residual = io.out(kResidual);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t g = points_per_foot_;
  for (std::size_t f = 0; f < feet_; ++f) {
    bool full_contact = true;
    for (std::size_t i = 0; i < g && full_contact; ++i) {
      const std::size_t j = f * g + i;
      const double load = correction_wired_ ? x[j] - correction[j] : x[j];
      loads_[i] = load;
      full_contact = std::isfinite(load) && load > loaded_above_[j] &&
                     (!loadable_wired_ || !(loadable_in[j] < 0.5)) && (!substituted_wired_ || !(substituted[j] >= 0.5));
    }
    for (std::size_t i = 0; i < g; ++i) {
      double r = full_contact ? 0.0 : kNaN;
      for (std::size_t k = 0; k < g && full_contact; ++k) r += row_[i * g + k] * loads_[k];
      residual[f * g + i] = r;
    }
  }
}

}  // namespace ftsense::generic
