// Gain faults: the offset-or-gain test on a jump's onset, the gain's refit against the leave-one-out force,
// and the stance regression of the sum residual on each channel that names a gain no jump showed.
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>

#include "contact_force_fdi_detail.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

void ContactForceFdi::offset_or_gain_test(Channel& c, double reading, bool airborne, double residual) noexcept {
  // Raised by a jump on a loaded pad and not yet seen in the air: x = L + b and x = k L, with
  // k = 1 + b / L0 (L0 the load before the jump), fit the onset alike; they part as the load moves.
  if (c.type != FaultType::offset || c.fit_has_air || !c.following || !std::isfinite(reading)) return;
  const auto k = onset_gain(c);
  if (!k || std::abs(*k) < kMinGain) return;  // none, or a dead output (not a scale): left to the air test
  // The residual takes this channel as x - b; taken as x / k instead it moves by x / k - (x - b).
  const double as_gain = airborne ? residual : residual - (reading - c.offset) + reading / *k;
  c.offset_power += residual * residual;
  c.gain_power += as_gain * as_gain;
  // Judged once the load has moved from L0, where both models meet, by twice the total force's
  // own error bound (not the span since the smoother settled: the load may have moved most of
  // the way within that settling); the gain must leave under half the offset's residual power (a
  // clear win, not a tie on noise).
  c.load_move_from_onset = std::max(c.load_move_from_onset, std::abs(c.virtual_smoothed - c.onset_load));
  if (c.load_move_from_onset < 2.0 * params_.sum_threshold_N) return;
  if (gain_leads(c)) take_gain(c, *k);
}

bool ContactForceFdi::gain_leads(const Channel& c) const noexcept {
  return c.following && offset_may_be_gain(c) && c.gain_power < 0.5 * c.offset_power;
}

bool ContactForceFdi::step_is_gains_load(const Channel& c, double load_before) const noexcept {
  if (!c.jump_gain_led) return false;
  // An offset at the jump, taken for the gain since (the offset-or-gain test may decide on the tick
  // before the group is decided, within its window): the same step, judged with the gain it has.
  const bool taken = c.type == FaultType::gain;
  if (!taken && !offset_may_be_gain(c)) return false;
  const double k = taken ? c.gain : *onset_gain(c);
  return residual_steps_by(c.last_virtual - c.jump_virtual_before, (c.previous - load_before) / k,
                           params_.jump_confirm_N);
}

bool ContactForceFdi::offset_may_be_gain(const Channel& c) const noexcept {
  if (c.type != FaultType::offset || c.fit_has_air) return false;
  const auto k = onset_gain(c);
  return k && std::abs(*k) >= kMinGain;
}

std::optional<double> ContactForceFdi::onset_gain(const Channel& c) const noexcept {
  if (!(c.onset_load > params_.gain_min_load_N) || !(std::abs(c.offset) > 0.1 * c.onset_load)) {
    return std::nullopt;
  }
  return 1.0 + c.offset / c.onset_load;
}

void ContactForceFdi::refit_gain(Channel& c) noexcept {
  const SlopeFit& fit = c.gain_fit;
  if (fit.n < stance_min_ticks_ || fit.v_hi - fit.v_lo < params_.sum_threshold_N || !(fit.svv > 0.0)) return;
  const double k = fit.sxv / fit.svv;
  const double standard_error = std::sqrt(std::max(0.0, fit.sxx - k * fit.sxv) / ((fit.n - 1.0) * fit.svv));
  if (!(k >= kMinGain) || std::abs(k - c.gain) <= relation_z_ * standard_error ||
      std::abs(k / c.gain - 1.0) <= 0.5 * params_.gain_threshold) {
    return;
  }
  c.gain = k;
  // The gain test's window holds residuals computed with the old k (as when it refines k).
  restart_gain_window();
}

void ContactForceFdi::take_gain(Channel& c, double k) noexcept {
  c.type = FaultType::gain;
  c.gain = k;
  c.sign_fault = k < 0.0;  // re-admitted when it reads right side up under load
  // The stance regression's window holds residuals computed with this channel taken as x - b;
  // refining k on them would fit the change of correction, not the sensor. Start a new one.
  restart_gain_window();
}

