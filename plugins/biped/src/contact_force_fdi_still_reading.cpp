// Readings that stay still while their load moves: the still-reading test over a stance (a frozen output
// that keeps its noise), the follow test against the leave-one-out force, and the load such a fault implies.
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "contact_force_fdi_detail.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

void ContactForceFdi::still_reading_test(std::span<const double> measured,
                                         std::span<const double> height, double residual, bool usable,
                                         bool stepped, double t) noexcept {
  usable = usable && std::isfinite(residual);  // readings too large to sum leave it unknown
  if (usable) {
    residual_smoothed_ = residual_smoothed_started_ ? residual_smoothed_ + smoothing_ * (residual - residual_smoothed_)
                                                    : residual;
    residual_smoothed_started_ = true;
  }
  // The windows restart, once the smoothers have settled, when the residual is unknown, a channel
  // steps (a jump is the jump test's), a flag changes (the corrected residual changes meaning), or
  // a loaded channel's correction follows its load (gain) or replaces it (substituted, noise): a
  // wrong k or share moves the residual as that load moves, which a still neighbour would take.
  bool restart = !usable || stepped;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const bool airborne = height[j] > params_.airborne_height_m;
    restart = restart || c.type != c.still_window_type;
    c.still_window_type = c.type;
    // An offset raised by a jump under load and not yet told from a gain (offset_or_gain_test) is
    // corrected as x - b while it may scale with its load: not additive until decided.
    const bool undecided = c.type == FaultType::offset && !c.fit_has_air && onset_gain(c).has_value();
    const bool additive =
        (c.type == FaultType::offset && !undecided) || c.type == FaultType::drift || c.type == FaultType::spikes;
    restart = restart || (c.type != FaultType::none && !additive && !airborne);
  }
  if (restart) {
    for (StillWindow& w : still_windows_) w.active = false;
    still_window_settle_until_s_ = t + smoother_settle_s_;
    next_short_window_s_ = still_window_settle_until_s_ + short_window_stagger_s_;
    return;
  }
  if (t < still_window_settle_until_s_) return;
  const std::size_t n = channels_.size();
  for (std::size_t j = 0; j < n; ++j) {
    const Channel& c = channels_[j];
    smoothed_[j] = c.smoothed;
    judgeable_[j] = c.type == FaultType::none && !(height[j] > params_.airborne_height_m) && std::isfinite(measured[j]);
  }
  // A window opened on this tick (start_s == t) holds this tick's values only: judged from the next.
  const auto open = [&](std::size_t w) {
    StillWindow& window = still_windows_[w];
    window.active = true;
    window.start_s = t;
    window.residual_lo = window.residual_hi = residual_smoothed_;
    for (std::size_t j = 0; j < n; ++j) {
      const double x = smoothed_[j];
      still_lo_[w * n + j] = still_hi_[w * n + j] = x;
      since_low_min_[w * n + j] = since_low_max_[w * n + j] = x;
      since_high_min_[w * n + j] = since_high_max_[w * n + j] = x;
      still_grounded_[w * n + j] = channels_[j].type == FaultType::none && !(height[j] > params_.airborne_height_m);
    }
  };
  if (!still_windows_[kLongStillWindow].active) open(kLongStillWindow);
  if (t >= next_short_window_s_) {
    open(next_short_window_);
    next_short_window_ = next_short_window_ + 1 == kShortStillWindows ? 0 : next_short_window_ + 1;
    next_short_window_s_ = t + short_window_stagger_s_;
  }
  for (std::size_t w = 0; w < still_windows_.size(); ++w) {
    StillWindow& window = still_windows_[w];
    if (!window.active || window.start_s == t) continue;
    window.residual_lo = std::min(window.residual_lo, residual_smoothed_);
    window.residual_hi = std::max(window.residual_hi, residual_smoothed_);
    double* lo = still_lo_.data() + w * n;
    double* hi = still_hi_.data() + w * n;
    char* grounded = still_grounded_.data() + w * n;
    for (std::size_t j = 0; j < n; ++j) {
      lo[j] = std::min(lo[j], smoothed_[j]);
      hi[j] = std::max(hi[j], smoothed_[j]);
      grounded[j] = static_cast<char>(grounded[j] & judgeable_[j]);
    }
    if (w == kLongStillWindow) continue;  // judged by the whole range alone
    // Each reading's range since the residual was last near each extreme (within a quarter of
    // its bound: its noise does not take the start back into what happened before it moved).
    const bool near_low = residual_smoothed_ <= window.residual_lo + residual_near_N_;
    const bool near_high = residual_smoothed_ >= window.residual_hi - residual_near_N_;
    const auto track = [&](std::vector<double>& min, std::vector<double>& max, bool restart_range) {
      double* const lo_since = min.data() + w * n;
      double* const hi_since = max.data() + w * n;
      if (restart_range) {
        std::copy_n(smoothed_.data(), n, lo_since);
        std::copy_n(smoothed_.data(), n, hi_since);
        return;
      }
      for (std::size_t j = 0; j < n; ++j) {
        lo_since[j] = std::min(lo_since[j], smoothed_[j]);
        hi_since[j] = std::max(hi_since[j], smoothed_[j]);
      }
    };
    track(since_low_min_, since_low_max_, near_low);
    track(since_high_min_, since_high_max_, near_high);
  }
  // The long window first, then the short ones; a raise restarts them all on the next tick.
  for (std::size_t k = 0; k < still_windows_.size(); ++k) {
    const std::size_t w = k == 0 ? kLongStillWindow : k - 1;
    StillWindow& window = still_windows_[w];
    if (!window.active || window.start_s == t) continue;
    const double residual_span = window.residual_hi - window.residual_lo;
    // A window shorter than the smoother's settling measures the smoother, not the signals.
    if (residual_span < params_.sum_threshold_N || t - window.start_s < smoother_settle_s_) continue;
    // The residual has moved beyond the total force's error: one still reading explains it (its
    // load moved by that much unread); two or more cannot be told apart (cannot judge), none: some
    // other fault or the reference, left to the other tests.
    // A short window is a tenth of a second: slow loads barely move in it, and a reading that
    // sticks inside it (a saturation's ceiling reached) moved before the residual did. So it rules
    // a reading out only when it spanned beyond twice what a stuck one shows (still_band_N_) since
    // the residual was last near the extreme it moved away from (while it moved), and it names
    // one only when that one stayed within the band over the whole window.
    const bool short_window = w != kLongStillWindow;
    const double bar = short_window ? std::max(params_.follow_ratio * residual_span, 2.0 * still_band_N_)
                                    : params_.follow_ratio * residual_span;
    const bool fell = residual_smoothed_ - window.residual_lo < window.residual_hi - residual_smoothed_;
    std::size_t candidates = 0, culprit = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const Channel& c = channels_[j];
      const std::size_t i = w * n + j;
      const double moved = !short_window ? still_hi_[i] - still_lo_[i]
                           : fell        ? since_high_max_[i] - since_high_min_[i]   // from its high
                                         : since_low_max_[i] - since_low_min_[i];    // from its low
      // Under "j is stuck" its load is its leave-one-out force, x_j - r (both smoothed): a pad only
      // pushes, so one that would carry less than -airborne_threshold_N cannot be the one (a pad
      // reading 0 while the pads' sum reads too much); one stuck where its load came to 0 (a foot
      // about to lift) can.
      if (still_grounded_[i] != 0 && moved < bar &&
          c.smoothed - residual_smoothed_ > -params_.airborne_threshold_N) {
        ++candidates;
        culprit = j;
      }
    }
    window.active = false;  // judged: the long one opens afresh, a short one waits for its turn
    // A landing foot's pads take their loads each in its turn as the sole rolls on (a toe still at
    // its air level beside a loaded heel): such a pad may be the one, but is not named while its
    // foot lands (counted, it keeps any other from being named).
    if (candidates == 1 && !foot_landing(channel_foot_[culprit], t) &&
        (!short_window || still_hi_[w * n + culprit] - still_lo_[w * n + culprit] <= still_band_N_)) {
      raise_stuck(channels_[culprit], t);
      break;
    }
  }
}

