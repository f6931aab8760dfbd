// The jump test's groups: a healthy pad does not step by tens of newtons in a tick while the
// total force stays put, so the channels that stepped together form a group, confirmed when the
// sum residual stepped by their sum over the window after the jump (contact_force_fdi.hpp, "jump").
// Ends and onsets seen inside a touchdown guard are judged once it is over.
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "contact_force_fdi_detail.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

ContactForceFdi::GroupDecisions ContactForceFdi::judge_jump_groups(std::span<const double> measured,
                                                                   std::span<const double> height, double fz,
                                                                   const TickEvidence& ev, double t) noexcept {
  const bool fz_ok = std::isfinite(fz);
  relation_jumps(measured, height, t);
  // Sum residual history for the jump confirmation.
  const double raw_residual = fz_ok ? ev.raw_sum - fz : 0.0;
  if (ev.median_lag_correction != 0.0 && residual_count_ > 0) {
    residual_ring_[ring_back(residual_next_, residual_ring_.size(), 0)] += ev.median_lag_correction;
  }
  residual_ring_[residual_next_] = raw_residual;
  residual_next_ = ring_after(residual_next_, residual_ring_.size());
  residual_count_ = std::min(residual_count_ + 1, residual_ring_.size());
  // The sum held before the jump: a corrected residual (last tick's, low-passed) already beyond
  // the total force's error bound holds a fault no test has named yet (a dead pad under a
  // landing heel), and loads moving in or out of it step the residual like a sensor would: its
  // steps are no evidence, and the other tests name that fault first.
  const bool sum_held = !residual_smoothed_started_ || std::abs(residual_smoothed_) <= params_.sum_threshold_N;
  // Nor while the jump window before this tick holds a change of a gain's correction.
  const bool divisor_settled = ticks_since_divisor_change_ >= jump_window_ticks_;
  // Nor while a healthy reading sat on a level it was found stuck at (Channel::on_ceiling) on
  // this tick or within that window: its load there is not read, and its leaving the level steps
  // the residual as a neighbour's step would (a pad clipped at its stance peak as the other foot
  // lands, every stride). (The window's oldest tick is jump_window_ticks_ ago.)
  const bool ceiling_clear = ticks_since_ceiling_ > jump_window_ticks_;
  if (ev.jump_candidates > 0 && fz_ok && sum_held && divisor_settled && ceiling_clear &&
      !unread_landing_may_explain(height, ev.jump_sum)) {
    group_pending_ = true;
    ++group_serial_;
    group_before_ = recent_residual_mean(1);  // the window before this tick's jump
    group_age_ = 0;
    group_sum_ = ev.jump_sum;
    group_size_ = ev.jump_candidates;
    for (auto& c : channels_) {
      c.jump_member = c.jump_pending;
      if (c.jump_member) {
        c.jump_load_before = c.candidate_load;
        c.jump_from_flagged = c.candidate_flagged;
      }
    }
  }
  // A late group forms only while no fault's end is pending: an end's residual step is judged
  // against the first group's decision alone.
  const auto ends_waiting = [&] {
    return std::any_of(channels_.begin(), channels_.end(), [](const Channel& c) { return c.end_pending; });
  };
  if (ev.late_candidates > 0 && group_pending_ && !ends_waiting()) {
    late_pending_ = true;
    late_age_ = 0;
    late_sum_ = ev.late_jump_sum;
    late_size_ = ev.late_candidates;
    for (auto& c : channels_) c.late_member = c.late_candidate;
  }
  // While a loaded channel is substituted from the total force, the sum residual carries that
  // channel's unmeasured changes, and while one reads a noise burst, its swings (a 10 ms mean of
  // 40 N noise moves by 13 N; spikes come too seldom to matter): confirming a jump then takes
  // three times the step, and while one is substituted at least sum_threshold_N, the bound of the
  // total force's error that its share carries (a substituted heel pad chattering on and off
  // the ground hands 40-55 N to its neighbours and back within a tick, which at 1 N of noise
  // would confirm their moves as a group of offsets).
  // When such a channel's foot is rolling on or off (some pads up), its load changes fast and
  // unmeasured, and no jump is confirmed at all.
  bool unmeasured_in_residual = false;  // a loaded channel substituted, or reading a noise burst
  bool substituted_loaded = false;
  bool substituting_rolling = false;
  bool uncorrected_loaded = false;  // a loaded channel flagged as anything but a corrected fault
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    const bool airborne = height[j] > params_.airborne_height_m;
    const bool substituted = channels_[j].type != FaultType::none && !own_estimate(channels_[j].type) && !airborne;
    const FaultType type = channels_[j].type;
    uncorrected_loaded = uncorrected_loaded || (type != FaultType::none && !corrects(type) && !airborne);
    const bool noisy_loaded = type == FaultType::noise && !airborne;
    unmeasured_in_residual = unmeasured_in_residual || substituted || noisy_loaded;
    substituted_loaded = substituted_loaded || substituted;
    substituting_rolling = substituting_rolling || (substituted && foot_airborne_[channel_foot_[j]] != 0);
  }
  bool group_dropped = false;
  if (ev.group_emptied && group_pending_) {
    group_pending_ = false;
    group_dropped = true;
  }
  if (substituting_rolling && group_pending_) {
    group_pending_ = false;
    group_dropped = true;
  }
  // A gain's correction changed within a pending group's window, or a healthy reading sat on a
  // level it was found stuck at: that step, or that unread load, is in the residual's.
  const bool residual_moved_unread = ev.divisor_changed || ticks_since_ceiling_ == 0;
  if (residual_moved_unread && group_pending_) {
    group_pending_ = false;
    group_dropped = true;
  }
  if ((substituting_rolling || residual_moved_unread) && (late_pending_ || group_deferred_)) {
    group_dropped = group_dropped || group_deferred_;
    late_pending_ = group_deferred_ = false;
    for (auto& c : channels_) c.late_member = false;
  }
  // Every late member spiked for a tick, and the first group is still in its window: it is
  // decided alone, as before.
  if (late_pending_ && late_size_ == 0 && !group_deferred_) late_pending_ = false;
  const double confirm_N = substituted_loaded    ? std::max(3.0 * params_.jump_confirm_N, params_.sum_threshold_N)
                           : unmeasured_in_residual ? 3.0 * params_.jump_confirm_N
                                                    : params_.jump_confirm_N;
  // Confirm (or drop) the pending group once the window after the jump is complete.
  bool group_confirmed = false;
  bool group_decided = false;
  if (group_pending_ && group_age_++ >= jump_window_ticks_ - 1) {
    group_pending_ = false;
    if (late_pending_) {
      // A late group's jump is in this window: decided with it, once its window is over.
      group_deferred_ = true;
    } else if (residual_count_ == residual_ring_.size()) {
      group_decided = true;
      const double step =
          recent_residual_mean() - recent_residual_mean(static_cast<std::size_t>(jump_window_ticks_));
      // Pads trading load jump in opposite directions and leave the residual alone: not a fault.
      group_confirmed = std::abs(group_sum_) >= confirm_N && residual_steps_by(step, group_sum_, confirm_N);
    } else {
      group_decided = true;
      group_dropped = true;
    }
  }
  // The late group, a jump window after its jump, with the first if that one is still undecided:
  // the residual's step from before the first group's jump is the first's sum, the late one's, or
  // both (a dropped first group: the late one's only); the hypothesis that passes the step test
  // and lies nearest is taken. (The first group's own window holds the late jump, so it cannot
  // be judged alone.)
  bool late_decided = false;
  bool late_confirmed = false;
  if (late_pending_ && late_age_++ >= jump_window_ticks_ - 1) {
    late_pending_ = false;
    late_decided = true;
    const bool first_open = group_deferred_;
    group_deferred_ = false;
    if (first_open) group_decided = true;
    if (residual_count_ == residual_ring_.size()) {
      const double step = recent_residual_mean() - group_before_;
      const double first = first_open ? group_sum_ : 0.0;
      double best = std::numeric_limits<double>::infinity();
      // Each group's own sum must reach the confirmation step, as it must alone (two moves under it
      // are no step of a sensor, even where the residual drifts by their sum).
      const auto consider = [&](double expected, bool with_first, bool with_late) {
        if ((with_first && std::abs(first) < confirm_N) || (with_late && std::abs(late_sum_) < confirm_N)) return;
        if (!residual_steps_by(step, expected, confirm_N) || std::abs(step - expected) >= best) return;
        best = std::abs(step - expected);
        group_confirmed = with_first;
        late_confirmed = with_late;
      };
      if (late_size_ > 0) consider(late_sum_, false, true);
      if (first_open) consider(first, true, false);
      if (first_open && late_size_ > 0) consider(first + late_sum_, true, true);
    } else if (first_open) {
      group_dropped = true;
    }
  }
  // Ends seen while this group was pending: its step, if it was one, is in theirs too.
  if (group_decided || group_dropped) {
    for (auto& c : channels_) {
      if (!c.end_pending || c.end_after_guard || c.end_group != group_serial_) continue;
      if (group_dropped) {
        c.end_pending = false;
      } else if (group_confirmed) {
        c.end_jump += group_sum_;
      }
    }
  }

  // A fault's end seen inside another foot's touchdown guard: once the guard is over and the
  // residual has had a jump window to settle, it must have stepped by what the end implies, as a
  // jump's group must (a healthy pad's move as the load shifts leaves the residual alone). One
  // seen while another group was pending: after its own jump window, by its step.
  // Two ends judged on one residual could each be matched by the step of one of them (a fault
  // that ended and a flagged pad that handed its load over): with more than one pending, none is
  // re-admitted this way.
  int ends_pending = 0;
  for (const auto& c : channels_) ends_pending += c.end_pending ? 1 : 0;
  for (auto& c : channels_) {
    if (!c.end_pending) continue;
    if (!corrects(c.type) ||
        t - c.end_since_s > guard_pending_limit_s_) {
      c.end_pending = false;  // re-typed, or the guards kept coming: left to the other tests
      continue;
    }
    if (c.end_after_guard && ev.touching_down) {
      c.end_clear_ticks = 0;  // a further landing: its impact must pass too
      continue;
    }
    if (!fz_ok) continue;
    if (++c.end_clear_ticks < jump_window_ticks_) continue;
    c.end_pending = false;
    if (ends_pending > 1) continue;
    // A gain's error in the residual scales with its load: one whose pad has since gone to its air
    // level left the residual with its load, ended or not (the next stance judges it).
    if (gain_reads_air_level(c, measured[static_cast<std::size_t>(&c - channels_.data())])) continue;
    if (residual_steps_by(recent_residual_mean() - c.end_before, c.end_jump, confirm_N)) clear(c);
  }

  // Onset jumps inside a touchdown guard that their foot's plane could not judge: once the guard
  // is over and the residual has had a jump window to settle, it must have stepped from its mean
  // before the guard by one of them, as an end seen there must, and by more than a landing moves
  // it on a healthy walk (z times the RMS of that step over the walk's healthy guards so far:
  // the total force's error before and after a landing differs by tens of newtons, where within
  // a jump window it barely moves). A pad's step in the guard is often load shifting with its
  // foot's other pads on the same tick: such a group is judged by its net step, and a group of
  // two or more cannot name its pad. One match alone is raised; two (or an end pending beside)
  // cannot be told apart, and none is.
  bool onsets_pending = false;
  for (const auto& c : channels_) onsets_pending = onsets_pending || c.onset_after_guard;
  if (onsets_pending) {
    // Dropped unjudged when the guards kept coming, or when a channel was raised or re-admitted
    // since the guard began: that moved the residual (offsets are in it as read), so its step no
    // longer measures these jumps alone.
    bool expired = false;
    for (const auto& c : channels_) {
      // Or when a healthy reading sat on a level it was found stuck at since the window before
      // the guard began (its oldest tick jump_window_ticks_ before; half a tick's margin for
      // timestamps that accumulate): its unread load is in that step too.
      expired = expired || (c.onset_after_guard && (t - c.guard_onset_since_s > guard_pending_limit_s_ ||
                                                    last_flag_change_s_ >= c.guard_onset_guard_began_s ||
                                                    ceiling_read_s_ >= c.guard_onset_guard_began_s -
                                                                           (jump_window_ticks_ + 0.5) * period_s_));
    }
    if (ev.touching_down) guard_onsets_clear_ticks_ = 0;
    if (!ev.touching_down && fz_ok && !expired) ++guard_onsets_clear_ticks_;
    if (expired || guard_onsets_clear_ticks_ >= jump_window_ticks_) {
      int matches = 0;
      std::size_t match = channels_.size();
      for (std::size_t j = 0; j < channels_.size() && !expired; ++j) {
        const Channel& c = channels_[j];
        if (!c.onset_after_guard) continue;
        const std::size_t foot = channel_foot_[j];
        double net = 0.0;
        bool first_of_group = true;
        for (std::size_t i = 0; i < feet_points_; ++i) {
          const std::size_t k = foot * feet_points_ + i;
          const Channel& o = channels_[k];
          if (!o.onset_after_guard || o.guard_onset_since_s != c.guard_onset_since_s) continue;
          first_of_group = first_of_group && k >= j;
          net += o.guard_onset_jump;
        }
        if (!first_of_group) continue;  // its group is judged once
        if (guard_step_count_ < kMinGuardSteps) continue;  // a landing's own step not known yet
        const double bar = landing_step_bar(confirm_N);
        if (std::abs(net) >= bar && residual_steps_by(recent_residual_mean() - c.guard_onset_before, net, bar)) {
          ++matches;
          // Nameable only when its whole plane group of that tick is the pad alone (the
          // qualifying members are among that group's).
          match = c.guard_onset_plane_group == 1 ? j : channels_.size();
        }
      }
      // The bar was learnt on guards with no channel flagged; a substituted, gain-corrected or
      // noisy channel moves the residual by what it does not read, an offset not at all and a
      // drift by its slope over the guard (a few newtons). Re-typed channels (an offset taken
      // for a gain or a frozen output) fall here too: raise() records only new flags.
      bool comparable = true;
      for (const auto& c : channels_) {
        comparable = comparable && (c.type == FaultType::none || c.type == FaultType::offset || c.type == FaultType::drift);
      }
      if (matches == 1 && match < channels_.size() && ends_pending == 0 && comparable) {
        Channel& c = channels_[match];
        if (c.type == FaultType::none && !(height[match] > params_.airborne_height_m)) {
          raise_jump_onset(c, c.guard_onset_jump, c.guard_onset_load, t);
        }
      }
      for (auto& c : channels_) c.onset_after_guard = false;
      guard_onsets_clear_ticks_ = 0;
    }
  }
  // The residual's step across each guard, a jump window after it, counted when no channel is
  // flagged and none was raised or re-admitted since the guard began (an onset judged there, or
  // found by another test, is no healthy landing).
  if (ev.touching_down) {
    guard_step_ticks_ = 0;
  } else if (guard_step_ticks_ >= 0 && fz_ok && ++guard_step_ticks_ >= jump_window_ticks_) {
    guard_step_ticks_ = -1;
    bool healthy = residual_before_known_ && last_flag_change_s_ < guard_began_s_;
    for (const auto& c : channels_) healthy = healthy && c.type == FaultType::none;
    if (healthy) {
      // Clipped at the bar once it is known: a fault not raised on this guard (ambiguous, or its
      // judgment still to come) would otherwise raise the bar for the rest of the walk; a
      // healthy step beyond z_g of the RMS is rare enough that the clip barely lowers it.
      double step = std::abs(recent_residual_mean() - residual_before_touchdown_);
      if (guard_step_count_ >= kMinGuardSteps) {
        step = std::min(step, landing_step_bar(params_.jump_confirm_N));
      }
      guard_step_square_ += step * step;
      ++guard_step_count_;
    }
  }

  // The feet's plane verdicts, taken before any member is raised (a raise sets the offset the
  // verdict's level check corrects by), and the size of each group decided this tick.
  for (std::size_t f = 0; f < relation_verdict_.size(); ++f) {
    relation_verdict_[f] = relation_group_[f] == 2 && relation_confirmed(f, measured, t) ? 1 : 0;
    relation_group_size_[f] = 0;
    for (std::size_t i = 0; i < feet_points_ && relation_group_[f] == 2; ++i) {
      relation_group_size_[f] += channels_[f * feet_points_ + i].relation_member ? 1 : 0;
    }
  }
  return {group_decided, group_confirmed, late_decided, late_confirmed, uncorrected_loaded};
}

}  // namespace ftsense::biped
