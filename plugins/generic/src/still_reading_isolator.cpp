#include "ftsense/generic/still_reading_isolator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/generic/quantity_bounds.hpp"

namespace ftsense::generic {

void StillReadingIsolator::Params::describe(ParamSchema<Params>& schema) {
  schema.add("group_size", &Params::group_size,
             "channels per sum residual g; the wired channels are the groups one after another (0: all of them, "
             "one residual)")
      .at_least(0)
      .at_most(64);
  schema
      .add("residual_noise_density", &Params::residual_noise_density,
           "low-frequency noise density q of each group's fault-free sum residual, in its unit times sqrt(s); one "
           "value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  describe_reading_noise(schema);
  schema.add("floor", &Params::floor,
             "the least load a channel carries (0 for a pad that is pressed, never pulled), in the readings' unit; "
             "one value applies to all");
  schema.add("block_s", &Params::block_s, "length of the blocks whose means are compared (taken to the nearest whole number of ticks)")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.001, 1.0, "from a tick to a second");
  schema.add("span_s", &Params::span_s, "how far apart the two blocks compared are (taken to the nearest whole number of blocks)")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.01, 5.0, "from ten milliseconds to a few seconds");
  schema.add("follow_ratio", &Params::follow_ratio,
             "a reading moved by less than this share of the residual's move stood still")
      .greater_than(0.0)
      .at_most(0.5);
  schema.add("noise_margin", &Params::noise_margin,
             "a healthy noise is known within this factor: a channel counts as loaded above the floor plus "
             "noise_margin sigma times z")
      .at_least(1.0)
      .plausible(1.0, 5.0, "1 (the noise known exactly) to a few");
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between wrong names the bounds are set for")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
}

StillReadingIsolator::StillReadingIsolator(const Params& params, const StageContext& context)
    : follow_ratio_(params.follow_ratio) {
  channels_ = context.wired_dim("signal", params.group_size > 0 ? static_cast<std::size_t>(params.group_size) : 2);
  group_size_ = params.group_size > 0 ? static_cast<std::size_t>(params.group_size) : channels_;
  if (channels_ == 0 || channels_ % group_size_ != 0) {
    throw ConfigError("/params/group_size", " = " + std::to_string(group_size_) + " does not divide the " +
                                                std::to_string(channels_) + " wired channels into whole groups");
  }
  groups_ = channels_ / group_size_;
  const double period = context.sample_period_s();
  // Blocks of the nearest whole number of ticks, a span of the nearest whole number of blocks
  // (at least one each), as the other block parts take theirs: a config holds at any rate.
  ticks_per_block_ = std::max(1, static_cast<int>(std::lround(params.block_s / period)));
  const double block_s = ticks_per_block_ * period;
  const double blocks = std::max(1.0, std::round(params.span_s / block_s));
  // The span's K + 1 blocks and the one after it, whose flags are read too (a step is named
  // within a few ticks of it: a block later the flag is known).
  ring_ = static_cast<std::size_t>(blocks) + 2;
  check_noise_margin(params.noise_margin);
  // One decision per block: the move's bound at alpha = b / interval; the loaded bound per tick.
  const double z_block = two_sided_z(false_alarm_per_tick(block_s, params.false_alarm_interval_s));
  const double z_tick = two_sided_z(false_alarm_per_tick(period, params.false_alarm_interval_s));
  const auto density = channel_values(params.residual_noise_density, groups_, "residual_noise_density");
  move_bound_.resize(groups_);
  for (std::size_t g = 0; g < groups_; ++g) {
    move_bound_[g] = z_block * std::sqrt(2.0 / block_s) * density[g];
  }
  floor_ = channel_values(params.floor, channels_, "floor");
  const auto noise = channel_values(params.noise_std, channels_, "noise_std");
  const auto resolution = channel_values(params.resolution, channels_, "resolution");
  margin_.resize(channels_);
  loaded_above_.resize(channels_);
  for (std::size_t j = 0; j < channels_; ++j) {
    margin_[j] = reading_margin(z_tick, params.noise_margin, noise[j], resolution[j]);
    loaded_above_[j] = floor_[j] + margin_[j];
  }

  ports_.add_input(PortSpec{"signal", channels_, std::string(kAnyUnit),
                            "the readings x, group after group (those the sum residual sums)", PortRole::measured}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"sum_residual", groups_, std::string(kAnyUnit),
                            "e per group: its readings' sum less its reference (sum_constraint_residual's sum_residual)"}
                       .sized_by("channels / group_size"));
  ports_.add_input(PortSpec{"alarm", channels_, std::string(kDimensionless),
                            "1 while a detector flags the channel's residual; a group is judged while any of its "
                            "channels is flagged"}
                       .sized_by("as `signal`"));
  ports_.add_input(PortSpec{"loadable", channels_, std::string(kDimensionless),
                            "1 while channel j can carry load, 0 while it cannot (below 1/2: cannot; NaN: can)",
                            PortRole::virtual_estimate}
                       .sized_by("as `signal`"));
  // A virtual estimate for the independence rule: fed back from the flags of the tick before.
  ports_.add_input(PortSpec{"flagged", channels_, std::string(kDimensionless),
                            "1 where channel j was flagged on the tick before: its group is not judged over a span "
                            "that holds it",
                            PortRole::virtual_estimate}
                       .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault", channels_, std::string(kDimensionless),
                             "1 while the channel is named: its reading stood still while the residual moved"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_type", channels_, std::string(kDimensionless),
                             "fault type code (fault_type.hpp): frozen while named, else none"}
                        .sized_by("as `signal`"));

  sum_e_.assign(groups_, 0.0);
  sum_x_.assign(channels_, 0.0);
  ticks_e_.assign(groups_, 0);
  ticks_x_.assign(channels_, 0);
  loaded_now_.assign(channels_, 1);
  flagged_now_.assign(groups_, 0);
  block_e_.assign(groups_ * ring_, 0.0);
  block_x_.assign(channels_ * ring_, 0.0);
  block_loaded_.assign(channels_ * ring_, 0);
  block_flagged_.assign(groups_ * ring_, 0);
  named_.assign(groups_, -1);
}