void ContactForceFdi::gain_regression(std::span<const double> measured, std::span<const double> recovered,
                                      std::span<const double> height, double residual, bool usable,
                                      double t) noexcept {
  if (!usable) {  // the window keeps what it has; impacts and substitutions add nothing
    usable_ticks_in_a_row_ = 0;
    return;
  }
  // A channel re-typed on this tick after the recovered values and the residual were computed
  // with its correction before: the tick belongs to neither model, in any of the sums below (an
  // offset's 384 N correction on the tick it was taken as a gain was the new gain's first tick in
  // its stance comparison, and its weight alone made the reading win 49 ticks later: a x2 gain
  // dropped as its pad lifted; the joint test of all gains took it alike). A re-typing restarts
  // the window (take_gain) or the channel's stance sums (a new type); they start on the next tick.
  for (const Channel& c : channels_) {
    if (c.type != c.recovered_as) return;
  }
  // The sum residual as the jump test takes it (this tick's, the ring's newest), and its level
  // before this tick once settled over 2 clear_s of usable ticks (for a drift's end at once),
  // with that level's variance in units of the residual's (seeded_low_pass_variance).
  const double ring_now = residual_ring_[ring_back(residual_next_, residual_ring_.size(), 0)];
  const double a = residual_level_gain_;
  const bool settled = usable_ticks_in_a_row_ >= 2 * stance_min_ticks_;
  const double level_before = settled ? residual_level_ : std::numeric_limits<double>::quiet_NaN();
  const double seed_weight = residual_level_seed_weight_;  // before this tick's update
  if (!std::isfinite(ring_now) || !std::isfinite(residual)) {
    usable_ticks_in_a_row_ = 0;  // a residual too large to hold: the level starts again
  } else if (usable_ticks_in_a_row_ == 0) {
    residual_level_ = ring_now;
    corrected_level_ = residual;
    residual_level_seed_weight_ = 1.0;
    usable_ticks_in_a_row_ = 1;
  } else {
    residual_level_ += a * (ring_now - residual_level_);
    corrected_level_ += a * (residual - corrected_level_);
    residual_level_seed_weight_ *= 1.0 - a;
    usable_ticks_in_a_row_ = std::min(usable_ticks_in_a_row_ + 1, kCountCap);
  }
  const double f = gain_forgetting_;
  if (!gain_window_.add(recovered, height, params_.airborne_height_m, residual, f)) {
    restart_gain_window();
    return;
  }
  // The window since an unexplained residual's onset: opened on a usable tick while no channel is
  // flagged and the residual is off (as `unisolated` says), closed by any flag and after 3 windows,
  // not when the residual returns within its bound (a gain's does in every swing). So an earlier
  // excursion that resolved itself keeps the stances after it in the window (the 2 s window then
  // judges as before, or this one once 3 windows have passed).
  const bool none_flagged =
      std::all_of(channels_.begin(), channels_.end(), [](const Channel& c) { return c.type == FaultType::none; });
  if (since_unexplained_open_ && (!none_flagged || since_unexplained_.ticks >= 3 * gain_window_ticks_)) {
    since_unexplained_open_ = false;
  }
  if (!since_unexplained_open_ && none_flagged && std::abs(sum_filtered_) > params_.sum_threshold_N) {
    since_unexplained_.restart();
    since_unexplained_open_ = true;
  }
  if (since_unexplained_open_ && !since_unexplained_.add(recovered, height, params_.airborne_height_m, residual, f)) {
    since_unexplained_open_ = false;
  }
  // Every channel held as a gain, read as it is together with the others (the joint test below).
  {
    double joint_raw = residual;
    int gains = 0;
    bool same_set = true;
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      const bool gain = channels_[j].type == FaultType::gain;
      if (gain) {
        joint_raw += measured[j] - recovered[j];
        ++gains;
      }
      same_set = same_set && (joint_gain_set_[j] != 0) == gain;
      joint_gain_set_[j] = gain ? 1 : 0;
    }
    if (!same_set || gains < 2) {
      joint_raw_rr_ = joint_held_rr_ = 0.0;
      joint_gain_ticks_ = 0;
    }
    if (gains >= 2) {
      joint_raw_rr_ = f * joint_raw_rr_ + joint_raw * joint_raw;
      joint_held_rr_ = f * joint_held_rr_ + residual * residual;
      joint_gain_ticks_ = std::min(joint_gain_ticks_ + 1, kCountCap);
    }
  }
  // What the residual would be if a channel held as a gain fault were read as it is, against what
  // it is with the correction, both over the ticks since the correction was last set.
  // In stance, the same comparison for a gain and for an offset: an offset whose end stepped
  // under jump_threshold_N (no jump test sees it) leaves its correction in the residual while its
  // foot stays down, and the air test would only drop it at the next swing. For a drift, not by
  // that alone: its slope, fitted on a swing's readings, is extrapolated through the stance, and a
  // correction grown wrong by that is no sign the fault is over (a 12 N/s drift at 200 Hz was
  // dropped while 30 N, in a try). A drift's reading must also have stayed flat where the drift
  // would have shown (StancePowers::trend): a pad that stays loaded to the end of a log (a robot
  // that stops and stands) has no next swing, and its correction grew without bound. Only while
  // it is the one correction the residual carries: with two, the
  // one that ended and the one that did not both move it, and the one still faulty could win
  // first (a +48 N offset beside a +60 N one fading out). A pad in the air carries none (it is
  // recovered as 0, what it carries there).
  const double stance_bound = params_.gain_min_load_N * params_.gain_min_load_N;
  const int corrections = corrections_in_residual(height);
  for (std::size_t j = 0; j < gain_raw_rr_.size(); ++j) {
    const Channel& c = channels_[j];
    const bool on_ground = !(height[j] > params_.airborne_height_m);  // unknown: on the ground, as it is corrected
    const bool judged =
        (c.type == FaultType::gain || c.type == FaultType::offset || c.type == FaultType::drift) && on_ground;
    StancePowers& stance = stance_powers_[j];
    StancePowers& run = stance_cusum_[j];
    // A new stance, or sums taken for another correction (not rewritten when already fresh: most
    // channels most ticks).
    if (!judged) channels_[j].still_load_drift = false;  // its foot lifted: the stance it rose in is over
    if ((!judged || stance.type != c.type) && !(stance.fresh_for(c.type) && run.fresh_for(c.type))) {
      stance = run = StancePowers{.type = c.type};
      // Raised from the residual's ramp on a still load: the drift rose in this stance already.
      stance.rose_with_drift = c.type == FaultType::drift && c.still_load_drift;
    }
    const double raw = residual + measured[j] - recovered[j];
    if (c.type != FaultType::gain) {
      gain_raw_rr_[j] = gain_held_rr_[j] = 0.0;
      gain_held_ticks_[j] = 0;
    } else {
      gain_raw_rr_[j] = f * gain_raw_rr_[j] + raw * raw;
      gain_held_rr_[j] = f * gain_held_rr_[j] + residual * residual;
      gain_held_ticks_[j] = std::min(gain_held_ticks_[j] + 1, kCountCap);
    }
    if (!judged) {
      if (guard_powers_[j].ticks > 0) guard_powers_[j] = StancePowers{};
      continue;
    }
    // The guard's ticks, judged alone once it is over (compare_held_gain_in_guard).
    if (guard_powers_[j].ticks > 0) {
      const bool fresh = t - guard_powers_last_s_ < (jump_window_ticks_ + 0.5) * period_s_;
      const bool reading_won = fresh && c.type == FaultType::gain && corrections == 1 &&
                               guard_powers_[j].reading_wins(stance_min_ticks_, stance_bound);
      guard_powers_[j] = StancePowers{};
      if (reading_won) {
        clear(channels_[j]);
        restart_gain_window();
        return;
      }
    }
    // Two explanations of the stance, the correction and the reading as it is: the reading wins
    // when the correction leaves 4 times its residual power (twice its RMS), over clear_s of
    // usable ticks in which the correction itself moved the reading by gain_min_load_N RMS or
    // more (a smaller correction is within what the residual's own error can mimic: as a pad
    // unloads, the sum residual's error is as large as a gain's effect on its few newtons). An
    // offset that may yet be a gain must leave a quarter of that model's power too.
    // Over the stance so far; for an offset also over the ticks since the CUSUM of the reading's
    // lead was last at 0: its sums start again whenever the correction has won so far, so a
    // fault that ends late in a long stance is judged on the ticks since its end, not against
    // the stance it was right in. (Not for a gain: its stance so far judges it, as before.)
    // Summed only over ticks with this one correction in the residual: sums that held another's
    // would be judged once that one lifts or ends (a true +48 N offset, leading while a +60 N
    // one beside it had ended, was dropped the tick that one's foot lifted).
    if (corrections != 1) {
      const bool rose = stance.rose_with_drift;
      stance = run = StancePowers{.type = c.type};
      stance.rose_with_drift = rose;
      continue;
    }
    const double correction = measured[j] - recovered[j];
    stance.add(raw, residual, correction, t, period_s_);
    run.add(raw, residual, correction, t, period_s_);
    if (c.type == FaultType::offset && !c.fit_has_air) {
      if (const auto k = onset_gain(c); k && std::abs(*k) >= kMinGain) {
        const double as_gain = residual - recovered[j] + measured[j] / *k;
        const double gain_correction = measured[j] - measured[j] / *k;
        stance.add_gain_model(as_gain, gain_correction);
        run.add_gain_model(as_gain, gain_correction);
      }
    }
    if (!run.reading_leads()) run = StancePowers{.type = c.type};
    // A drift that ended at once (its cause gone, its sensor re-zeroed) steps its reading and its
    // foot's summed reading back by its size, on a tick within a jump window before it began to
    // lead (c.stepped_back_s: load moving between the foot's pads leaves that sum alone), and the
    // sum residual by as much: its level before, and its mean since (StancePowers::stepped_back;
    // load moving between feet leaves the residual alone).
    if (c.type == FaultType::drift && run.ticks == 1) {
      const bool reading_stepped = t - c.stepped_back_s < (jump_window_ticks_ + 0.5) * period_s_;
      run.level_before = reading_stepped ? level_before : std::numeric_limits<double>::quiet_NaN();
      run.level_variance = seeded_low_pass_variance(a, seed_weight);
      run.correction_before = correction;
    }
    if (c.type == FaultType::drift && run.ticks > 0) run.level_sum += ring_now;
    // A drift, only since the reading last led and only where the reading stayed flat: its slope
    // extrapolated through a stance may grow wrong while the drift goes on. A window that shows a
    // slope is closed and the next one judged afresh (the load's own moves in a walking stance
    // before the robot stood still are no drift after it).
    bool flat = false;
    if (c.type == FaultType::drift) {
      const StancePowers::Trend trend = run.trend(c.slope * period_s_, relation_z_);
      flat = trend == StancePowers::Trend::flat;
      if (trend == StancePowers::Trend::sloped) {
        run.trend_window.restart();
        run.level_before = std::numeric_limits<double>::quiet_NaN();  // the reading has moved since
      }
      // The reading as it is, flat over the stance where the drift would have shown, after a window
      // of the same stance in which it rose with the drift (its slope the fitted drift's sign),
      // and off the load by more than the residual's own error can mimic (gain_min_load_N): the
      // drift went on into this stance and stopped there, leaving its level, which the reading
      // keeps (a plateau). An offset at that level (the window's mean lead of the reading, over
      // clear_s at least) from here on: the slope extrapolated would grow past it until the
      // reading, still that far off, won the comparison and was re-admitted. A drift that ended
      // by fading out fell before its flat window (the reading's lead then is the total force's
      // own bias, not a fault: left to the comparison). Over the stance's own window, not the
      // one since the reading last led: while the correction is still about right the reading
      // does not lead.
      const StancePowers::Trend stance_trend = stance.trend(c.slope * period_s_, relation_z_);
      if (stance_trend == StancePowers::Trend::sloped) {
        stance.rose_with_drift = stance.trend_window.slope() * c.slope > 0.0;
        stance.trend_window.restart();
      }
      // (A still-load drift's lead is taken from the residual's healthy level it was raised on:
      // the total force's bias, which a walking stance averages out, stays in a standing one.)
      const double lead = stance.trend_window.mean() - (c.still_load_drift ? c.still_load_healthy_level : 0.0);
      if (stance_trend == StancePowers::Trend::flat && stance.rose_with_drift && corrections == 1 &&
          stance.trend_window.count() >= stance_min_ticks_ && std::abs(lead) > plateau_bar(c, stance.trend_window.count())) {
        hold_as_offset(channels_[j], lead);
        restart_gain_window();  // its window holds residuals taken with the drift's correction
        continue;
      }
    }
    // A drift whose reading stepped back to the load: that step, with the reading on the load since
    // (its mean lead within gain_min_load_N, what the residual's own error can mimic) is enough,
    // with the comparison. A drift regrowing after a fade never stepped.
    const auto ended_by_step = [&] {
      return std::abs(run.trend_window.mean()) <= params_.gain_min_load_N && run.stepped_back(relation_z_);
    };
    const bool wins = c.type == FaultType::drift
                          ? run.reading_wins(stance_min_ticks_, stance_bound) && (flat || ended_by_step())
                          : stance.reading_wins(stance_min_ticks_, stance_bound) ||
                                (c.type == FaultType::offset && run.reading_wins(stance_min_ticks_, stance_bound));
    if (wins && corrections == 1) {
      clear(channels_[j]);
      restart_gain_window();
      return;
    }
  }
  // Judge once per 10 ticks, and only over a full window; then the window since an unexplained
  // residual's onset, while no channel is flagged.
  if (gain_window_.ticks >= gain_window_ticks_ && gain_window_.ticks % 10 == 0 && gain_window_.rr > 0.0) {
    judge_gain_window(t);
  }
  if (since_unexplained_open_ && since_unexplained_.ticks % 10 == 0 &&
      std::all_of(channels_.begin(), channels_.end(), [](const Channel& c) { return c.type == FaultType::none; })) {
    judge_since_unexplained(t);
  }
}