void ContactForceFdi::follow_test(Channel& c, double reading, double virtual_force, double t) noexcept {
  const bool judged = c.type == FaultType::offset || c.type == FaultType::drift ||
                      (c.type == FaultType::frozen && c.frozen_by_follow);
  // The span is the fault's own output's: it starts once the smoothed reading has settled after
  // the step that raised the flag (a frozen output that jumped to 150 N would otherwise span the
  // smoother's rise to it).
  if (!judged || t - c.flagged_since < smoother_settle_s_) {
    c.following = false;
    return;
  }
  if (!std::isfinite(reading) || !std::isfinite(virtual_force)) return;
  const double smoothed = c.smoothed;
  if (!c.following) {
    c.following = true;
    c.offset_power = c.gain_power = 0.0;
    c.load_move_from_onset = 0.0;
    c.virtual_smoothed = virtual_force;
    c.reading_lo = c.reading_hi = smoothed;
    c.virtual_lo = c.virtual_hi = virtual_force;
    return;
  }
  c.virtual_smoothed += smoothing_ * (virtual_force - c.virtual_smoothed);
  c.reading_lo = std::min(c.reading_lo, smoothed);
  c.reading_hi = std::max(c.reading_hi, smoothed);
  c.virtual_lo = std::min(c.virtual_lo, c.virtual_smoothed);
  c.virtual_hi = std::max(c.virtual_hi, c.virtual_smoothed);
  const double load_span = c.virtual_hi - c.virtual_lo;
  const double reading_span = c.reading_hi - c.reading_lo;
  // A frozen output whose own reading moves by sum_threshold_N again, half as much as its load at
  // least, follows a load: a stuck sensor's noise never spans that, so the load's move need not
  // first exceed the force's error twice over.
  if (c.frozen_by_follow && reading_span >= params_.sum_threshold_N && reading_span >= 0.5 * load_span) {
    clear(c);
    return;
  }
  if (load_span < 2.0 * params_.sum_threshold_N) return;  // the load has not moved beyond the force's error
  if (!c.frozen_by_follow) {
    if (reading_span >= params_.follow_ratio * load_span) {
      c.follows_load = true;  // seen to follow: an offset's reading (unread_landing_may_explain)
    } else {
      c.type = FaultType::frozen;
      c.frozen_by_follow = true;
      c.following = false;  // judge re-admission on a fresh span
    }
  } else {
    // Judged on each load move of its own, not on the span since the flag: a reading that has
    // followed again since the fault ended must not have to match every move it missed.
    if (reading_span >= 0.5 * load_span) {
      clear(c);  // the reading follows the load again
    } else {
      c.following = false;  // a fresh span from the next tick
    }
  }
}

