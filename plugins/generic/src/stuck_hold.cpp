#include "ftsense/generic/stuck_hold.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/low_pass_gain.hpp"

namespace ftsense::generic {

void StuckHold::Params::describe(ParamSchema<Params>& schema) {
  schema
      .add("noise_std", &Params::noise_std,
           "standard deviation sigma of the reading's noise, in the signal's unit (a stuck output keeps its "
           "electrical noise); one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema
      .add("resolution", &Params::resolution,
           "quantisation step q of the reading, in its unit (0: continuous); one value applies to all")
      .at_least(0.0)
      .count_at_least(1);
  schema.add("types", &Params::types,
             "fault type names held while the reading stays where it stuck (a reading that lost its load; "
             "saturation is not held by default: a clipped reading is right on every tick below its ceiling)");
  schema.add("smoothing_s", &Params::smoothing_s,
             "time constant tau of the low-pass l of the reading compared with the episode's mean")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.002, 2.0, "a few ticks to a couple of seconds");
  schema.add("noise_margin", &Params::noise_margin,
             "a stuck output's noise may be up to m noise_std: the bound holds its rate over that range")
      .at_least(1.0)
      .plausible(1.0, 4.0, "noise specifications hold within a factor of 1 to 2");
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between re-admissions of a still-stuck channel by its noise alone (sets z)")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("cannot_judge", &Params::cannot_judge,
             "adds input cannot_judge (one per channel) and output cannot_judge: the input's, 0 while held");
}

void StuckHold::Params::validate(Diagnostics& diag, std::string_view path) const {
  std::vector<std::string> names;
  for (FaultType t : sensor_fault_types()) names.emplace_back(to_string(t));
  for (std::size_t i = 0; i < types.size(); ++i) {
    const auto type = fault_type_from_string(types[i]);
    if (!type || *type == FaultType::none || *type == FaultType::unclassified) {
      diag.error(json_pointer_append(std::string(path) + "/types", i),
                 "'" + types[i] + "' is not a sensor fault type; " + suggest(types[i], names));
    }
  }
}

StuckHold::StuckHold(const Params& params, const StageContext& context) : cannot_judge_(params.cannot_judge) {
  const double period = context.sample_period_s();
  const std::size_t dim = context.wired_dim("signal", params.noise_std.size());
  const auto noise_std = channel_values(params.noise_std, dim, "noise_std");
  const auto resolution = channel_values(params.resolution, dim, "resolution");
  check_noise_margin(params.noise_margin);
  const double alpha = false_alarm_per_tick(period, params.false_alarm_interval_s);
  const double z = two_sided_z(alpha);
  lp_gain_ = low_pass_gain_from_time_constant(params.smoothing_s, period, "smoothing_s");
  lp_noise_ = low_pass_noise_ratio(lp_gain_);
  z_ = z;
  // v's independent draws: a low-pass of gain a averages (2 - a) / a values, and successive d^2
  // correlate by 1/4, which takes a factor 1 + 2 / 4 off.
  const double v_draws = (2.0 - lp_gain_) / (1.5 * lp_gain_);
  noise_ratio_ = chi_square_quantile_at_z(v_draws, z) / v_draws;
  half_step_.resize(dim);
  noise_scale_.resize(dim);
  noise_floor_.resize(dim);
  for (std::size_t j = 0; j < dim; ++j) {
    half_step_[j] = 0.5 * resolution[j];
    noise_scale_[j] = z * params.noise_margin * noise_std[j];
    const double quiet = noise_std[j] / params.noise_margin;
    noise_floor_[j] = 2.0 * quiet * quiet / noise_ratio_;
  }
  held_type_.fill(false);
  for (const std::string& t : params.types) held_type_[static_cast<std::size_t>(*fault_type_from_string(t))] = true;
  channels_.assign(dim, Channel{});

  ports_.add_input(PortSpec{"signal", dim, std::string(kAnyUnit), "the readings x", PortRole::measured}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"fault", dim, std::string(kDimensionless),
                            "the channels' flags (nonzero and finite: flagged), e.g. fault_merge's"}
                       .sized_by("as `signal`"));
  ports_.add_input(PortSpec{"fault_type", dim, std::string(kDimensionless), "the channels' fault type codes"}
                       .sized_by("as `signal`"));
  if (cannot_judge_) {
    ports_.add_input(PortSpec{"cannot_judge", dim, std::string(kDimensionless),
                              "1 while a part cannot judge the channel"}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"fault", dim, std::string(kDimensionless),
                             "1 while the input flags the channel or its stuck reading has not moved since"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_type", dim, std::string(kDimensionless),
                             "the input's type, or the held episode's; none when unflagged"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"held", dim, std::string(kDimensionless),
                             "1 while the flag is this part's own: the input's is down, the reading has not moved"}
                        .sized_by("as `signal`"));
  if (cannot_judge_) {
    ports_.add_output(PortSpec{"cannot_judge", dim, std::string(kDimensionless),
                               "the input's cannot_judge, 0 while held"}
                          .sized_by("as `signal`"));
  }
}