void ContactForceFdi::compare_held_gain_in_guard(std::span<const double> measured, std::span<const double> recovered,
                                                 std::span<const double> height, double residual,
                                                 double t) noexcept {
  // A gain that ended while its pad was in the air lands reading its load again, its correction
  // x / k now wrong by d = x (1 / k - 1) in the sum residual. Judged only on the ticks after the
  // landing's guard, it was still held when the jump test resumed there, and that test took the
  // wrong correction's moves for its neighbours' jumps (a x0.5 gain that ended in the air: three
  // healthy pads raised as offsets 10 ms after the guard). So the ticks of its own foot's guard
  // get the stance comparison of their own, judged on the first usable tick after the guards
  // (within a jump window of the last: sums kept across a gap of unusable ticks would judge a
  // stance long over), before a group the jump test forms there has had its jump window. Apart
  // from the stance's: a gain that ends within the guard, after ticks on which it was right, is
  // judged after the guard as before. Only its own foot's landing: another foot's is no new
  // evidence of this pad, and its impact error would be judged against a gain held right.
  // Not judged inside the guard: the impact's error e of the total force enters both
  // explanations alike (the correction leaves e, or e + d where the gain has ended; the reading
  // leaves e - d, or e), but a pulse of e of d's sign and size, early in the guard, can make a
  // gain still right look ended over clear_s (a 300 N impact fading over 20 ms against
  // d = 150 N). Over the whole guard such a pulse is diluted by the ticks after it, where only d
  // remains; an error of d's sign and two thirds of its size that lasts the guard is not (the
  // reading wins where e > 2 |e - d|), as it would not be over clear_s after the guard.
  guard_powers_last_s_ = t;
  const int corrections = corrections_in_residual(height);
  bool retyped = false;
  for (const Channel& c : channels_) retyped = retyped || c.type != c.recovered_as;
  if (retyped) return;  // re-typed this tick: the tick belongs to neither model
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    const Channel& c = channels_[j];
    StancePowers& guard = guard_powers_[j];
    // Only while it is the one correction in the residual (as judged), on the ground.
    if (c.type != FaultType::gain || corrections != 1 || height[j] > params_.airborne_height_m) {
      if (guard.ticks > 0) guard = StancePowers{};
      continue;
    }
    if (!foot_landing(channel_foot_[j], t)) continue;  // another foot's guard
    const double correction = measured[j] - recovered[j];
    guard.add(residual + correction, residual, correction, t, period_s_);
  }
}

