// Load the readings do not show: a pad on the ground at its air level while the pads read short of the total
// force (a dead pad that lands), and the jump groups such a pad explains.
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "contact_force_fdi_detail.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

void ContactForceFdi::unread_load_test(std::span<const double> height, bool usable, double t) noexcept {
  // The pads read short of the total force by more than a reading at the air level can hide
  // (zero_evidence_above_N_: the total force's error bound, plus a driver's zero clamp), and on
  // one foot one healthy pad on the ground reads its air level while another healthy one carries
  // load: under "that pad reads nothing of its load" it carries the shortfall. Substituted or
  // gain-corrected loaded channels absorb or scale the residual: judged only without them, and
  // not while the gain test has a fit it cannot isolate (a gain elsewhere short of the load).
  if (usable && residual_smoothed_started_ && std::abs(residual_smoothed_) <= params_.sum_threshold_N) {
    residual_within_bound_s_ = t;
  }
  for (Channel& c : channels_) {
    if (c.smoothed > params_.airborne_threshold_N) c.loaded_at_s = t;
  }
  bool judged = usable && residual_smoothed_started_ && residual_smoothed_ < -zero_evidence_above_N_ &&
                !gain_unisolated_;
  for (std::size_t j = 0; j < channels_.size() && judged; ++j) {
    const Channel& c = channels_[j];
    const bool additive = c.type == FaultType::offset || c.type == FaultType::drift || c.type == FaultType::spikes;
    judged = c.type == FaultType::none || additive || height[j] > params_.airborne_height_m;
  }
  // Candidates of two strengths: a pad at its air level since its foot landed (a dead pad that
  // lands), and one that has read nothing since the residual was last within its bound and was
  // handed load since it last read any (its foot's healthy neighbours stepped together while the
  // sum fell, a group the jump test left unnamed for it: a pad that rolled off within the stance,
  // died there and takes its load back unread). The weaker are counted only where no stronger one
  // stands.
  std::size_t candidates = 0, culprit = channels_.size();
  std::size_t weak_candidates = 0, weak_culprit = channels_.size();
  for (std::size_t f = 0; f < feet_ && judged; ++f) {
    bool loaded = false;
    std::size_t since_landing = 0, since_bound = 0, last = channels_.size(), weak_last = channels_.size();
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const std::size_t j = f * feet_points_ + i;
      const Channel& c = channels_[j];
      if (c.type != FaultType::none || height[j] > params_.airborne_height_m) continue;
      if (c.smoothed > params_.airborne_threshold_N) {
        loaded = true;
      } else if (c.smoothed > -params_.airborne_threshold_N && c.loaded_at_s < last_touchdown_s_[f]) {
        ++since_landing;
        last = j;
      } else if (c.smoothed > -params_.airborne_threshold_N && c.loaded_at_s < residual_within_bound_s_ &&
                 c.handed_load_s > c.loaded_at_s) {
        ++since_bound;
        weak_last = j;
      }
    }
    // The shortfall began after this foot landed (the residual was within its bound since), and
    // the landing's guard is over (an impact's error in F_z outlasts the smoother's settling).
    const bool landed = residual_within_bound_s_ >= last_touchdown_s_[f] &&
                        t - last_touchdown_s_[f] >= params_.touchdown_guard_s;
    if (loaded && landed) {
      candidates += since_landing;
      culprit = since_landing > 0 ? last : culprit;
      weak_candidates += since_bound;
      weak_culprit = since_bound > 0 ? weak_last : weak_culprit;
    }
  }
  if (candidates == 0) {
    candidates = weak_candidates;
    culprit = weak_culprit;
  }
  // Two or more cannot be told apart (a sole landing on its heel leaves both toe pads unloaded).
  if (candidates != 1) {
    unread_candidate_ = channels_.size();
    return;
  }
  if (culprit != unread_candidate_) {
    unread_candidate_ = culprit;
    unread_since_s_ = t;
    return;
  }
  // Held for the smoother's settling, past the guard: the residual's lag is not the evidence.
  if (t - unread_since_s_ < smoother_settle_s_) return;
  raise_stuck(channels_[culprit], t);
  unread_candidate_ = channels_.size();
}

