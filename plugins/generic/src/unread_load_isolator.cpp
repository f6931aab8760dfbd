#include "ftsense/generic/unread_load_isolator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/low_pass_gain.hpp"

namespace ftsense::generic {

void UnreadLoadIsolator::Params::describe(ParamSchema<Params>& schema) {
  schema.add("group_size", &Params::group_size,
             "g, the channels that share one sum residual and one alarm (0: all wired channels are one group)")
      .at_least(0);
  schema.add("contact_group_size", &Params::contact_group_size,
             "the consecutive channels within a group that share a contact (a foot's pads: a channel's "
             "landing shows in its neighbours' readings); 0: the whole group is one contact")
      .at_least(0);
  schema
      .add("noise_std", &Params::noise_std,
           "standard deviation sigma of a reading's noise, in the signal's unit; one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema
      .add("resolution", &Params::resolution,
           "quantisation step q of the reading, in its unit (0: continuous); one value applies to all")
      .at_least(0.0)
      .count_at_least(1);
  schema
      .add("residual_noise_std", &Params::residual_noise_std,
           "s_e, the sum residual's fault-free RMS per group (the reference's error): a shortfall counts beyond "
           "z s_e; one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema.add("smoothing_s", &Params::smoothing_s, "time constant tau of the low-pass of readings and residual")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.002, 1.0, "a few ticks to a second");
  schema.add("min_loaded_s", &Params::min_loaded_s,
             "a channel is judged once its contact group has carried load this long since it landed (a "
             "landing loads a sole's pads one by one: heel strike to foot flat)")
      .unit("s")
      .at_least(0.0)
      .plausible(0.0, 2.0, "up to a stance");
  schema.add("noise_margin", &Params::noise_margin,
             "a reading's noise may be up to m noise_std: the band of 'read nothing' holds over that range")
      .at_least(1.0)
      .plausible(1.0, 4.0, "noise specifications hold within a factor of 1 to 2");
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between a healthy idle channel's noise passing the band (sets z)")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
}

UnreadLoadIsolator::UnreadLoadIsolator(const Params& params, const StageContext& context) {
  const double period = context.sample_period_s();
  channels_ = context.wired_dim("signal", 2);
  group_size_ = params.group_size > 0 ? static_cast<std::size_t>(params.group_size) : channels_;
  if (group_size_ == 0 || channels_ % group_size_ != 0) {
    throw ConfigError("/params/group_size", " = " + std::to_string(group_size_) + " does not divide the " +
                                                std::to_string(channels_) + " wired channels into whole groups");
  }
  groups_ = channels_ / group_size_;
  contact_size_ = params.contact_group_size > 0 ? static_cast<std::size_t>(params.contact_group_size) : group_size_;
  if (contact_size_ < 2 || group_size_ % contact_size_ != 0) {
    throw ConfigError("/params/contact_group_size",
                      " = " + std::to_string(contact_size_) + " does not divide a group of " +
                          std::to_string(group_size_) +
                          " into contact groups of 2 or more (a channel alone has no neighbour to show its landing)");
  }
  check_noise_margin(params.noise_margin);
  const double alpha = false_alarm_per_tick(period, params.false_alarm_interval_s);
  if (!(params.min_loaded_s <= 1e6)) {
    throw ConfigError("/params/min_loaded_s", " = " + format_number(params.min_loaded_s) + " s is not a time to wait");
  }
  lp_gain_ = low_pass_gain_from_time_constant(params.smoothing_s, period, "smoothing_s");
  min_loaded_ticks_ = std::lround(params.min_loaded_s / period);
  const double z = two_sided_z(alpha);
  const auto noise_std = channel_values(params.noise_std, channels_, "noise_std");
  const auto resolution = channel_values(params.resolution, channels_, "resolution");
  band_.resize(channels_);
  for (std::size_t j = 0; j < channels_; ++j) {
    band_[j] = resolution[j] + 2.0 * z * params.noise_margin * noise_std[j] * low_pass_noise_ratio(lp_gain_);
  }
  const auto residual_noise = channel_values(params.residual_noise_std, groups_, "residual_noise_std");
  shortfall_bound_.resize(groups_);
  for (std::size_t g = 0; g < groups_; ++g) shortfall_bound_[g] = z * residual_noise[g];
  state_.assign(channels_, Channel{});
  e_lp_.assign(groups_, 0.0);
  e_started_.assign(groups_, 0);
  named_.assign(groups_, -1);

  ports_.add_input(PortSpec{"signal", channels_, std::string(kAnyUnit),
                            "the readings x, group after group (those the sum residual sums)", PortRole::measured}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"sum_residual", groups_, std::string(kAnyUnit),
                            "e per group: its readings' sum less its reference (sum_constraint_residual's sum_residual)"}
                       .sized_by("channels / group_size"));
  ports_.add_input(PortSpec{"alarm", channels_, std::string(kDimensionless),
                            "1 while a detector flags the channel's residual; a group is raised while any of its "
                            "channels is flagged"}
                       .sized_by("as `signal`"));
  ports_.add_input(PortSpec{"loadable", channels_, std::string(kDimensionless),
                            "1 while channel j can carry load, 0 while it cannot (below 1/2: cannot; NaN: can)",
                            PortRole::virtual_estimate}
                       .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault", channels_, std::string(kDimensionless),
                             "1 while the channel is named: the one loadable channel that read nothing since its landing"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_type", channels_, std::string(kDimensionless),
                             "fault type code (fault_type.hpp): frozen while named, else none"}
                        .sized_by("as `signal`"));
}

void UnreadLoadIsolator::reset() noexcept {
  std::fill(state_.begin(), state_.end(), Channel{});
  std::fill(e_lp_.begin(), e_lp_.end(), 0.0);
  std::fill(e_started_.begin(), e_started_.end(), static_cast<char>(0));
  std::fill(named_.begin(), named_.end(), -1);
}

bool UnreadLoadIsolator::candidate(std::size_t j, std::size_t group) const noexcept {
  const Channel& c = state_[j];
  if (!(c.loadable && c.air_known && c.finite_now && !c.moved && c.clear_since && !c.sum_over &&
        c.foot_loaded_ticks >= min_loaded_ticks_)) {
    return false;
  }
  if (!(e_lp_[group] < -shortfall_bound_[group])) return false;
  // Every neighbour on its contact has read load (pushed its reading up past the band).
  const std::size_t first = j - j % contact_size_;
  for (std::size_t k = first; k < first + contact_size_; ++k) {
    if (k != j && !(state_[k].loadable && state_[k].read_load)) return false;
  }
  return true;
}

void UnreadLoadIsolator::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto e = io.in(kSumResidual);
  const auto alarm = io.in(kAlarm);
  const auto loadable = io.in(kLoadable);
  const auto fault = io.out(kFault);
  const auto fault_type = io.out(kFaultType);
  for (std::size_t g = 0; g < groups_; ++g) {
    if (std::isfinite(e[g])) {
      e_lp_[g] = e_started_[g] ? e_lp_[g] + lp_gain_ * (e[g] - e_lp_[g]) : e[g];
      e_started_[g] = 1;
    }
    bool raised = false;
    for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
      raised = raised || (std::isfinite(alarm[j]) && alarm[j] != 0.0);  // as the other isolators read it
    }
    for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
      Channel& c = state_[j];
      c.finite_now = std::isfinite(x[j]);  // a reading not seen is no candidate: it read nothing we know of
      if (c.finite_now) {
        c.lp = c.lp_started ? c.lp + lp_gain_ * (x[j] - c.lp) : x[j];
        c.lp_started = true;
      }
      const bool can_carry = !(loadable[j] < 0.5);  // NaN: can
      if (!can_carry) {
        c.loadable = false;
        if (c.lp_started) {
          c.air_level = c.lp;
          c.air_known = true;
        }
        continue;
      }
      if (!c.loadable) {  // its landing
        c.loadable = true;
        c.foot_loaded_ticks = 0;
        c.sum_over = false;
        c.read_load = false;
        c.moved = false;
        c.clear_since = false;
      }
      c.read_load = c.read_load || (c.air_known && c.lp - c.air_level > band_[j]);
      c.moved = c.moved || (c.air_known && std::abs(c.lp - c.air_level) > band_[j]);
      c.clear_since = c.clear_since || !raised;
    }
    // Since its landing, how long channel j's contact has carried load (a channel of it read load).
    for (std::size_t first = g * group_size_; first < (g + 1) * group_size_; first += contact_size_) {
      bool foot_loaded = false;
      for (std::size_t k = first; k < first + contact_size_; ++k) {
        foot_loaded = foot_loaded || (state_[k].loadable && state_[k].read_load);
      }
      for (std::size_t k = first; k < first + contact_size_; ++k) {
        Channel& c = state_[k];
        if (!(c.loadable && foot_loaded)) continue;
        c.foot_loaded_ticks = std::min<std::int64_t>(c.foot_loaded_ticks + 1, std::int64_t{1} << 40);
        c.sum_over = c.sum_over || e_lp_[g] > shortfall_bound_[g];
      }
    }
    long& named = named_[g];
    if (named >= 0) {
      // A name holds while the alarm stays up and the channel, still on the ground, reads nothing.
      const Channel& c = state_[static_cast<std::size_t>(named)];
      if (!(raised && c.loadable && !c.moved)) named = -1;
    } else if (raised && std::isfinite(e[g])) {
      long found = -1;
      int count = 0;
      for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
        if (candidate(j, g)) {
          found = static_cast<long>(j);
          ++count;
        }
      }
      if (count == 1) named = found;
    }
    for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
      const bool is_named = named == static_cast<long>(j);
      fault[j] = is_named ? 1.0 : 0.0;
      fault_type[j] = fault_code(is_named ? FaultType::frozen : FaultType::none);
    }
  }
}

}  // namespace ftsense::generic