int ContactForceFdi::corrections_in_residual(std::span<const double> height) const noexcept {
  int corrections = 0;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    corrections += corrects(channels_[j].type) && !(height[j] > params_.airborne_height_m) ? 1 : 0;
  }
  return corrections;
}

void ContactForceFdi::GainWindow::resize(std::size_t channels) {
  xx.assign(channels, 0.0);
  xr.assign(channels, 0.0);
  x.assign(channels, 0.0);
  stance.assign(channels, StanceSums{});
  restart();
}

void ContactForceFdi::GainWindow::restart() noexcept {
  std::fill(xx.begin(), xx.end(), 0.0);
  std::fill(xr.begin(), xr.end(), 0.0);
  std::fill(x.begin(), x.end(), 0.0);
  std::fill(stance.begin(), stance.end(), StanceSums{});
  r = rr = weight = 0.0;
  ticks = 0;
}

bool ContactForceFdi::GainWindow::add(std::span<const double> recovered, std::span<const double> height,
                                      double airborne_height_m, double residual, double f) noexcept {
  for (std::size_t j = 0; j < xx.size(); ++j) {
    const double v = recovered[j];
    // A tick of unknown height is in no stance and closes none: neither on the ground nor in
    // the air (a foot pose lost for a few ticks splits no stance and is no air after one).
    const bool known = !std::isnan(height[j]);
    const bool on_ground = known && height[j] <= airborne_height_m;
    xx[j] = f * xx[j] + v * v;
    xr[j] = f * xr[j] + v * residual;
    x[j] = f * x[j] + v;
    // The same fit within each stance of the channel's point (each centred on its own means):
    // the current stance's sums, and the centred sums of the stances closed before it.
    StanceSums& g = stance[j];
    g.w *= f, g.x *= f, g.r *= f, g.xx *= f, g.xr *= f, g.closed_xx *= f, g.closed_xr *= f;
    g.air_after_stance *= f;
    if (on_ground) {
      g.w += 1.0, g.x += v, g.r += residual, g.xx += v * v, g.xr += v * residual;
    } else if (known) {
      if (g.w > 0.0) {
        g.closed_xx += centred(g.xx, g.x, g.x, g.w);
        g.closed_xr += centred(g.xr, g.x, g.r, g.w);
        g.w = g.x = g.r = g.xx = g.xr = 0.0;
        g.stance_closed = true;
      }
      if (g.stance_closed) g.air_after_stance += 1.0;
    }
  }
  r = f * r + residual;
  rr = f * rr + residual * residual;
  weight = f * weight + 1.0;
  // Saturates by whole windows of 10, so the judging cadence and a full window both hold.
  ticks = ticks < kCountCap ? ticks + 1 : ticks - 10 * (kCountCap / 20) + 1;
  return std::isfinite(rr);
}