void StillReadingIsolator::reset() noexcept {
  std::fill(sum_e_.begin(), sum_e_.end(), 0.0);
  std::fill(sum_x_.begin(), sum_x_.end(), 0.0);
  std::fill(ticks_e_.begin(), ticks_e_.end(), 0);
  std::fill(ticks_x_.begin(), ticks_x_.end(), 0);
  std::fill(loaded_now_.begin(), loaded_now_.end(), 1);
  std::fill(flagged_now_.begin(), flagged_now_.end(), 0);
  std::fill(block_loaded_.begin(), block_loaded_.end(), 0);
  std::fill(block_flagged_.begin(), block_flagged_.end(), 0);
  std::fill(named_.begin(), named_.end(), -1);
  tick_in_block_ = 0;
  blocks_ = 0;
}

void StillReadingIsolator::judge(std::size_t group) noexcept {
  // The span: from the ring's oldest block to the one before its newest.
  const std::size_t last = (blocks_ + ring_ - 2) % ring_, first = blocks_ % ring_;
  for (std::size_t b = 0; b < ring_; ++b) {
    if (block_flagged_[group * ring_ + b]) return;  // a fault found moves e by its own course
  }
  const double de = block_e_[group * ring_ + last] - block_e_[group * ring_ + first];
  if (!(std::abs(de) >= move_bound_[group])) return;  // NaN: a block without e
  const double still = follow_ratio_ * std::abs(de);
  long candidate = -1;
  for (std::size_t i = 0; i < group_size_; ++i) {
    const std::size_t j = group * group_size_ + i;
    const double dx = block_x_[j * ring_ + last] - block_x_[j * ring_ + first];
    if (!std::isfinite(dx)) return;  // a reading without a value: e is not this group's to read
    bool loaded = true;
    for (std::size_t b = 0; b + 1 < ring_; ++b) loaded = loaded && block_loaded_[j * ring_ + (first + b) % ring_] != 0;
    const bool could_be_stuck = block_x_[j * ring_ + last] - de >= floor_[j] - margin_[j];
    if (loaded && std::abs(dx) < still && could_be_stuck) {
      if (candidate >= 0) return;  // two still readings: neither is told from the other
      candidate = static_cast<long>(i);
    }
  }
  if (candidate >= 0) named_[group] = candidate;
}

void StillReadingIsolator::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto e = io.in(kSumResidual);
  const auto alarm = io.in(kAlarm);
  const auto loadable = io.in(kLoadable);
  const auto flagged = io.in(kFlagged);
  for (std::size_t g = 0; g < groups_; ++g) {
    if (std::isfinite(e[g])) {
      sum_e_[g] += e[g];
      ++ticks_e_[g];
    }
    for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
      if (std::isfinite(x[j])) {
        sum_x_[j] += x[j];
        ++ticks_x_[j];
      }
      loaded_now_[j] &= !(loadable[j] < 0.5) && x[j] > loaded_above_[j] ? 1 : 0;
      flagged_now_[g] |= !(flagged[j] < 0.5) ? 1 : 0;  // NaN: as flagged
    }
  }
  const bool block_ends = ++tick_in_block_ == ticks_per_block_;
  if (block_ends) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    const std::size_t slot = blocks_ % ring_;
    const int half = (ticks_per_block_ + 1) / 2;  // a block mean of fewer finite ticks is no mean
    for (std::size_t g = 0; g < groups_; ++g) {
      block_e_[g * ring_ + slot] = ticks_e_[g] >= half ? sum_e_[g] / ticks_e_[g] : kNaN;
      block_flagged_[g * ring_ + slot] = flagged_now_[g];
      sum_e_[g] = 0.0;
      ticks_e_[g] = 0;
      flagged_now_[g] = 0;
    }
    for (std::size_t j = 0; j < channels_; ++j) {
      block_x_[j * ring_ + slot] = ticks_x_[j] >= half ? sum_x_[j] / ticks_x_[j] : kNaN;
      block_loaded_[j * ring_ + slot] = loaded_now_[j];
      sum_x_[j] = 0.0;
      ticks_x_[j] = 0;
      loaded_now_[j] = 1;
    }
    ++blocks_;
    tick_in_block_ = 0;
  }
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  for (std::size_t g = 0; g < groups_; ++g) {
    bool raised = false;
    for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
      raised = raised || (std::isfinite(alarm[j]) && alarm[j] != 0.0);
    }
    if (!raised) {
      named_[g] = -1;
    } else if (block_ends && named_[g] < 0 && blocks_ >= ring_) {
      judge(g);
    }
    for (std::size_t i = 0; i < group_size_; ++i) {
      const bool named = named_[g] == static_cast<long>(i);
      fault[g * group_size_ + i] = named ? 1.0 : 0.0;
      type[g * group_size_ + i] = fault_code(named ? FaultType::frozen : FaultType::none);
    }
  }
}

}  // namespace ftsense::generic
