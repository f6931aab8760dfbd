#include "ftsense/generic/load_apportioner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/generic/quantity_bounds.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

void LoadApportioner::Params::describe(ParamSchema<Params>& schema) {
  schema.add("points_per_foot", &Params::points_per_foot,
             "channels per foot, foot after foot in `signal` (4 for a sole of four pads, 1 for a point foot)")
      .at_least(1)
      .plausible(1.0, 64.0, "one to a few dozen contact points a foot");
  schema.add("points", &Params::points,
             "the contact points (x, y) of one foot's channels on a rigid sole, foot frame, every foot alike: in "
             "full contact a foot's loads lie on a plane, which sets two substituted channels apart; empty: the "
             "sum alone")
      .unit("m")
      .count_at_most(64)
      .plausible(plausible::foot_point_m());
  schema.add("floor", &Params::floor,
             "the least load an unknown channel carries (0 for a pad that is pressed, never pulled), in the "
             "readings' unit; one value applies to all");
  describe_reading_noise(schema);
  schema.add("noise_margin", &Params::noise_margin,
             "a healthy noise is known within this factor: a pad counts as loaded above noise_margin sigma times z")
      .at_least(1.0)
      .plausible(1.0, 5.0, "1 (the noise known exactly) to a few");
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between a healthy pad at rest taken for a loaded one (sets z)")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
}

void LoadApportioner::Params::validate(Diagnostics& diag, std::string_view path) const {
  if (!points.empty() && points.size() != static_cast<std::size_t>(std::max(1, points_per_foot))) {
    diag.error(std::string(path) + "/points",
               "gives " + std::to_string(points.size()) + " contact points for a foot of " +
                   std::to_string(points_per_foot) +
                   " channels (points_per_foot); give one (x, y) per channel of a foot, or none");
  }
}

LoadApportioner::LoadApportioner(const Params& params, const StageContext& context)
    : points_per_foot_(static_cast<std::size_t>(std::max(1, params.points_per_foot))) {
  const std::size_t n = context.wired_dim("signal", 2 * points_per_foot_);
  if (n == 0 || n % points_per_foot_ != 0) {
    throw ConfigError("/params/points_per_foot", " = " + std::to_string(points_per_foot_) +
                                                     " does not divide the " + std::to_string(n) +
                                                     " wired channels into whole feet");
  }
  feet_ = n / points_per_foot_;
  loads_ = UnmeasuredContactLoads(params.points, points_per_foot_, feet_);
  floor_ = channel_values(params.floor, n, "floor");
  const auto noise = channel_values(params.noise_std, n, "noise_std");
  const auto resolution = channel_values(params.resolution, n, "resolution");
  check_noise_margin(params.noise_margin);
  const double z = two_sided_z(false_alarm_per_tick(context.sample_period_s(), params.false_alarm_interval_s));
  loaded_above_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    loaded_above_[k] = floor_[k] + reading_margin(z, params.noise_margin, noise[k], resolution[k]);
  }
  known_.assign(n, 0.0);
  solved_.assign(n, 0.0);
  unknown_.assign(n, 0);
  plane_usable_.assign(feet_, 0);
  ports_.add_input(PortSpec{"signal", n, std::string(kAnyUnit), "the readings x, foot after foot",
                            PortRole::measured}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"reference", 1, std::string(kAnyUnit),
                            "R, what all the channels' loads sum to (e.g. the total vertical force)",
                            PortRole::virtual_estimate});
  ports_.add_input(PortSpec{"loadable", n, std::string(kDimensionless),
                            "1 while channel j can carry load, 0 while it cannot (below 1/2: cannot; NaN: can)",
                            PortRole::virtual_estimate}
                       .sized_by("as `signal`"));
  // Virtual estimates for the independence rule: fed back from the readings' recovery, they
  // depend on the readings (docs/architecture.md, "The plugin contract").
  ports_.add_input(PortSpec{"correction", n, std::string(kAnyUnit),
                            "c_j, the recovery's correction of reading j on the tick before (not finite: as "
                            "substituted)",
                            PortRole::virtual_estimate}
                       .sized_by("as `signal`"));
  ports_.add_input(PortSpec{"substituted", n, std::string(kDimensionless),
                            "1 where reading j stood for nothing on the tick before: its load is unknown while it "
                            "can carry load",
                            PortRole::virtual_estimate}
                       .sized_by("as `signal`"));
  ports_.add_input(PortSpec{"flagged", n, std::string(kDimensionless),
                            "1 where channel j was flagged on the tick before: its readings teach no relation's "
                            "variance",
                            PortRole::virtual_estimate}
                       .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"virtual", n, std::string(kAnyUnit),
                             "v_i, channel i's load from the relations with i unknown too (0 while i cannot carry "
                             "load; NaN while R is not finite)",
                             PortRole::signal, /*leave_one_out=*/true}
                        .sized_by("as `signal`"));
}