void StuckHold::reset() noexcept { std::fill(channels_.begin(), channels_.end(), Channel{}); }

double StuckHold::moved_bound(std::size_t j, double n) const noexcept {
  return half_step_[j] + noise_scale_[j] * (lp_noise_ + 1.0 / std::sqrt(std::max(n, 1.0)));
}

double StuckHold::noise_bound(std::size_t j, double s, double n) const noexcept {
  const double draws = n / 1.5;
  // Too few differences to bound the episode's own noise from below (L = 0 at this z): the noise
  // test cannot judge, and only the level releases.
  const double low = draws >= 2.0 ? chi_square_quantile_at_z(draws, -z_) / draws : 0.0;
  if (!(low > 0.0)) return std::numeric_limits<double>::infinity();
  return std::max(noise_ratio_ * s / low, noise_floor_[j]);
}

void StuckHold::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto flag = io.in(kFault);
  const auto code = io.in(kFaultType);
  const auto fault = io.out(kHeldFault);
  const auto type = io.out(kHeldType);
  const auto held = io.out(kHeld);
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const bool finite = std::isfinite(x[j]);
    double d2 = 0.0;
    const bool has_d2 = finite && c.has_previous;
    if (finite) {
      c.lp = c.lp_started ? c.lp + lp_gain_ * (x[j] - c.lp) : x[j];
      c.lp_started = true;
      if (has_d2) {
        d2 = (x[j] - c.previous) * (x[j] - c.previous);
        c.lp_d2 = c.lp_d2_started ? c.lp_d2 + lp_gain_ * (d2 - c.lp_d2) : d2;
        c.lp_d2_started = true;
      }
    }
    c.has_previous = finite;
    c.previous = finite ? x[j] : 0.0;
    const bool flagged = std::isfinite(flag[j]) && flag[j] != 0.0;
    bool hold = false;
    if (flagged) {
      const auto t = fault_type_from_code(code[j]);
      if (t && held_type_[static_cast<std::size_t>(*t)]) {
        if (!c.in_episode) {
          c.in_episode = true;
          c.mean = 0.0;
          c.count = 0.0;
          c.d2_mean = 0.0;
          c.d2_count = 0.0;
        }
        c.type_code = code[j];
        c.noise_limit_set = false;  // s takes this tick's difference: its bound is judged anew
      } else {
        c.in_episode = false;
      }
    } else if (c.in_episode) {
      // The input let the channel go: held while the reading has not moved from the episode's mean.
      // A non-finite reading is no evidence; nor is an episode without a reading yet. s and its
      // count are fixed while held, so their bound is taken once.
      if (!c.noise_limit_set) {
        c.noise_limit = noise_bound(j, c.d2_mean, c.d2_count);
        c.noise_limit_set = true;
      }
      hold = c.count == 0.0 || !finite ||
             (std::abs(c.lp - c.mean) <= moved_bound(j, c.count) && !(c.lp_d2_started && c.lp_d2 > c.noise_limit));
      c.in_episode = hold;
    }
    if (c.in_episode && finite) {
      c.count += 1.0;
      c.mean += (x[j] - c.mean) / c.count;
      // s is the episode's noise while the input flagged it; held, a returning noise must not
      // raise the bound it is judged against.
      if (has_d2 && flagged) {
        c.d2_count += 1.0;
        c.d2_mean += (d2 - c.d2_mean) / c.d2_count;
      }
    }
    fault[j] = flagged || hold ? 1.0 : 0.0;
    type[j] = flagged ? code[j] : (hold ? c.type_code : fault_code(FaultType::none));
    held[j] = hold ? 1.0 : 0.0;
    if (cannot_judge_) {
      const double cj = io.in(kCannotJudge)[j];
      io.out(kHeldCannotJudge)[j] = !hold && std::isfinite(cj) && cj != 0.0 ? 1.0 : 0.0;
    }
  }
}

}  // namespace ftsense::generic
