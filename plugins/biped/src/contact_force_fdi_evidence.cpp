// The evidence of each tick, channel by channel (contact_force_fdi.hpp, "Tests"): the feet's
// touchdowns and summed readings, then each channel's jump candidates, repeats, spikes, noise,
// air readings and sign. Most decisions are taken later in the tick, once the jump groups are
// judged; here only what a reading settles on its own: a reading without a value is invalid (and a
// finite one re-admits it), a one-tick spike leaves its pending group, a flagged channel's step
// back by its fault's size opens its end's judgment.
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "contact_force_fdi_detail.hpp"
#include "ftsense/generic/median_of_three.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

ContactForceFdi::TickEvidence ContactForceFdi::observe_evidence(std::span<const double> measured,
                                                               std::span<const double> height, bool fz_ok,
                                                               int ticks_since_start, double t) noexcept {
  const double tick_noise = tick_noise_N_;
  double last_touchdown_s = -1e9;  // of any foot
  for (std::size_t f = 0; f < feet_; ++f) {
    bool any = false;
    for (std::size_t l = 0; l < feet_points_; ++l) any = any || height[f * feet_points_ + l] > params_.touchdown_height_m;
    if (foot_airborne_[f] && !any) last_touchdown_s_[f] = t;
    foot_airborne_[f] = any ? 1 : 0;
    last_touchdown_s = std::max(last_touchdown_s, last_touchdown_s_[f]);
  }
  const bool touching_down = t - last_touchdown_s < params_.touchdown_guard_s;
  // The sum residual before a touchdown's guard began (a later touchdown inside it keeps it):
  // what a fault's end seen inside the guard is judged against.
  if (touching_down && !was_touching_down_) {
    residual_before_known_ = residual_count_ >= static_cast<std::size_t>(jump_window_ticks_);
    residual_before_touchdown_ = recent_residual_mean();
    guard_began_s_ = t;
    // A jump still pending from the guard before would be judged across two landings, against a
    // bar learnt on one: dropped.
    for (auto& c : channels_) c.onset_after_guard = false;
  }
  was_touching_down_ = touching_down;
  // The second difference of each foot's summed reading: load moving between the pads of a foot
  // (a rocking or chattering foot) leaves it small, a pad's own noise does not. Unknown (taken as
  // large) while a pad has no value.
  for (std::size_t f = 0; f < feet_; ++f) {
    double sum = 0.0;
    bool known = true;
    for (std::size_t l = 0; l < feet_points_; ++l) {
      const double x = measured[f * feet_points_ + l];
      known = known && std::isfinite(x);
      sum += x;
    }
    foot_d2_[f] = known && foot_sum_ticks_[f] >= 2 ? sum - 2.0 * foot_sum_[f][0] + foot_sum_[f][1]
                                                   : std::numeric_limits<double>::infinity();
    foot_sum_[f][1] = foot_sum_[f][0];
    foot_sum_[f][0] = sum;
    foot_sum_ticks_[f] = known ? std::min(foot_sum_ticks_[f] + 1, 2) : 0;
    // Its pads whose readings are not their loads (as flagged until this tick): substituted
    // from the total force under load, or reading a noise burst. The summed reading then does not
    // cancel load moving between them and the others.
    foot_unread_[f] = 0;
    for (std::size_t l = 0; l < feet_points_; ++l) foot_unread_[f] += unread(f * feet_points_ + l, height) ? 1 : 0;
    foot_landing_pads_[f] = 0;
    for (std::size_t l = 0; l < feet_points_; ++l) {
      const std::size_t j = f * feet_points_ + l;
      const Channel& c = channels_[j];
      const bool known = ticks_since_start > 0;  // a previous reading to step from
      const bool lands = known && pad_lands(c, measured[j], height[j]);
      const bool step = lands || (known && ring_step(c, measured[j], height[j], t));
      landing_state_[j] = static_cast<char>(lands ? kLands : step ? kRingStep : kNoLandingStep);
      foot_landing_pads_[f] += step ? 1 : 0;
    }
  }
  const double foot_noise = foot_noise_N_;
  int jump_candidates = 0;
  bool group_emptied = false;  // every member of the pending group was a one-tick spike
  bool any_step = false;  // a channel stepped this tick (the still-reading test's window restarts)
  double jump_sum = 0.0;
  int late_candidates = 0;  // healthy channels stepping while a group is pending
  double late_jump_sum = 0.0;
  double raw_sum = 0.0;
  double median_lag_correction = 0.0;  // for the last tick's residual (judge_jump_groups)
  bool all_finite_readings = true;  // the gain test takes only ticks where every channel has a value
  // A gain fault's reading enters the jump test's residual as x / k (the loop below): a gain set, refitted or
  // dropped on a loaded pad steps that residual by x (1 / k_new - 1 / k_old) on the next tick,
  // which a group of jumps whose windows straddle it would take for its own step (a x0.5 gain that
  // ended in the air, dropped as its heel took 200 N: three healthy neighbours confirmed as
  // offsets 2 ms later). Counted from jump_confirm_N, the step the confirmation tells from none:
  // a sign flip's k, refined on every tick it is loaded, moves it by less (counted, it kept every
  // group from forming and the flip's end was judged 10 ms late). In the air, or without a
  // value, its reading is not in the residual as x / k.
  bool divisor_changed = false;
  bool any_on_ceiling = false;  // a healthy reading on a level it was found stuck at (below)
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    const bool airborne = height[j] > params_.airborne_height_m;
    c.on_ceiling = false;  // (set below, from a value)
    const double divisor = c.type == FaultType::gain ? c.gain : 1.0;
    if (divisor != c.residual_divisor && !airborne && std::isfinite(x) &&
        std::abs(x / divisor - x / c.residual_divisor) >= params_.jump_confirm_N) {
      divisor_changed = true;
    }
    c.residual_divisor = divisor;
    if (!std::isfinite(x)) {
      all_finite_readings = false;
      raise(c, FaultType::invalid, t);
      c.stale_count = 0;
      c.restart_air_readings();
      c.jump_pending = c.late_candidate = c.relation_pending = false;  // no candidate without a value
      c.median_gap = 0.0;
      raw_sum += c.recovered;
      continue;
    }
    // The sum residual of the jump test takes a gain fault's reading with its correction (a sign
    // flip's load changes, read twice over, must not make its neighbours' changes look like
    // steps), and a spiking channel's as the median of its last three readings (a 250 N spike
    // moves a 10 ms window's mean by 50 N at 500 Hz). Offsets stay as read: their correction
    // ends with the jump that ends them.
    // A median of three lags a step by a tick (at 200 Hz, 70 N as a spiking heel lands), which a
    // neighbour's step in the same window took for its confirmation: once the next reading shows
    // the step stayed (no spike returns within half its rise), the last tick's residual takes
    // the reading instead.
    if (c.type == FaultType::spikes && std::abs(c.median_gap) > params_.jump_threshold_N &&
        std::abs(x - c.previous) < 0.5 * std::abs(c.previous - c.previous2)) {
      median_lag_correction += c.median_gap;
    }
    c.median_gap = 0.0;
    if (c.type == FaultType::gain) {
      raw_sum += airborne ? 0.0 : x / c.gain;
    } else if (c.type == FaultType::spikes && ticks_since_start > 0) {
      const double median = generic::median_of_three(x, c.previous, c.previous2);
      raw_sum += median;
      c.median_gap = fz_ok ? x - median : 0.0;
    } else {
      raw_sum += x;
    }
    if (c.type == FaultType::invalid) clear(c);  // a finite value re-admits at once
    if (ticks_since_start > 0) {
      const double change = x - c.previous;
      // A drift's reading stepping back by about its size s on this tick (nearer -s than no
      // step), s beyond the noise of a tick's change, and its foot's summed reading stepping
      // alike (load moving between the foot's pads leaves that sum alone): a cue for the
      // stance comparison (gain_regression), not a decision.
      if (c.type == FaultType::drift) {
        const double size = fault_at(c, t);
        const std::size_t f = channel_foot_[j];
        const double foot_change = foot_sum_ticks_[f] >= 2 ? foot_sum_[f][0] - foot_sum_[f][1]
                                                           : std::numeric_limits<double>::quiet_NaN();
        if (std::abs(size) > step_back_bar_N_ && std::abs(change + size) < 0.5 * std::abs(size) &&
            std::abs(foot_change + size) < 0.5 * std::abs(size)) {
          c.stepped_back_s = t;
        }
      }
      // A pad on its zero level that may carry no more than a driver's zero clamp (in the air, or
      // on the ground with a load within the clamp and the total force's error) may repeat
      // itself: no evidence either way, so the run neither grows nor restarts. Any other value
      // repeated in the air is evidence (a noisy sensor does not repeat 1.3 N).
      const bool unloaded = airborne || (std::isfinite(c.last_virtual) && c.last_virtual < zero_evidence_above_N_);
      const bool unloaded_zero = unloaded && std::abs(x) <= repeat_band_N_;
      if (std::abs(change) > repeat_band_N_) {
        c.stale_count = 0;
      } else if (!unloaded_zero) {
        c.stale_count = std::min(c.stale_count + 1, kCountCap);
      }
      // A pad's own landing: a pad on the ground left no load by the others, reading its zero
      // level, takes its load back as the foot rolls onto it. That contact is as abrupt as a
      // foot's touchdown and rings alike (at 200 Hz: tens of newtons in one tick, chatter on and
      // off), so the jump and spike tests leave the pad alone while it rings: until its changes
      // have stayed below jump_threshold_N for jump_window_s, or while it steps to or from its
      // air level (its contact lost and made again: a heavy robot's heel bounces 8-10 ms apart), at
      // most touchdown_guard_s after the landing (a ring that has died out is over; a step after
      // it is judged like any other).
      // A fault that starts while it rings is left to the sum residual and the air test.
      const bool lands = landing_state_[j] == kLands;
      if (lands) {
        c.last_pad_landing_s = t;
        c.last_landing_ring_s = t;
      }
      // Rung until the tick before: this tick's change is what the tests below judge.
      const bool in_landing_guard = t - c.last_pad_landing_s < params_.touchdown_guard_s;
      const bool pad_landing =
          in_landing_guard && (t - c.last_landing_ring_s < params_.jump_window_s ||
                               (std::abs(change) > params_.jump_threshold_N && contact_step(c, x)));
      if (pad_landing && std::abs(change) > params_.jump_threshold_N) c.last_landing_ring_s = t;
      // A neighbour of this pad whose reading is not its load (substituted under load, or a
      // noise burst): the foot's sum then misses the load that moves between it and this pad (a
      // heel chattering on and off), so this pad's roughness is no verdict of noise, nor its
      // one-tick excursion one of a spike: not judged then.
      // (A channel flagged already keeps being judged, so that it can be cleared.)
      const bool neighbour_unread = foot_unread_[channel_foot_[j]] > (unread(j, height) ? 1 : 0);
      const double spike = c.previous - 0.5 * (x + c.previous2);
      const bool spikes_seen = !touching_down && !pad_landing;
      if (spikes_seen) c.spikes.see(period_s_);
      // A sensor's spike is in its foot's summed reading too (the sum's own spike, -d2 / 2, at
      // least half the pad's, same sign); load that rocks between the pads of a foot for a tick
      // (a pad chattering on and off the ground) is not. Unknown (a pad without a value): counted.
      const std::size_t foot = channel_foot_[j];
      const double foot_spike = -0.5 * foot_d2_[foot];
      const bool in_foot_sum = !std::isfinite(foot_spike) || foot_spike * spike >= 0.5 * spike * spike;
      // Nor is load that rocked (load_rocked: asked last, as it scans the foot).
      if (spikes_seen && std::abs(spike) > params_.spike_threshold_N &&
          std::abs(x - c.previous2) < 0.5 * params_.spike_threshold_N && in_foot_sum &&
          (!neighbour_unread || c.type == FaultType::spikes) && !load_rocked(j, spike, measured)) {
        c.spikes.spike(spike_rule_);
      }
      const double innovation = x - 2.0 * c.previous + c.previous2;
      // A pad making its contact (inside its landing's guard) whose reading leaves or regains its
      // air level within these three readings, none below it: its contact chatters (a 180 kg
      // biped's outer heel lets go for a tick every 6 ms for 0.14 s as its foot rolls onto it), the
      // sensor is not noisy. A contact does not pull, a noise burst does (on an unloaded pad half
      // its readings lie below the air level), and under load a burst's readings seldom fall to
      // it: a burst still shows (and one already flagged keeps being judged on every tick, as
      // beside an unread neighbour).
      const bool contact_chatter =
          in_landing_guard && std::abs(std::min({x, c.previous, c.previous2})) <= params_.airborne_threshold_N;
      c.noisy_count -= c.noisy_tick[c.second_diff_next];
      c.second_diff[c.second_diff_next] = std::abs(innovation);
      c.noisy_tick[c.second_diff_next] = std::abs(innovation) > tick_noise &&
                                                 std::abs(foot_d2_[channel_foot_[j]]) > foot_noise &&
                                                 (!(neighbour_unread || contact_chatter) || c.type == FaultType::noise)
                                             ? 1
                                             : 0;
      c.noisy_count += c.noisy_tick[c.second_diff_next];
      c.first_diff[c.second_diff_next] = std::abs(change);
      c.second_diff_next = ring_after(c.second_diff_next, c.second_diff.size());
      c.jump_pending = false;
      c.late_candidate = false;
      c.relation_pending = false;
      // A member of the pending group whose reading is back within half its jump of the reading
      // before it, on the tick after, jumped for one tick: a spike, not a step. At 200 Hz the
      // jump window is two ticks, and a 100 N spike moves its mean by 50 N. (Judged against the
      // reading before, not its trend: a noise burst's trend is its last swing, and extrapolated
      // it took a burst's swings for steps. So a step against a pad unloading as fast as half
      // the step per tick, at a slow log rate, leaves the group too: found by the other tests.)
      const auto back = [&](double jump) { return std::abs(x - c.previous2) < 0.5 * std::abs(jump); };
      bool spiked_back = false;  // its return is no step of its own (no late candidate)
      if (c.jump_member && group_pending_ && group_age_ == 1 && back(c.jump_size)) {
        spiked_back = true;
        c.jump_member = false;
        group_sum_ -= in_residual(c.type, c.gain, c.jump_size);
        --group_size_;
        group_emptied = group_emptied || group_size_ == 0;
      }
      if (c.late_member && late_pending_ && late_age_ == 1 && back(c.late_jump)) {
        c.late_member = false;
        late_sum_ -= in_residual(c.type, c.gain, c.late_jump);
        --late_size_;
      }
      // Likewise a member of its foot's plane group (inside a touchdown guard).
      if (c.relation_member && relation_group_[foot] == 1 && relation_group_age_[foot] == 1 &&
          back(c.relation_jump_size)) {
        c.relation_member = false;
        const std::size_t relations = unmeasured_.relations_per_foot();
        const double jump = in_residual(c.type, c.gain, c.relation_jump_size);
        for (std::size_t r = 0; r < relations; ++r) {
          relation_expect_[foot * relations + r] -= unmeasured_.relation_weight(j - foot * feet_points_, r) * jump;
        }
        bool members = false;
        for (std::size_t i = 0; i < feet_points_; ++i) members = members || channels_[foot * feet_points_ + i].relation_member;
        if (!members) relation_group_[foot] = 0;
      }
      // Any time but a landing: a rolling foot's pads change a few newtons per tick, far below
      // jump_threshold_N, and the sum-residual confirmation rejects what is not a sensor step.
      // Nor on a tick another pad of its foot lands or, ringing, jumps on or off: a heel landing
      // late jolts its neighbours by tens of newtons on that tick, which F_z misses as it does a
      // foot's impact (a 20 N jolt of a toe pad was confirmed an offset), and a pad chattering
      // on and off trades its load with them on each of its jumps. Only those ticks: kept shut
      // while the heel rang (10 ms and more), the test missed a gain that began 9 ms after such
      // a landing.
      const bool neighbour_landing = foot_landing_pads_[foot] > (landing_state_[j] != kNoLandingStep ? 1 : 0);
      const bool may_jump = !touching_down && !pad_landing && !neighbour_landing;
      // A noise burst's swings are the fault the channel is flagged for, not steps.
      const bool steps = std::abs(change) > params_.jump_threshold_N &&
                         std::abs(innovation) > params_.jump_threshold_N && c.type != FaultType::noise;
      // The still test's windows restart on a step: it may be a fault's onset or end the jump test
      // did not judge. But a landing foot's unflagged pads step as they take their loads (none of
      // them is named while its foot lands): no restart, so a window holds the load that landing
      // moves off the other foot's pads, which a stuck one among them does not follow. (Inside
      // its foot's guard the jump test judges no step: touching_down holds.)
      any_step = any_step || (steps && (c.type != FaultType::none || !foot_landing(foot, t)));
      if (steps && may_jump && !group_pending_ && !late_pending_) {
        c.jump_pending = true;
        c.jump_gain_led = gain_leads(c);  // this tick's powers are not yet added
        c.jump_virtual_before = c.last_virtual;
        c.jump_size = change;
        c.candidate_load = c.previous;
        c.candidate_flagged = c.type != FaultType::none;
        ++jump_candidates;
        // In the terms of the sum residual, which takes a gain fault's reading corrected.
        jump_sum += in_residual(c.type, c.gain, change);
      } else if (steps && may_jump && !late_pending_ && !spiked_back && fz_ok &&
                 residual_count_ == residual_ring_.size() &&
                 (c.type == FaultType::none ||
                  (c.jump_member && !c.end_pending && corrects(c.type) &&
                   steps_back(change, fault_size(c, t, c.previous))))) {
        // A healthy channel's step while a group awaits its confirmation (the other foot's pads
        // unloading at its lift-off, a fault starting within the jump window; a member of that
        // group too, as the load it moved keeps moving), or a member's step back by its fault's
        // size (the fault's end, which the end test below leaves to the group it is in): a late
        // group, decided with the pending one (judge_jump_groups), not lost.
        c.late_candidate = true;
        c.late_jump = change;
        c.late_load_before = c.previous;
        c.late_from_flagged = c.type != FaultType::none;
        ++late_candidates;
        late_jump_sum += in_residual(c.type, c.gain, change);  // as the sum residual takes it
      } else if (steps && may_jump && !late_pending_ && !c.jump_member && !c.end_pending && corrects(c.type) &&
                 fz_ok && residual_count_ == residual_ring_.size()) {
        // A step while another group awaits its confirmation (a landing foot's pads jumping as
        // it rolls on): judged on its own window, as a group of its own would be, when it steps
        // back by the fault's size (the fault may have ended; an onset on a healthy channel waits
        // for the next free group, as before).
        if (steps_back(change, fault_size(c, t, c.previous))) {
          c.end_pending = true;
          c.end_after_guard = false;
          c.end_jump = in_residual(c.type, c.gain, change);  // as the sum residual takes it
          // Before the pending group's jump, which the group's own confirmation then accounts for
          // (its step is added to what this end implies once the group is decided).
          c.end_before = group_before_;
          c.end_group = group_serial_;
          c.end_since_s = t;
          c.end_clear_ticks = 0;
        }
      } else if (steps && touching_down && !pad_landing && unmeasured_.relations_per_foot() > 0 &&
                 relation_group_[channel_foot_[j]] != 1) {  // 2: decided last tick, free again
        // Inside a touchdown guard the sum residual carries the impact; the foot's plane does not.
        c.relation_pending = true;
        c.relation_jump = change;
        c.relation_candidate_load = c.previous;
        c.candidate_flagged = c.type != FaultType::none;
      } else if (steps && touching_down && !pad_landing && !c.end_pending && corrects(c.type) &&
                 (c.type == FaultType::gain || c.fit_has_air) && !gain_reads_air_level(c, x) &&
                 t - last_touchdown_s_[channel_foot_[j]] >= params_.touchdown_guard_s && fz_ok &&
                 residual_before_known_) {
        // A step back by the fault's size on a foot that is not landing, while another foot is:
        // the fault may have ended. Only a fault whose model is settled (measured in the air, or
        // a gain): an offset raised by a jump may yet be a gain, whose error shrinks as its foot
        // hands load over at the landing, as an end would. The sum residual carries the other
        // foot's impact now, so it judges the step once the guard is over (the loads have
        // settled by then), against what it was before the guard (at 200 Hz a load shifting at
        // a landing moves a pad by tens of newtons in a tick: the residual, not the step, tells
        // a sensor's end).
        const double estimate = fault_size(c, t, c.previous);
        if (steps_back(change, estimate)) {
          c.end_pending = true;
          c.end_after_guard = true;
          // Ended, the fault leaves the residual by its size (a gain's reading is taken as x / k:
          // the load L = x_before / k then reads L / k): not by the step, which at a landing also
          // carries the load the foot hands over.
          c.end_jump = c.type == FaultType::gain ? -(1.0 - 1.0 / c.gain) * c.previous / c.gain : -estimate;
          c.end_before = residual_before_touchdown_;
          c.end_since_s = t;
          c.end_clear_ticks = 0;
        }
      }
    }
    if (airborne) {
      // A step in flight (a fault starting or ending in the air): the mean starts again there, and
      // so does the air's fit of the fault, at its next reading in the air, this swing or the
      // next (one line through the readings before and after a step would average the two
      // levels: a fault that ended mid-swing was kept at half its size).
      if (c.airborne_ticks > 0 && ticks_since_start > 0 && std::abs(x - c.previous) > params_.jump_threshold_N) {
        close_air_window(c);
        c.restart_air_readings();
        c.air_refit = c.fit_has_air;
      }
      ++c.airborne_ticks;
      if (c.airborne_ticks * period_s_ >= params_.airborne_settle_s) {
        if (c.airborne_count == 0) c.air_origin_s = t;
        const double u = t - c.air_origin_s;
        c.airborne_sum += x;
        c.airborne_u_sum += u;
        c.airborne_uu_sum += u * u;
        c.airborne_ux_sum += u * x;
        c.air_window_flagged = c.air_window_flagged || c.type != FaultType::none;
        ++c.airborne_count;
        // The latest block of min_airborne_samples readings: does it read zero? (A fault that
        // ends mid-swing, by a step too small to restart the mean, leaves the swing's mean
        // beyond airborne_clear_N to the landing; its last block does not.)
        c.air_block_sum += x;
        if (++c.air_block_count >= min_airborne_samples_) {
          c.air_block_reads_zero = std::abs(c.air_block_sum / c.air_block_count) < params_.airborne_clear_N;
          c.air_block_sum = 0.0;
          c.air_block_count = 0;
        }
      }
    } else {
      close_air_window(c);
      c.restart_air_readings();  // (air_refit stays until the air's fit next takes a reading)
    }
    c.max_seen = std::max(c.max_seen, x);
    if (x > c.ceiling_N + repeat_band_N_) c.ceiling_N = std::numeric_limits<double>::quiet_NaN();  // not clipped there
    // A healthy reading back on the level it was found stuck at under load: its load is not read
    // (a clip hides what it carries beyond that level), and leaving the level steps the sum
    // residual and its foot's plane by what it hid, as a neighbour's step would (the jump test's
    // groups). Only while not flagged: a flagged stuck pad is substituted, and the groups then
    // take their larger bar (judge_jump_groups), as before.
    c.on_ceiling = c.type == FaultType::none && std::abs(x - c.ceiling_N) <= repeat_band_N_ &&
                   x > params_.airborne_threshold_N;
    if (c.on_ceiling) {
      ceiling_read_s_ = t;
      any_on_ceiling = true;
    }
    // A pad only pushes: a loaded pad reading below -airborne_threshold_N is a negative offset
    // or a negative multiple of its load (a sign flip). The least-squares line of the reading on
    // the leave-one-out force (fitted in step once that force is known) tells them apart: slope
    // about 1, or k < 0; a pad read right side up again under load clears it.
    const bool shows_load = !airborne && std::isfinite(c.last_virtual) && c.last_virtual > params_.gain_min_load_N;
    if (!airborne && x < -params_.airborne_threshold_N) {
      c.negative_ticks = std::min(c.negative_ticks + 1, kCountCap);
      c.positive_ticks = 0;
    } else {
      c.negative_ticks = 0;
      c.positive_ticks = shows_load && x > params_.airborne_threshold_N ? std::min(c.positive_ticks + 1, kCountCap) : 0;
      if (!c.sign_fault) c.negative_fit = SlopeFit{};
    }
  }

  ticks_since_divisor_change_ = divisor_changed ? 0 : std::min(ticks_since_divisor_change_ + 1, kCountCap);
  ticks_since_ceiling_ = any_on_ceiling ? 0 : std::min(ticks_since_ceiling_ + 1, kCountCap);
  return {touching_down, jump_candidates, group_emptied, any_step, jump_sum, late_candidates, late_jump_sum,
          raw_sum, median_lag_correction, all_finite_readings, divisor_changed};
}

}  // namespace ftsense::biped