void ContactForceFdi::raise_still_load_fault(Channel& c, double implied_load, double t) noexcept {
  // Beside another flagged channel nothing is raised: a drift raised there could not be judged
  // at its plateau (the stance comparison holds a plateau only as the one correction), and its
  // extrapolated slope would run away; and that channel's correction, right or not, is in the
  // residual the blocks read.
  for (const Channel& o : channels_) {
    if (&o != &c && o.type != FaultType::none) return;
  }
  // The sum residual's blocks since the last flag change (a change moves the residual partway
  // through), and the open block: a step a few tenths of a second old has no closed block yet.
  std::array<generic::LevelPoint, generic::LevelHistory::kCapacity + 1> all{};
  std::size_t count = sum_levels_.ordered(all);
  if (sum_block_count_ > 0) {  // its variance as a short block's
    all[count++] = {sum_block_t_sum_ / sum_block_count_, sum_block_sum_ / sum_block_count_,
                    static_cast<double>(sum_block_target_ticks_) / sum_block_count_};
  }
  const double half_block = 0.5 * sum_block_target_ticks_ * period_s_;
  std::size_t first = 0;
  while (first < count && all[first].t_s - half_block < last_flag_change_s_) ++first;
  const std::span<generic::LevelPoint> points(all.data() + first, count - first);
  // Without a measured noise or a healthy level before the fault, nothing is raised: the window
  // restarts and the next one judges (a level taken as healthy at 0 would absorb the total
  // force's bias into the offset).
  const auto v = sum_block_variance();
  if (!v || points.size() < 3) return;
  for (auto& p : points) p.variance *= *v;
  const generic::OnsetShape shape = generic::onset_shape(points, relation_z_);
  if (shape.first_faulty == 0) return;  // no healthy block since the last flag change
  // The fault's size now: the corrected residual's level (a low-pass of time constant clear_s, as
  // the jump test's residual_level_ is) from its healthy level. Its noise: the residual taken as
  // white of the variance that gives a block's mean v (a block's ticks times v per tick;
  // correlated error makes that an upper bound for a short mean), times the low-pass's factor
  // (seeded_low_pass_variance: its first value's remaining weight counted), plus the healthy
  // level's, v at most. A fault the gain test saw in its window but that has ended within its
  // noise is none now: nothing is raised (a drift that came and went while the robot stood).
  const double present_variance =
      *v * (sum_block_target_ticks_ * seeded_low_pass_variance(residual_level_gain_, residual_level_seed_weight_) + 1.0);
  const double present = corrected_level_ - shape.healthy_level;
  const double bound = relation_z_ * std::sqrt(present_variance);
  if (!(std::abs(present) > bound)) return;
  if (shape.ramp) {
    // A drift from where the ramp left the healthy level, sized by its fitted line.
    raise(c, FaultType::drift, t);
    c.onset_load = 0.0;
    c.reads_as_gain = false;
    start_drift_from_levels(c, t, points.subspan(shape.first_faulty), shape.healthy_level, {});
    double level = 0.0, slope = 0.0;
    c.fit.solve(level, slope);
    c.offset = level;
    c.slope = slope;
    c.still_load_drift = true;
    c.still_load_healthy_level = shape.healthy_level;
    return;
  }
  // A step: an offset of its size now, from the load it had, told from a gain as any jump's.
  raise_jump_onset(c, present, implied_load + shape.healthy_level, t);
}

double ContactForceFdi::plateau_bar(const Channel& c, int ticks) const noexcept {
  if (!c.still_load_drift) return params_.gain_min_load_N;
  // The mean of `ticks` residuals, as a white residual's of the variance that gives a block's mean
  // v (v at least: a longer mean of a correlated error need not scatter less), and the healthy
  // level's, v: beyond z of that, within gain_min_load_N at most.
  const auto v = sum_block_variance();
  if (!v) return params_.gain_min_load_N;
  const double block_ratio = static_cast<double>(sum_block_target_ticks_) / std::max(ticks, 1);
  const double variance = *v * (std::max(1.0, block_ratio) + 1.0);
  return std::min(params_.gain_min_load_N, relation_z_ * std::sqrt(variance));
}

}  // namespace ftsense::biped