bool ContactForceFdi::fits_a_gain_from_the_air(const GainWindow& w, std::size_t j, double slope) const noexcept {
  // A gain k > 0 of a reading that is positive on the whole has beta = 1 - 1/k < 1 (beyond: a
  // reading of the opposite sign, a sign flip, which reads negative). One that began in the air,
  // where its pad read its air level, took no step: r = beta N^_j, its residual at zero load
  // (the fit's intercept) within the residual's bound.
  const double zero_load_residual = (w.r - slope * w.x[j]) / w.weight;
  return !(slope >= 1.0 && w.x[j] > 0.0) && std::abs(zero_load_residual) <= params_.sum_threshold_N;
}

ContactForceFdi::GainFit ContactForceFdi::best_gain_fit(const GainWindow& w, double min_power,
                                                         bool only_gains_from_the_air) const noexcept {
  // The channel whose fit r ~ b + beta_j N^_j explains the most of the residual's variation.
  // With the intercept b, an offset anywhere (a constant r) is b, not a gain: through the origin
  // it would be fitted by beta_j N^_j of any pad that is loaded most of the time.
  GainFit fit{.best = w.xx.size()};
  const double r_mean = w.r / w.weight;
  fit.r_variation = w.rr - w.r * r_mean;
  if (!(fit.r_variation > 0.0)) return fit;
  for (std::size_t j = 0; j < w.xx.size(); ++j) {
    const Channel& c = channels_[j];
    // Hardly loaded: not blamed, but its share still counts against the best one's isolation (at
    // the end of a stance every pad of the foot unloads alike, and a loaded neighbour was blamed
    // for what such a pad explained better).
    const bool loaded = w.xx[j] >= min_power;
    const double x_variation = centred(w.xx[j], w.x[j], w.x[j], w.weight);
    const double covariation = w.xr[j] - w.x[j] * r_mean;
    if (!(x_variation > 0.0)) continue;
    const double explained = covariation * covariation / (x_variation * fit.r_variation);
    const double slope = covariation / x_variation;
    // A fit that is no gain begun in the air is no candidate there, but it explains the residual
    // all the same (a load shifting between the feet with the total force's error): a rival.
    if (only_gains_from_the_air && !fits_a_gain_from_the_air(w, j, slope)) {
      fit.second_explained = std::max(fit.second_explained, explained);
      continue;
    }
    const bool judged = c.type == FaultType::none || c.type == FaultType::gain;  // others: by their own evidence
    if (loaded && judged && explained > fit.explained) {
      fit.second_explained = std::max(fit.second_explained, fit.explained);
      fit.best = j;
      fit.explained = explained;
      fit.beta = slope;
      fit.x_variation = x_variation;
      fit.covariation = covariation;
    } else {
      fit.second_explained = std::max(fit.second_explained, explained);
    }
  }
  return fit;
}

