#include "ftsense/generic/gain_isolator.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

void GainIsolator::Params::describe(ParamSchema<Params>& schema) {
  schema.add("group_size", &Params::group_size,
             "channels per sum residual g; the wired channels are the groups one after another (0: all of them, "
             "one residual)")
      .at_least(0)
      .at_most(64);
  schema
      .add("residual_noise_density", &Params::residual_noise_density,
           "low-frequency noise density q of each group's fault-free sum residual, in its unit times sqrt(s): the "
           "mean of e over w seconds has standard deviation q / sqrt(w); one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema.add("block_s", &Params::block_s, "length of the blocks whose means are fitted (a whole number of ticks)")
      .unit("s")
      .greater_than(0.0)
      .at_most(60.0)
      .plausible(0.001, 2.0, "from a tick to a couple of seconds");
  schema
      .add("history_s", &Params::history_s,
           "how far back the gain's onset is searched and the fit made (a few strides: the loads' shapes must differ "
           "within it)")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.2, 600.0, "from a stride to ten minutes");
  schema
      .add("min_fault_s", &Params::min_fault_s,
           "the least time after the fitted onset a gain is named on (a fit on a block or two takes a reading's "
           "noise for a gain)")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.01, 60.0, "from a few ticks to a minute");
  schema.add("hold_until_refuted", &Params::hold_until_refuted,
             "keep a named channel named after the group's alarm falls, until the blocks since show that e no longer "
             "follows its reading by the gain fitted (a gain is invisible while its pad carries nothing)");
  schema
      .add("false_alarm_interval_s", &Params::false_alarm_interval_s,
           "mean time between wrong names the margins are set for, per decision: alpha = block_s / interval")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("substituted", &Params::substituted,
             "adds input substituted (1 where a reading stands for nothing, a recovery's substituted one tick "
             "late): a block on which one other than the named channel stood for nothing is left out, or, with "
             "loadable, taken with that channel at zero if it could carry load on none of the block's ticks");
  schema.add("loadable", &Params::loadable,
             "adds input loadable (1 while a channel can carry load, by kinematics): nobody is named while "
             "another channel's reading stood still while loaded (a stuck reading's own load moves e)");
  schema.add("flagged", &Params::flagged,
             "adds input flagged (1 where another part isolated the channel on the tick before, e.g. the merged "
             "isolators' flags through previous_tick): a channel flagged on a block since its fitted onset is "
             "named without the lead over the runner-up, which only tells which channel, when it explains e best");
  schema
      .add("follow_ratio", &Params::follow_ratio,
           "with loadable: a loaded reading that moved by less than this share of what the sum residual moved "
           "(RMS, over the blocks after the onset) could be a stuck one, and then nobody is named")
      .greater_than(0.0)
      .less_than(1.0);
}