void LoadApportioner::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const double r = io.in(kReference)[0];
  const auto loadable = io.in(kLoadable);
  const auto correction = io.in(kCorrection);
  const auto substituted = io.in(kSubstituted);
  const auto flagged = io.in(kFlagged);
  const auto virtual_value = io.out(kVirtual);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = known_.size();
  // NaN (unknown) counts as loadable: nothing is judged on a guess.
  const auto can_carry = [&](std::size_t j) { return !(loadable[j] < 0.5); };

  // The relations' fault-free statistics.
  bool none_flagged = std::isfinite(r);
  double sum = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    none_flagged = none_flagged && flagged[j] < 0.5 && std::isfinite(x[j]);
    sum += x[j];
  }
  if (none_flagged) loads_.observe_sum(sum - r);
  if (loads_.relations_per_foot() > 0) {
    for (std::size_t f = 0; f < feet_; ++f) {
      bool full_contact = true;
      for (std::size_t i = 0; i < points_per_foot_ && full_contact; ++i) {
        const std::size_t j = f * points_per_foot_ + i;
        full_contact = flagged[j] < 0.5 && can_carry(j) && std::isfinite(x[j]) && x[j] > loaded_above_[j];
      }
      if (full_contact) loads_.observe_foot(f, x.subspan(f * points_per_foot_, points_per_foot_));
    }
  }

  // Each channel's load as the others see it: NaN where it stands for nothing on the ground.
  std::size_t unknowns = 0;
  double known_total = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const bool stands = std::isfinite(correction[j]) && substituted[j] < 0.5 && std::isfinite(x[j]);
    known_[j] = !can_carry(j) ? 0.0 : stands ? x[j] - correction[j] : kNaN;
    if (std::isnan(known_[j])) {
      ++unknowns;
    } else {
      known_total += known_[j];
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!can_carry(i)) {
      virtual_value[i] = 0.0;
      continue;
    }
    if (!std::isfinite(r)) {
      virtual_value[i] = kNaN;
      continue;
    }
    if (unknowns == 0) {
      // i alone unknown: the sum's leave-one-out value (the solve's answer for one unknown).
      virtual_value[i] = std::max(floor_[i], r - (known_total - known_[i]));
      continue;
    }
    // Channel i unknown too; a foot's plane usable while all its pads are on the ground and its
    // known ones loaded.
    for (std::size_t f = 0; f < feet_; ++f) plane_usable_[f] = 1;
    for (std::size_t j = 0; j < n; ++j) {
      const bool unknown = j == i || std::isnan(known_[j]);
      unknown_[j] = unknown ? 1 : 0;
      solved_[j] = unknown ? 0.0 : known_[j];
      if (!can_carry(j) || (!unknown && !(known_[j] > loaded_above_[j]))) plane_usable_[j / points_per_foot_] = 0;
    }
    const double known_sum = known_total - (std::isnan(known_[i]) ? 0.0 : known_[i]);
    loads_.solve(solved_, unknown_, floor_, plane_usable_, r - known_sum);
    // An equal share across feet is no measure: cannot judge.
    virtual_value[i] = loads_.foot_total_determined(i / points_per_foot_) ? solved_[i] : kNaN;
  }
}

}  // namespace ftsense::generic