bool ContactForceFdi::stances_confirm(const GainWindow& w, const GainFit& fit, double threshold) noexcept {
  const GainWindow::StanceSums& g = w.stance[fit.best];
  const double x_variation = g.closed_xx + (g.w > 0.0 ? centred(g.xx, g.x, g.x, g.w) : 0.0);
  const double covariation = g.closed_xr + (g.w > 0.0 ? centred(g.xr, g.x, g.r, g.w) : 0.0);
  const double stance_beta = x_variation > 0.0 ? covariation / x_variation : 0.0;
  return stance_beta * fit.beta > 0.0 && std::abs(stance_beta) > threshold;
}

void ContactForceFdi::judge_gain_window(double t) noexcept {
  GainWindow& w = gain_window_;
  // Re-admission by model comparison, once the correction has held for a window: a channel held
  // as a gain fault that carried load and whose reading, taken as it is, leaves no more residual
  // power than its correction does is healthy again (this needs no isolation: the pads of one
  // foot are fitted alike, so a small gain error on a healthy pad might never stand out).
  const double min_power = params_.gain_min_load_N * params_.gain_min_load_N * w.weight;
  bool readmitted = false;
  for (std::size_t j = 0; j < gain_raw_rr_.size(); ++j) {
    if (channels_[j].type == FaultType::gain && gain_held_ticks_[j] >= gain_window_ticks_ &&
        w.xx[j] >= min_power && gain_raw_rr_[j] <= gain_held_rr_[j]) {
      clear(channels_[j]);
      readmitted = true;
    }
  }
  // Two or more gains, none of which wins alone: each is judged with the others' corrections
  // still in the residual, so two wrong ones hold each other (a heel's chatter at 200 Hz swapped
  // load between two pads within a tick; taken for two jumps, they were typed gains once their
  // pads read zero in the air, and held for 15 s). Taken as they are together, their readings
  // leave a quarter of the residual power of all their corrections (the stance comparison's
  // margin): every one is healthy again. Not at equal powers: a true gain among them may leave
  // less than the wrong ones' corrections, and true gains whose errors cancel in the sum leave
  // the two alike.
  if (!readmitted && joint_gain_ticks_ >= gain_window_ticks_ && joint_held_rr_ > kReadingWinsPowerRatio * joint_raw_rr_) {
    bool loaded = true;
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      if (joint_gain_set_[j] != 0) loaded = loaded && w.xx[j] >= min_power;
    }
    for (std::size_t j = 0; j < channels_.size() && loaded; ++j) {
      if (joint_gain_set_[j] != 0) {
        clear(channels_[j]);
        readmitted = true;
      }
    }
  }
  if (readmitted) {
    restart_gain_window();
    return;
  }
  const GainFit fit = best_gain_fit(w, min_power);
  // The pads of one foot load together, so a gain fault on one is fitted almost as well by its
  // neighbours (the sum residual cannot see moments): blame a channel only when its fit stands out.
  // A strong fit that does not stand out is a fault that cannot be isolated: reported as such
  // (`unisolated`) until a window shows no strong fit or an isolated one.
  if (fit.best == w.xx.size() || fit.explained < params_.gain_explained) {
    gain_unisolated_ = false;
    return;
  }
  Channel& c = channels_[fit.best];
  const double threshold = c.type == FaultType::none ? params_.gain_threshold : 0.5 * params_.gain_threshold;
  if (std::abs(fit.beta) <= threshold) {
    gain_unisolated_ = false;
    return;
  }
  gain_unisolated_ = fit.explained - fit.second_explained < params_.gain_isolation_margin;
  if (gain_unisolated_) return;
  // A new gain must hold within each stance too: a fault that begins as the pad lands (an offset
  // b: r = 0 with N^ = 0 in the air before, r = b with N^ = N + b after) lies on a line across the
  // landing, but within a stance r stays b while N^ moves. Only a confirmation: within a stance
  // the limb dynamics follow the loads, too weak a test to raise a flag by itself.
  if (c.type == FaultType::none && !stances_confirm(w, fit, threshold)) return;
  // A gain reads its load N k times, so k is told from an additive error only where the load
  // moved. A new flag whose implied load N^ = x - r stayed within gain_min_load_N RMS over the
  // window (a robot standing while a pad drifts: r and x rise together, beta near 1, k = 10 from
  // the clamp below) is an additive fault, typed and sized from the sum residual's history.
  if (c.type == FaultType::none) {
    const double load_variation = fit.x_variation - 2.0 * fit.covariation + fit.r_variation;
    if (load_variation < min_power) {
      raise_still_load_fault(c, (w.x[fit.best] - w.r) / w.weight, t);
      restart_gain_window();
      return;
    }
  }
  // recovered_new = recovered (1 - beta): k_new = k / (1 - beta).
  double gain = (c.type == FaultType::gain ? c.gain : 1.0) / (1.0 - std::clamp(fit.beta, -5.0, 0.9));
  if (std::abs(gain) < kMinGain) gain = std::copysign(kMinGain, gain);  // the recovery divides by it
  if (c.type == FaultType::gain && std::abs(1.0 - 1.0 / gain) < 0.5 * params_.gain_threshold) {
    clear(c);  // the reading is its force again
  } else {
    raise(c, FaultType::gain, t);
    c.gain = gain;
  }
  // The window's residuals were computed with the old correction: start a new one.
  restart_gain_window();
}

