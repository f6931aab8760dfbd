// The decisions of each tick, channel by channel, once the jump groups are judged: a decided jump's
// onset or end, then the frozen and saturation, spike, noise-burst, negative-reading and air tests
// (contact_force_fdi.hpp, "Tests"). Where several fire on one channel, `raise` keeps the type
// whose evidence ranks highest (`priority`, contact_force_fdi_detail.hpp).
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "contact_force_fdi_detail.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

void ContactForceFdi::decide_channels(std::span<const double> measured, std::span<const double> height,
                                      const GroupDecisions& groups, bool touching_down, double t) noexcept {
  const bool group_decided = groups.decided, group_confirmed = groups.confirmed;
  const bool late_decided = groups.late_decided, late_confirmed = groups.late_confirmed;
  const int min_airborne_samples = min_airborne_samples_;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    if (!std::isfinite(x)) continue;
    // The channel's jump, when its group is decided: the sum residual's group, then (inside a
    // touchdown guard) its foot's plane group; each with its own jump and load before it.
    // A jump of a channel flagged when it jumped is no onset: a stuck output's step back to its
    // load is its end, whichever test re-admitted it while the group was pending (the follow
    // test, on that very step).
    const bool in_air = height[j] > params_.airborne_height_m;
    const auto decide = [&](double jump, double load_before, bool from_flagged, bool gains_load) {
      if (corrects(c.type) && !gain_reads_air_level(c, x) && steps_back(jump, fault_size(c, t, load_before))) {
        // The fault ended with a jump back. In the air, where the reading is the fault itself, a
        // step back by half the fault's size is within steps_back's band and is a fault that
        // changed: there the reading must be back within its noise of 0 (else the mean of the
        // readings after the step decides: the air test, below).
        // But an offset that may be a gain, whose gain explained the residual better before the
        // step and whose load stepped with it as the gain implies, is a gain whose pad is
        // unloading: its reading falls by k times the load's fall, which steps back by about the
        // offset when the pad sheds its onset load within a jump window (a lift-off logged at
        // 200 Hz), and the residual then steps by the offset as an end's would. The
        // offset-or-gain test's own decision, taken on the step that would otherwise have ended
        // it (step_is_gains_load).
        if (gains_load) {
          if (c.type != FaultType::gain) take_gain(c, *onset_gain(c));
        } else if (!(in_air && c.fit_has_air) || std::abs(x) < params_.airborne_threshold_N) {
          clear(c);
        }
      } else if (c.type == FaultType::none && !from_flagged) {
        raise_jump_onset(c, jump, load_before, t);
      }
    };
    const bool first_member = group_decided && c.jump_member;
    const bool late_member = late_decided && c.late_member;
    if (first_member) c.jump_member = false;
    if (late_member) c.late_member = false;
    if (first_member && group_confirmed && late_member && late_confirmed && !c.late_from_flagged) {
      decide(c.jump_size + c.late_jump, c.jump_load_before, c.jump_from_flagged, false);  // both its steps: one onset
    } else if (late_member && late_confirmed && c.late_from_flagged) {
      decide(c.late_jump, c.late_load_before, true, false);  // a flagged member's end is its step back alone
    } else if (first_member && group_confirmed) {
      decide(c.jump_size, c.jump_load_before, c.jump_from_flagged, step_is_gains_load(c, c.jump_load_before));
    } else if (late_member && late_confirmed) {
      decide(c.late_jump, c.late_load_before, false, false);  // a healthy channel's (flagged: above)
    }
    const std::size_t foot = channel_foot_[j];
    if (c.relation_member && relation_group_[foot] == 2) {
      c.relation_member = false;
      if (relation_verdict_[foot] != 0) {
        decide(c.relation_jump_size, c.relation_load_before, c.relation_from_flagged, false);
      } else if (relation_step_known_[foot] == 0 && c.type == FaultType::none && !c.relation_from_flagged &&
                 residual_before_known_ && c.relation_load_before > params_.airborne_threshold_N &&
                 x > params_.airborne_threshold_N) {
        // The plane could not judge it (the foot was not in full contact over the windows): the
        // sum residual does, once the guard is over, against its mean before the guard. Only a
        // step between two loads: one from or to the pad's zero level is its contact coming or
        // going (a sole rolling off or onto it as the feet trade load).
        c.onset_after_guard = true;
        c.guard_onset_jump = c.relation_jump_size;
        c.guard_onset_load = c.relation_load_before;
        c.guard_onset_before = residual_before_touchdown_;
        c.guard_onset_guard_began_s = guard_began_s_;
        c.guard_onset_since_s = t;  // the group's stamp: its foot's candidates decided this tick
        c.guard_onset_plane_group = relation_group_size_[foot];  // every member, qualifying or not
        guard_onsets_clear_ticks_ = 0;
      }
    }
    // Frozen / saturation.
    if (repeat_test_off_ && params_.upper_limit_N > 0.0 && x >= params_.upper_limit_N - repeat_band_N_) {
      // Without the repeat test, a reading at the top of the stated range is saturation on its tick.
      raise(c, FaultType::saturation, t);
    } else if (c.stale_count >= frozen_ticks_) {
      // Saturation: stuck at the top of the range, or at the largest load the channel has shown,
      // or stuck again at the value of its previous stuck episode after moving in between (a
      // clipped load comes back to the same ceiling; a frozen sensor does not leave and return).
      const bool loaded = x > params_.airborne_threshold_N;
      const bool at_limit = params_.upper_limit_N > 0.0 && x >= params_.upper_limit_N - repeat_band_N_;
      const bool at_max = at_limit || (loaded && x >= c.max_seen - repeat_band_N_);
      const bool same_ceiling = loaded && std::abs(x - c.last_stale_value) <= repeat_band_N_;
      if (c.stale_count == frozen_ticks_) {
        c.stale_episodes = same_ceiling ? c.stale_episodes + 1 : 1;
        c.last_stale_value = x;
      }
      raise(c, at_max || c.stale_episodes >= 2 ? FaultType::saturation : FaultType::frozen, t);
      if (c.stale_episodes >= 2 && c.type == FaultType::frozen) c.type = FaultType::saturation;
      if (loaded) c.ceiling_N = x;  // stuck under load: a level it may be clipped at again
    } else if (c.type == FaultType::none && c.stale_count >= 1 && !in_air && std::isfinite(c.ceiling_N) &&
               std::abs(x - c.ceiling_N) <= repeat_band_N_ && std::isfinite(c.last_virtual) &&
               c.last_virtual - x > params_.sum_threshold_N) {
      // Back on the level it was last found stuck at under load, while the total force leaves it more.
      raise(c, FaultType::saturation, t);
    } else if ((c.type == FaultType::frozen || c.type == FaultType::saturation) && c.stale_count == 0 &&
               !c.frozen_by_follow) {
      if (c.clear_since < 0) c.clear_since = t;
      if (t - c.clear_since >= params_.clear_s && t - c.flagged_since >= params_.hold_s) clear(c);
    }
    // Spikes. While the channel is flagged as a noise burst, the spikes seen are that noise's own
    // tails: the noise test alone judges when it ends, and the spike episode ends with it.
    if (c.spikes.running()) {
      if (c.type != FaultType::noise) raise(c, FaultType::spikes, t);
    } else if (c.type == FaultType::spikes) {
      clear(c);
    }
    // Noise burst: most second differences far above their healthy spread (counted as the ring
    // fills), and the window rougher than it moves (summed only then: a rare event).
    const int noisy = c.noisy_count;
    bool rough = false;
    if (noisy * 2 > noise_window_ticks_) {
      double d2_power = 0.0, d1_power = 0.0;
      for (std::size_t i = 0; i < c.second_diff.size(); ++i) {
        d2_power += c.second_diff[i] * c.second_diff[i];
        d1_power += c.first_diff[i] * c.first_diff[i];
      }
      rough = d2_power > d1_power;
    }
    // Not raised while a landing rings in the window: the foot bounces on its pads for tens of
    // milliseconds (a few ticks of a slow log), and the other foot's pads ring with the impact.
    if (noisy * 2 > noise_window_ticks_ && rough && !touching_down) {
      raise(c, FaultType::noise, t);
    } else if (c.type == FaultType::noise && noisy * 4 < noise_window_ticks_) {
      if (c.clear_since < 0) c.clear_since = t;
      if (t - c.clear_since >= params_.clear_s && t - c.flagged_since >= params_.hold_s) {
        clear(c);
        c.spikes.end();
      }
    }
    // Negative reading under load (its evidence: observe_evidence, contact_force_fdi_evidence.cpp).
    if (c.sign_fault && c.type == FaultType::gain) {
      double k = 0.0;
      if (c.positive_ticks >= min_airborne_samples) {
        clear(c);
      } else if (c.negative_fit.negative_slope(k)) {
        c.gain = k;
      }
    } else if (double k = 0.0; c.negative_ticks >= min_airborne_samples && !c.fit_has_air &&
                               c.negative_fit.v_hi - c.negative_fit.v_lo >= params_.sum_threshold_N &&
                               c.negative_fit.negative_slope(k) && priority(c.type) <= priority(FaultType::gain)) {
      raise(c, FaultType::gain, t);
      c.gain = k;
      c.sign_fault = true;
    }
    // Airborne pad: its reading is the fault itself.
    if (c.airborne_count >= min_airborne_samples) {
      const double mean = c.airborne_sum / c.airborne_count;
      if (c.type == FaultType::none && std::abs(mean) > params_.airborne_threshold_N) {
        raise(c, FaultType::offset, t);
        c.fit.clear(t);
        c.fit_has_air = false;
        c.air_block_reads_zero = false;  // a block read before the raise says nothing of the fault
        type_air_onset(c, x, t);
        if (c.type == FaultType::offset) type_sum_onset(c, x, t);
      }
      if (c.type == FaultType::offset || c.type == FaultType::drift) {
        const bool reads_zero = std::abs(mean) < params_.airborne_clear_N;
        const bool settled = c.airborne_count >= 3 * min_airborne_samples;
        if (!c.fit_has_air && reads_zero && !settled) {
          // Raised by a jump and near zero in the air so far: wait until the mean settles before
          // fitting the air as an offset (which would hide a gain fault).
        } else if (!c.fit_has_air && reads_zero) {
          // Raised by a jump, zero in the air: a gain fault if the pad was loaded, else over. A
          // pad that kept under a tenth of its load reads nothing, not a scale of it: its output
          // is dead (frozen near zero) and is substituted; dividing by k would blow it up.
          if (const auto k = onset_gain(c)) {
            if (std::abs(*k) >= kMinGain) {
              take_gain(c, *k);
            } else {
              c.type = FaultType::frozen;
              c.frozen_by_follow = true;  // re-admitted only when the reading follows the load again
            }
          } else {
            clear(c);
          }
        } else if (c.fit_has_air && ((std::abs(mean) < params_.airborne_clear_N && settled) || c.air_block_reads_zero) &&
                   t - c.flagged_since >= params_.hold_s) {
          clear(c);  // reads zero in the air again (this swing, or its latest block): the offset or drift is over
          // Judged healthy from here: the swing's mean, which still holds the fault's readings,
          // starts again (else the air test's raise above would take it back on the next tick).
          c.airborne_sum = c.airborne_u_sum = c.airborne_uu_sum = c.airborne_ux_sum = 0.0;
          c.airborne_count = 0;
          c.air_window_flagged = false;
        } else {
          // The air measures directly: drop the jump's estimate, or the level before a step in flight.
          if (!c.fit_has_air || c.air_refit) c.fit.clear(t);
          c.air_refit = false;
          c.fit_has_air = true;
          c.fit.add(t, x, 1.0);
          double a = c.offset, s = 0.0;
          c.fit.solve(a, s);
          // A drift when the slope stands out of the readings' noise: beyond relation_z_ of its
          // standard errors (the decision is taken again every tick: alpha = T / interval).
          // Until the swing's mean has settled, the type stays as it is (the fit spans the
          // swings before: a drift stays a drift at the start of the next).
          const bool drifting = settled ? std::abs(s) * c.fit.slope_scale() > relation_z_ * reading_sigma_N_
                                        : c.type == FaultType::drift;
          c.type = drifting ? FaultType::drift : FaultType::offset;
          c.offset = drifting ? a : c.fit.sb / c.fit.n;
          c.slope = drifting ? s : 0.0;
        }
      }
    }
  }

}

}  // namespace ftsense::biped