bool ContactForceFdi::unread_landing_may_explain(std::span<const double> height, double jump_sum) noexcept {
  const bool fell = jump_sum < 0.0;  // the pads now read less than the total force
  bool explained = false;
  for (std::size_t f = 0; f < feet_; ++f) {
    bool loaded = false, unread_load = false;
    int members = 0, onsets = 0;
    bool gain_takes_load = false;
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const std::size_t j = f * feet_points_ + i;
      const Channel& c = channels_[j];
      members += c.jump_pending ? 1 : 0;
      onsets += c.jump_pending && !c.candidate_flagged ? 1 : 0;
      gain_takes_load = gain_takes_load || (c.jump_pending && c.type == FaultType::gain &&
                                            !(height[j] > params_.airborne_height_m) &&
                                            std::abs(c.candidate_load) <= params_.airborne_threshold_N);
    }
    // A held gain on the ground that takes its load from its air level may have ended in the air
    // (its reading there is its fault's end as much as its going on): its correction then errs by
    // (1/k - 1) of the load, the group's step. One fault's end is fewer faults than two healthy
    // sensors' onsets; the stance comparison judges the gain. (A gain still right, beside two
    // true onsets on that tick, loses them to the other tests: the stated limit.)
    explained = explained || (onsets >= 2 && gain_takes_load);
    for (std::size_t i = 0; i < feet_points_ && members > 0; ++i) {
      const std::size_t j = f * feet_points_ + i;
      const Channel& c = channels_[j];
      if (height[j] > params_.airborne_height_m) continue;
      loaded = loaded || (c.type == FaultType::none && c.smoothed > params_.airborne_threshold_N);
      unread_load = unread_load || (!c.jump_pending && may_hold_unread_load(c, f, fell, onsets >= 2));
    }
    if (members > 0 && loaded && unread_load) {
      explained = true;
      // Two or more healthy sensors of this foot stepped while the sum fell, beside a pad at its
      // air level: the load they handed it is the unread-load test's evidence for that pad.
      for (std::size_t i = 0; i < feet_points_ && onsets >= 2 && fell; ++i) {
        const std::size_t j = f * feet_points_ + i;
        Channel& c = channels_[j];
        if (!(height[j] > params_.airborne_height_m) && !c.jump_pending && c.type == FaultType::none &&
            std::abs(c.smoothed) <= params_.airborne_threshold_N) {
          c.handed_load_s = last_tick_s_;
        }
      }
    }
  }
  return explained;
}

bool ContactForceFdi::may_hold_unread_load(const Channel& c, std::size_t f, bool fell,
                                           bool several_onsets) const noexcept {
  if (c.type == FaultType::none) {
    // Its landing unread: on the ground at its air level, unloaded since the foot landed. Or, where
    // the jump would name two or more healthy sensors of its foot at once, at its air level now
    // (a pad that rolled off within the stance, died there and takes its load back unread): one
    // dead pad is the fewer faults. Not against one sensor's step or a fault's end, which are one
    // fault or none.
    return fell && std::abs(c.smoothed) <= params_.airborne_threshold_N &&
           (several_onsets || c.loaded_at_s < last_touchdown_s_[f]);
  }
  if (!own_estimate(c.type) && c.type != FaultType::invalid) {
    // A stuck reading in the residual as read: load coming onto it reads nothing, and load
    // leaving it (while it carries some) nothing either.
    return fell || c.recovered > params_.airborne_threshold_N;
  }
  // An offset the air measured, not yet seen to follow its load: a reading frozen at a load reads
  // as that offset in the air, and on the ground its correction then says nothing of what it
  // carries (load may come or go unread).
  return (c.type == FaultType::offset || c.type == FaultType::drift) && c.fit_has_air && !c.follows_load;
}

double ContactForceFdi::landing_step_bar(double floor_N) const noexcept {
  return std::max(floor_N, guard_z_ * std::sqrt(guard_step_square_ / std::max(guard_step_count_, 1)));
}

void ContactForceFdi::raise_stuck(Channel& c, double t) noexcept {
  raise(c, FaultType::frozen, t);
  c.frozen_by_follow = true;
  c.following = false;
}

}  // namespace ftsense::biped