void ContactForceFdi::judge_since_unexplained(double t) noexcept {
  // The same tests as the gain window's for a new flag, on the ticks since the residual left its
  // bound (clear_s of them at least), the best among the fits a gain begun in the air makes
  // (through zero load, k > 0) standing out of every other channel's fit. A gain reads its
  // load k times, so its residual follows the load to 0 in the air, where an additive fault's
  // stays: once the best channel's point has closed a stance within the window and been in the
  // air clear_s since, that is settled; before, a still reading on the ground (below) may be a
  // stuck sensor the fit mistakes. Still loads are left to the gain window (their type is the
  // residual's history, which this window does not hold).
  const GainWindow& w = since_unexplained_;
  if (w.ticks < stance_min_ticks_) return;
  const double min_power = params_.gain_min_load_N * params_.gain_min_load_N * w.weight;
  const GainFit fit = best_gain_fit(w, min_power, true);
  if (fit.best == w.xx.size() || fit.explained < params_.gain_explained ||
      std::abs(fit.beta) <= params_.gain_threshold ||
      fit.explained - fit.second_explained < params_.gain_isolation_margin) {
    return;
  }
  // Before its pad has been in the air after a stance (where a gain reads 0 as its load does and
  // an additive fault's residual stays), a reading that stayed still on the ground within the
  // window (its power about each stance's own mean, over the ticks its point was on the ground)
  // may be a stuck one whose load is the residual: its neighbour's fit is then a load shift
  // between them, not a gain. (Every channel is healthy while this window is judged.)
  if (w.stance[fit.best].air_after_stance < stance_min_ticks_) {
    const double still = params_.follow_ratio * params_.follow_ratio * fit.r_variation;
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      const GainWindow::StanceSums& g = w.stance[j];
      if (j == fit.best || !(g.w > 0.0 || g.stance_closed)) continue;  // never on the ground in the window
      const double power = g.closed_xx + (g.w > 0.0 ? centred(g.xx, g.x, g.x, g.w) : 0.0);
      if (!(power >= still)) return;
    }
  }
  if (!stances_confirm(w, fit, params_.gain_threshold)) return;
  if (fit.x_variation - 2.0 * fit.covariation + fit.r_variation < min_power) return;
  Channel& c = channels_[fit.best];
  double gain = 1.0 / (1.0 - std::clamp(fit.beta, -5.0, 0.9));
  if (std::abs(gain) < kMinGain) gain = std::copysign(kMinGain, gain);  // the recovery divides by it
  raise(c, FaultType::gain, t);
  c.gain = gain;
  since_unexplained_open_ = false;
  gain_unisolated_ = false;  // isolated now: the gain window, restarted below, judges again in a window
  // The gain window's residuals were computed without the correction: start a new one.
  restart_gain_window();
}