GainIsolator::GainIsolator(const Params& params, const StageContext& context)
    : substituted_(params.substituted),
      loadable_(params.loadable),
      follow_ratio_(params.follow_ratio),
      flagged_wired_(params.flagged) {
  const double period = context.sample_period_s();
  channels_ = context.wired_dim("signal", params.group_size > 0 ? static_cast<std::size_t>(params.group_size) : 2);
  group_size_ = params.group_size > 0 ? static_cast<std::size_t>(params.group_size) : channels_;
  if (group_size_ < 2) {
    throw ConfigError("/params/group_size", ": a group of " + std::to_string(group_size_) +
                                                " channel shares its residual with nobody; there is nothing to "
                                                "isolate, give 2 or more");
  }
  if (channels_ % group_size_ != 0) {
    throw ConfigError("/params/group_size", " = " + std::to_string(group_size_) + " does not divide the " +
                                                std::to_string(channels_) + " wired channels into whole groups");
  }
  groups_ = channels_ / group_size_;
  ticks_per_block_ = std::max(1, static_cast<int>(std::lround(params.block_s / period)));
  const double block_s = ticks_per_block_ * period;
  const double blocks_in_history = std::ceil(params.history_s / block_s - 1e-9);
  const double min_fault_blocks = std::ceil(params.min_fault_s / block_s - 1e-9);
  if (!(blocks_in_history <= 1e5)) {
    throw ConfigError("/params/history_s", " = " + format_number(params.history_s) + " s is more than 100000 blocks of " +
                                               format_number(block_s) + " s: make it shorter or block_s longer");
  }
  // The fit takes the intercept, the slope and the onset: it needs blocks beyond those three.
  if (!(blocks_in_history >= min_fault_blocks + 3.0)) {
    throw ConfigError("/params/history_s", " = " + format_number(params.history_s) + " s holds " +
                                               format_number(blocks_in_history) + " blocks of " +
                                               format_number(block_s) + " s; the fit needs min_fault_s (" +
                                               format_number(min_fault_blocks) +
                                               " blocks) and 3 more: make it longer or min_fault_s shorter");
  }
  capacity_ = static_cast<std::size_t>(blocks_in_history);
  min_fault_blocks_ = static_cast<std::size_t>(std::max(1.0, min_fault_blocks));
  const double alpha = std::clamp(block_s / params.false_alarm_interval_s, 1e-15, 0.5);
  // A decision takes the best of g channels at up to capacity - min_fault_blocks + 1 onsets each:
  // the margin holds alpha over all of them (Bonferroni), the fit test is one test. With
  // `substituted`, a decision that names nobody may judge each channel once more on its own
  // window (judge): g more tries at as many onsets.
  const double windows = substituted_ ? 2.0 : 1.0;
  const double tries = static_cast<double>(group_size_) * (blocks_in_history - std::max(1.0, min_fault_blocks) + 1.0);
  margin_ = chi_square_quantile(1.0, 1.0 - alpha / (windows * tries));
  // The hold's refutation is one test of the named channel's fit, at the naming's own margin over
  // one window of fits.
  hold_margin_ = chi_square_quantile(1.0, 1.0 - alpha / tries);
  fit_bound_.assign(capacity_ + 1, 0.0);
  for (std::size_t n = 4; n <= capacity_; ++n) {
    fit_bound_[n] = chi_square_quantile(static_cast<double>(n - 3), 1.0 - alpha);
  }
  const std::vector<double> density = channel_values(params.residual_noise_density, groups_, "residual_noise_density");
  inv_block_var_.resize(groups_);
  for (std::size_t g = 0; g < groups_; ++g) inv_block_var_[g] = block_s / (density[g] * density[g]);

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
  std::size_t next_input = kSubstituted;
  if (substituted_) {
    substituted_input_ = next_input++;
    // A virtual estimate for the independence rule: fed back from the readings' recovery.
    ports_.add_input(PortSpec{"substituted", channels_, std::string(kDimensionless),
                              "1 where reading i stands for nothing (its recovery is a virtual value)",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  if (loadable_) {
    loadable_input_ = next_input++;
    ports_.add_input(PortSpec{"loadable", channels_, std::string(kDimensionless),
                              "1 while channel j can carry load, 0 while it cannot (below 1/2: cannot; NaN: can)",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  if (flagged_wired_) {
    flagged_input_ = next_input++;
    ports_.add_input(PortSpec{"flagged", channels_, std::string(kDimensionless),
                              "1 where another part isolated channel j on the tick before (previous_tick)",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"fault", channels_, std::string(kDimensionless),
                             "1 while the channel is named: its reading explains the raised sum residual"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_type", channels_, std::string(kDimensionless),
                             "fault type code (fault_type.hpp): gain while named, else none"}
                        .sized_by("as `signal`"));

  sum_e_.assign(groups_, 0.0);
  sum_x_.assign(channels_, 0.0);
  usable_ticks_.assign(groups_, 0);
  block_e_.assign(groups_ * capacity_, 0.0);
  block_x_.assign(channels_ * capacity_, 0.0);
  block_usable_.assign(groups_ * capacity_, 0);
  block_substituted_.assign(channels_ * capacity_, 0);
  loaded_now_.assign(channels_, 1);
  block_loaded_.assign(channels_ * capacity_, 0);
  window_loaded_.assign(group_size_ * capacity_, 0);
  flagged_now_.assign(channels_, 0);
  shown_before_.assign(channels_, 0);
  block_flagged_.assign(channels_ * capacity_, 0);
  flagged_before_.assign(channels_, 0);
  onset_.assign(group_size_, 0);
  substituted_now_.assign(channels_, 0);
  unloaded_now_.assign(channels_, 1);
  named_.assign(groups_, -1);
  last_named_.assign(groups_, -1);
  hold_ = params.hold_until_refuted;
  held_.assign(groups_, -1);
  beta_.assign(groups_, 0.0);
  held_n_.assign(groups_, 0.0);
  held_e_.assign(groups_, 0.0);
  held_ee_.assign(groups_, 0.0);
  held_u_.assign(groups_, 0.0);
  held_uu_.assign(groups_, 0.0);
  held_loaded_blocks_.assign(groups_, 0);
  window_e_.assign(capacity_, 0.0);
  window_t_.assign(capacity_, 0.0);
  window_x_.assign(group_size_ * capacity_, 0.0);
}

void GainIsolator::reset() noexcept {
  std::fill(sum_e_.begin(), sum_e_.end(), 0.0);
  std::fill(sum_x_.begin(), sum_x_.end(), 0.0);
  std::fill(usable_ticks_.begin(), usable_ticks_.end(), 0);
  std::fill(block_usable_.begin(), block_usable_.end(), 0);
  std::fill(block_substituted_.begin(), block_substituted_.end(), 0);
  std::fill(loaded_now_.begin(), loaded_now_.end(), 1);
  std::fill(block_loaded_.begin(), block_loaded_.end(), 0);
  std::fill(flagged_now_.begin(), flagged_now_.end(), 0);
  std::fill(flagged_before_.begin(), flagged_before_.end(), 0);
  std::fill(shown_before_.begin(), shown_before_.end(), 0);
  std::fill(block_flagged_.begin(), block_flagged_.end(), 0);
  std::fill(substituted_now_.begin(), substituted_now_.end(), 0);
  std::fill(unloaded_now_.begin(), unloaded_now_.end(), 1);
  std::fill(named_.begin(), named_.end(), -1);
  std::fill(last_named_.begin(), last_named_.end(), -1);
  std::fill(held_.begin(), held_.end(), -1);
  std::fill(beta_.begin(), beta_.end(), 0.0);
  tick_in_block_ = 0;
  blocks_ = 0;
}

bool GainIsolator::block_residual(std::size_t group, std::size_t slot, long keep, double& e,
                                  long candidate) const noexcept {
  if (!block_usable_[group * capacity_ + slot]) return false;
  e = block_e_[group * capacity_ + slot];
  for (std::size_t j = 0; j < group_size_; ++j) {
    if (static_cast<long>(j) == keep || static_cast<long>(j) == candidate) continue;
    const std::size_t at = (group * group_size_ + j) * capacity_ + slot;
    if (block_substituted_[at] == kStoodForNothing) return false;
    if (block_substituted_[at] == kStoodForNothingInAir) e -= block_x_[at];
  }
  return true;
}

long GainIsolator::judge(std::size_t group) noexcept {
  const long named = judge_window(group, -1);
  if (named >= 0 || !substituted_) return named;
  // Nobody named on the blocks every channel stood for something on: a channel that stood for
  // nothing on some of them (flagged by another test, not yet typed) is judged on its own blocks
  // too, as the channel named last is. Its reading is still in e there, and if its gain is the
  // fault, its course is e's.
  const std::size_t filled = std::min(blocks_, capacity_);
  for (std::size_t j = 0; j < group_size_; ++j) {
    if (static_cast<long>(j) == last_named_[group]) continue;
    bool stood_for_nothing = false;
    for (std::size_t age = 0; age < filled && !stood_for_nothing; ++age) {
      const std::size_t slot = (blocks_ - 1 - age) % capacity_;
      stood_for_nothing = block_substituted_[(group * group_size_ + j) * capacity_ + slot] == kStoodForNothing;
    }
    if (stood_for_nothing && judge_window(group, static_cast<long>(j)) == static_cast<long>(j)) {
      return static_cast<long>(j);
    }
  }
  return -1;
}

long GainIsolator::judge_window(std::size_t group, long candidate) noexcept {
  // The window's usable blocks, oldest first. A reading that stood for nothing (frozen, clipped,
  // invalid, not yet typed) has an unknown course in e, which its neighbours' loads follow: a block
  // on which it could carry load is left out; a block it spent in the air takes it at its load
  // there, zero (e less its reading). The channel named last is kept as it reads: it stands for
  // nothing while it is typed, and its own course is the gain's; so is `candidate`, who alone may
  // then be named.
  const std::size_t filled = std::min(blocks_, capacity_);
  const long keep = last_named_[group];
  std::size_t n = 0;
  for (std::size_t age = filled; age-- > 0;) {
    const std::size_t slot = (blocks_ - 1 - age) % capacity_;
    double e = 0.0;
    if (!block_residual(group, slot, keep, e, candidate)) continue;
    for (std::size_t j = 0; j < group_size_; ++j) {
      const std::size_t at = (group * group_size_ + j) * capacity_ + slot;
      const bool as_read = static_cast<long>(j) == keep || static_cast<long>(j) == candidate;
      const bool in_air = !as_read && block_substituted_[at] == kStoodForNothingInAir;
      window_x_[j * capacity_ + n] = in_air ? 0.0 : block_x_[at];
      window_loaded_[j * capacity_ + n] = block_loaded_[at];
    }
    window_e_[n] = e;
    window_t_[n] = static_cast<double>(blocks_ - 1 - age);  // the block's index: a ramp is in time
    ++n;
  }
  if (n < min_fault_blocks_ + 3) return -1;
  const double count = static_cast<double>(n);
  double sum_e = 0.0, sum_ee = 0.0;
  for (std::size_t b = 0; b < n; ++b) {
    sum_e += window_e_[b];
    sum_ee += window_e_[b] * window_e_[b];
  }
  const double centred_ee = sum_ee - sum_e * sum_e / count;  // what the intercept alone leaves
  const double w = inv_block_var_[group];
  // What a regressor z (given by its sums over the window, z = 0 before the onset) explains of e
  // beside the intercept; a regressor that does not move explains nothing (and divides by nothing).
  // Also its coefficient, through `coefficient` when given (0 for a regressor that does not move).
  const auto explained = [&](double s_z, double s_zz, double s_ez, double* coefficient = nullptr) {
    const double spread = s_zz - s_z * s_z / count;
    if (coefficient != nullptr) *coefficient = 0.0;
    if (!(spread > 1e-12 * std::max(1.0, s_zz))) return 0.0;
    const double covariance = s_ez - sum_e * s_z / count;
    if (coefficient != nullptr) *coefficient = covariance / spread;
    return covariance * covariance / spread;
  };
  // The courses that are nobody's gain: a step and a ramp from an onset (an offset, a drift, the
  // reference's own move), whichever channel carries them.
  double nobody = 0.0;
  {
    // Suffix sums of e_b, t_b, t_b^2 and t_b e_b, t_b the block's index (blocks that were not
    // usable leave gaps: the ramp z_b = t_b - t_o is in time, not in usable blocks).
    double s_e = 0.0, s_t = 0.0, s_tt = 0.0, s_te = 0.0;
    for (std::size_t o = n; o-- > 0;) {
      const double t = window_t_[o];
      s_e += window_e_[o];
      s_t += t;
      s_tt += t * t;
      s_te += t * window_e_[o];
      const double m = static_cast<double>(n - o);
      if (n - o < min_fault_blocks_) continue;
      nobody = std::max(nobody, explained(m, m, s_e));
      nobody = std::max(nobody, explained(s_t - m * t, s_tt - 2.0 * t * s_t + m * t * t, s_te - t * s_e));
    }
  }
  double best = 0.0, runner_up = 0.0, best_beta = 0.0;  // runner_up: the best other channel
  long best_channel = -1;
  for (std::size_t j = 0; j < group_size_; ++j) {
    const double* x = window_x_.data() + j * capacity_;
    // Onsets from the latest allowed back to the window's start: suffix sums of z = x [b >= o].
    double s_z = 0.0, s_zz = 0.0, s_ez = 0.0, best_j = 0.0, beta_j = 0.0;
    onset_[j] = 0;
    for (std::size_t o = n; o-- > 0;) {
      s_z += x[o];
      s_zz += x[o] * x[o];
      s_ez += window_e_[o] * x[o];
      if (n - o < min_fault_blocks_) continue;
      double beta_o = 0.0;
      const double explained_o = explained(s_z, s_zz, s_ez, &beta_o);
      if (explained_o > best_j) {
        best_j = explained_o;
        beta_j = beta_o;
        onset_[j] = o;
      }
    }
    if (best_j > best) {
      runner_up = std::max(runner_up, best);
      best = best_j;
      best_beta = beta_j;
      best_channel = static_cast<long>(j);
    } else {
      runner_up = std::max(runner_up, best_j);
    }
  }
  // In units of the block mean's variance: GLRs, and what the fit leaves, a chi^2_{N-3}.
  const double left = std::max(0.0, centred_ee - best) * w;
  // The lead over the runner-up tells which channel; another part that raised its flag on the
  // best one at the onset the fit found (on that block or the next, in time: a step on its row)
  // has told it already, and at the same time. The lead over a step or a ramp (nobody's gain)
  // holds either way.
  bool isolated_elsewhere = false;
  if (flagged_wired_ && best_channel >= 0) {
    const std::size_t at = (group * group_size_ + static_cast<std::size_t>(best_channel)) * capacity_;
    const std::size_t onset_block = static_cast<std::size_t>(window_t_[onset_[static_cast<std::size_t>(best_channel)]]);
    for (std::size_t b = onset_block; b < std::min(blocks_, onset_block + 2) && !isolated_elsewhere; ++b) {
      isolated_elsewhere = block_flagged_[at + b % capacity_] != 0;
    }
  }
  const bool explains = best * w >= margin_ && (best - nobody) * w >= margin_ &&
                        ((best - runner_up) * w >= margin_ || isolated_elsewhere) && left <= fit_bound_[n];
  if (!explains || (candidate >= 0 && best_channel != candidate)) return -1;
  if (loadable_ && stuck_neighbour(best_channel, n)) return -1;
  beta_[group] = best_beta;  // the named channel's coefficient from its onset on
  return best_channel;
}

bool GainIsolator::stuck_neighbour(long named, std::size_t n) const noexcept {
  const std::size_t onset = onset_[static_cast<std::size_t>(named)];
  for (std::size_t j = 0; j < group_size_; ++j) {
    if (static_cast<long>(j) == named) continue;
    // Over the blocks from the onset on which j could carry load: how x_j and e moved.
    double count = 0.0, s_x = 0.0, s_xx = 0.0, s_e = 0.0, s_ee = 0.0;
    for (std::size_t b = onset; b < n; ++b) {
      if (!window_loaded_[j * capacity_ + b]) continue;
      const double x = window_x_[j * capacity_ + b], e = window_e_[b];
      count += 1.0;
      s_x += x;
      s_xx += x * x;
      s_e += e;
      s_ee += e * e;
    }
    if (count < static_cast<double>(min_fault_blocks_)) continue;
    const double spread_x = s_xx - s_x * s_x / count, spread_e = s_ee - s_e * s_e / count;
    if (spread_x < follow_ratio_ * follow_ratio_ * spread_e) return true;
  }
  return false;
}

bool GainIsolator::held_refuted(std::size_t group, bool alarm_down) noexcept {
  // The block just completed, taken as judge() takes blocks (block_residual).
  const std::size_t slot = (blocks_ - 1) % capacity_;
  const long held = held_[group];
  // A gain that stayed shows in e as soon as its pad carries load, and the alarm rises again: a
  // pad that could carry load for min_fault_s of blocks (every block without `loadable`) with the
  // alarm down is no longer held, whatever the fit says (a neighbour standing for nothing may
  // leave no block to fit). Blocks with the alarm up count only in the fit.
  const std::size_t own = (group * group_size_ + static_cast<std::size_t>(held)) * capacity_ + slot;
  if (alarm_down && (!loadable_ || block_loaded_[own])) held_loaded_blocks_[group] += 1;
  if (held_loaded_blocks_[group] >= min_fault_blocks_) return true;
  double e = 0.0;
  if (!block_residual(group, slot, held, e)) return false;
  const double u = e - beta_[group] * block_x_[own];
  held_n_[group] += 1.0;
  held_e_[group] += e;
  held_ee_[group] += e * e;
  held_u_[group] += u;
  held_uu_[group] += u * u;
  const double n = held_n_[group];
  const double rss_none = held_ee_[group] - held_e_[group] * held_e_[group] / n;
  const double rss_gain = held_uu_[group] - held_u_[group] * held_u_[group] / n;
  return (rss_gain - rss_none) * inv_block_var_[group] >= hold_margin_;
}

void GainIsolator::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto e = io.in(kSumResidual);
  const auto alarm = io.in(kAlarm);
  const auto fault = io.out(kFault);
  const auto fault_type = io.out(kFaultType);
  if (loadable_) {
    const auto loadable = io.in(loadable_input_);
    for (std::size_t j = 0; j < channels_; ++j) {
      const bool can_carry = !(loadable[j] < 0.5);  // NaN: can
      loaded_now_[j] &= can_carry ? 1 : 0;
      unloaded_now_[j] &= can_carry ? 0 : 1;
    }
  }
  if (flagged_wired_) {
    const auto flagged = io.in(flagged_input_);
    // A flag raised (not one held since), and not by this part's own name of the tick before:
    // that is no other part's word.
    for (std::size_t j = 0; j < channels_; ++j) {
      const char raised = std::isfinite(flagged[j]) && flagged[j] != 0.0 ? 1 : 0;
      flagged_now_[j] |= raised && !flagged_before_[j] && !shown_before_[j] ? 1 : 0;
      flagged_before_[j] = raised;
    }
  }
  if (substituted_) {
    const auto substituted = io.in(substituted_input_);
    for (std::size_t j = 0; j < channels_; ++j) {
      substituted_now_[j] |= !(substituted[j] < 0.5) ? 1 : 0;  // not finite: stood for nothing
    }
  }
  for (std::size_t g = 0; g < groups_; ++g) {
    bool finite = std::isfinite(e[g]);
    for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) finite = finite && std::isfinite(x[j]);
    if (!finite) continue;
    sum_e_[g] += e[g];
    for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) sum_x_[j] += x[j];
    ++usable_ticks_[g];
  }
  const bool block_ends = ++tick_in_block_ == ticks_per_block_;
  if (block_ends) {
    const std::size_t slot = blocks_ % capacity_;
    for (std::size_t g = 0; g < groups_; ++g) {
      const int used = usable_ticks_[g];
      const bool usable = 2 * used >= ticks_per_block_;
      block_usable_[g * capacity_ + slot] = usable ? 1 : 0;
      if (usable) {
        block_e_[g * capacity_ + slot] = sum_e_[g] / used;
        for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
          block_x_[j * capacity_ + slot] = sum_x_[j] / used;
        }
      }
      for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
        block_substituted_[j * capacity_ + slot] =
            !substituted_now_[j]             ? kStoodForSomething
            : loadable_ && unloaded_now_[j] ? kStoodForNothingInAir
                                            : kStoodForNothing;
        substituted_now_[j] = 0;
        unloaded_now_[j] = 1;
        block_loaded_[j * capacity_ + slot] = loaded_now_[j];
        loaded_now_[j] = 1;
        block_flagged_[j * capacity_ + slot] = flagged_now_[j];
        flagged_now_[j] = 0;
      }
      sum_e_[g] = 0.0;
      for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) sum_x_[j] = 0.0;
      usable_ticks_[g] = 0;
    }
    ++blocks_;
    tick_in_block_ = 0;
  }
  for (std::size_t g = 0; g < groups_; ++g) {
    bool raised = false;
    for (std::size_t j = g * group_size_; j < (g + 1) * group_size_; ++j) {
      raised = raised || (std::isfinite(alarm[j]) && alarm[j] != 0.0);  // as the other isolators read it
    }
    // A name the evidence no longer gives (the alarm fell, or a block's judgement named nobody):
    // with hold_until_refuted it is held from here until the blocks refute its gain.
    const auto hold_named = [&] {
      if (hold_ && named_[g] >= 0) {
        held_[g] = named_[g];
        held_n_[g] = held_e_[g] = held_ee_[g] = held_u_[g] = held_uu_[g] = 0.0;
        held_loaded_blocks_[g] = 0;
      }
      named_[g] = -1;
    };
    if (!raised) {
      hold_named();
      if (held_[g] >= 0 && block_ends && held_refuted(g, true)) held_[g] = -1;
    } else if (block_ends) {
      const long judged = judge(g);
      if (judged >= 0) {
        named_[g] = last_named_[g] = judged;
        held_[g] = -1;
      } else {
        hold_named();
        if (held_[g] >= 0 && held_refuted(g, false)) held_[g] = -1;
      }
    }
    const long shown = named_[g] >= 0 ? named_[g] : held_[g];
    for (std::size_t j = 0; j < group_size_; ++j) {
      const bool named = shown == static_cast<long>(j);
      fault[g * group_size_ + j] = named ? 1.0 : 0.0;
      shown_before_[g * group_size_ + j] = named ? 1 : 0;
      fault_type[g * group_size_ + j] = fault_code(named ? FaultType::gain : FaultType::none);
    }
  }
}

}  // namespace ftsense::generic