void ContactForceFdi::hold_as_offset(Channel& c, double level) noexcept {
  c.still_load_drift = false;
  c.type = FaultType::offset;
  c.offset = level;
  c.slope = 0.0;
  c.fit.clear(last_tick_s_);
  c.air_refit = c.fit_has_air;  // the air's next reading fits afresh, not on the drift's swings
  c.end_pending = false;        // an end judged by the drift's size: the next step is judged anew
}

void ContactForceFdi::restart_gain_window() noexcept {
  std::fill(joint_gain_set_.begin(), joint_gain_set_.end(), 0);
  joint_raw_rr_ = joint_held_rr_ = 0.0;
  joint_gain_ticks_ = 0;
  gain_window_.restart();
  std::fill(gain_raw_rr_.begin(), gain_raw_rr_.end(), 0.0);
  std::fill(gain_held_rr_.begin(), gain_held_rr_.end(), 0.0);
  std::fill(gain_held_ticks_.begin(), gain_held_ticks_.end(), 0);
  std::fill(stance_powers_.begin(), stance_powers_.end(), StancePowers{});
  std::fill(stance_cusum_.begin(), stance_cusum_.end(), StancePowers{});
  std::fill(guard_powers_.begin(), guard_powers_.end(), StancePowers{});
}

}  // namespace ftsense::biped
