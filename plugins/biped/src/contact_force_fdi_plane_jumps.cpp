// Jumps inside a touchdown guard, judged by their foot's plane: a rigid sole's loads in full contact lie on a
// plane, so a pad's step that leaves its neighbours' plane is its own (contact_force_fdi.hpp, "jump").
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "contact_force_fdi_detail.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

void ContactForceFdi::relation_jumps(std::span<const double> measured, std::span<const double> height,
                                     double t) noexcept {
  const std::size_t relations = unmeasured_.relations_per_foot();
  if (relations == 0) return;
  const std::size_t ring = static_cast<std::size_t>(2 * jump_window_ticks_);
  const std::size_t w = static_cast<std::size_t>(jump_window_ticks_);
  for (std::size_t f = 0; f < feet_; ++f) {
    if (relation_group_[f] == 2) {  // decided on the last tick
      relation_group_[f] = 0;
      for (std::size_t i = 0; i < feet_points_; ++i) channels_[f * feet_points_ + i].relation_member = false;
    }
    // Full contact: every pad on the ground and carrying load (its reading, corrected), read as
    // it is or corrected (a substituted or noisy pad would put its unmeasured changes in the plane).
    bool full = true;
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const std::size_t j = f * feet_points_ + i;
      const Channel& c = channels_[j];
      const double x = measured[j];
      const double load = c.type == FaultType::gain                                    ? x / c.gain
                          : c.type == FaultType::offset || c.type == FaultType::drift ? x - fault_at(c, t)
                                                                                      : x;
      // A healthy pad back on a level it was found stuck at (a clip's ceiling) is not read as it is.
      full = full && std::isfinite(x) && !(height[j] > params_.airborne_height_m) &&
             load > params_.airborne_threshold_N && (c.type == FaultType::none || corrects(c.type)) && !c.on_ceiling;
    }
    full_contact_run_[f] = full ? std::min(full_contact_run_[f] + 1, ring) : 0;
    for (std::size_t r = 0; r < relations; ++r) {
      double value = 0.0;
      for (std::size_t i = 0; i < feet_points_ && full; ++i) {
        const std::size_t j = f * feet_points_ + i;
        const Channel& c = channels_[j];
        // As the jump test's sum takes them: a gain fault's reading corrected, an offset's as read.
        value += unmeasured_.relation_weight(i, r) * (c.type == FaultType::gain ? measured[j] / c.gain : measured[j]);
      }
      relation_ring_[(f * relations + r) * ring + relation_next_] = value;
    }
  }
  relation_next_ = ring_after(relation_next_, ring);
  for (std::size_t f = 0; f < feet_; ++f) {
    // A run of 2 W full ticks also means the ring holds 2 W values written since the reset.
    const bool known = full_contact_run_[f] == ring;
    relation_step_known_[f] = known ? 1 : 0;
    bool healthy = true, candidates = false;
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const Channel& c = channels_[f * feet_points_ + i];
      healthy = healthy && c.type == FaultType::none;
      candidates = candidates || c.relation_pending;
    }
    if (known) {
      for (std::size_t r = 0; r < relations; ++r) {
        const double* values = &relation_ring_[(f * relations + r) * ring];
        double before = 0.0, after = 0.0;
        for (std::size_t i = 0; i < w; ++i) {
          after += values[ring_back(relation_next_, ring, i)];
          before += values[ring_back(relation_next_, ring, w + i)];
        }
        relation_step_[f * relations + r] = (after - before) / static_cast<double>(w);
        relation_before_[f * relations + r] = before / static_cast<double>(w);
      }
      // The steps of a healthy foot: what the plane's departures and the sensors' noise do in a
      // window, the bar a confirmed jump must clear.
      if (healthy && relation_group_[f] == 0 && !candidates) {
        for (std::size_t r = 0; r < relations; ++r) {
          relation_step_square_[f * relations + r] += relation_step_[f * relations + r] * relation_step_[f * relations + r];
        }
        relation_step_count_[f] += 1.0;
      }
    }
    if (relation_group_[f] == 0 && candidates) {
      relation_group_[f] = 1;
      relation_group_age_[f] = 0;
      for (std::size_t r = 0; r < relations; ++r) relation_expect_[f * relations + r] = 0.0;
      for (std::size_t i = 0; i < feet_points_; ++i) {
        Channel& c = channels_[f * feet_points_ + i];
        c.relation_member = c.relation_pending;
        c.relation_reading_before = c.relation_member ? c.relation_candidate_load : measured[f * feet_points_ + i];
        if (!c.relation_member) continue;
        c.relation_load_before = c.relation_candidate_load;
        c.relation_jump_size = c.relation_jump;
        c.relation_from_flagged = c.candidate_flagged;
        const double jump = in_residual(c.type, c.gain, c.relation_jump);
        for (std::size_t r = 0; r < relations; ++r) {
          relation_expect_[f * relations + r] += unmeasured_.relation_weight(i, r) * jump;
        }
      }
    }
    if (relation_group_[f] == 1 && relation_group_age_[f]++ >= jump_window_ticks_ - 1) relation_group_[f] = 2;
  }
  for (auto& c : channels_) c.relation_pending = false;  // this tick's candidates are in their groups
}

bool ContactForceFdi::relation_confirmed(std::size_t foot, std::span<const double> measured, double t) const noexcept {
  const std::size_t relations = unmeasured_.relations_per_foot();
  if (relations == 0 || relation_step_known_[foot] == 0 ||
      relation_step_count_[foot] < generic::UnmeasuredContactLoads::kMinSamples) {
    return false;
  }
  // Relation r's fault-free window step sigma on this foot: the RMS of its healthy steps [N].
  const auto step_sigma = [&](std::size_t r) {
    return std::sqrt(std::max(relation_step_square_[foot * relations + r] / relation_step_count_[foot], 1e-12));
  };
  // In units of each relation's fault-free step sigma: the step and the jumps' expected step both
  // beyond z (the false-alarm target's quantile), alike in sign, and within z or half of it apart.
  double observed = 0.0, expected = 0.0, agreement = 0.0;
  for (std::size_t r = 0; r < relations; ++r) {
    const double sigma = step_sigma(r);
    const double step = relation_step_[foot * relations + r];
    const double e = relation_expect_[foot * relations + r];
    if (std::abs(step - e) > std::max(relation_z_ * sigma, 0.5 * std::abs(e))) return false;
    // The plane held before the jump: a foot whose relation is already off holds a fault no one
    // has found (a frozen pad that keeps its noise), and its steps are no evidence.
    // Offsets and drifts already found count with their corrections (the ring holds them as read).
    double before = relation_before_[foot * relations + r];
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const Channel& c = channels_[foot * feet_points_ + i];
      if (c.type == FaultType::offset || c.type == FaultType::drift) {
        before -= unmeasured_.relation_weight(i, r) * fault_at(c, t);
      }
    }
    const double level = std::max(unmeasured_.relation_rms(foot, r), 1e-6);  // NaN: not learnt, no verdict
    if (!(std::abs(before) <= relation_z_ * level)) return false;
    observed += (step / sigma) * (step / sigma);
    expected += (e / sigma) * (e / sigma);
    agreement += step * e / (sigma * sigma);
  }
  const double z2 = relation_z_ * relation_z_;
  if (!(observed >= z2 && expected >= z2 && agreement > 0.0)) return false;
  // A group of several pads is named only if no member alone explains the step within the noise
  // (z sigma) and beyond z on its own: with fewer relations than members the plane cannot tell
  // which of them stepped. A lifting sole's pads fall as one, and as one of them nears its zero
  // load it no longer presses in proportion and the plane departs by about what that pad's fall
  // alone implies (SURALP at 200 Hz: 19 N, three healthy pads raised together). None of them is
  // named then (the after-guard judgement names no group of several either); a sensor's fault
  // among them waits for another test (the air test at the foot's swing). Not the group test's
  // 50 % model allowance: with it a pad's +60 N beside a neighbour's +25 N was "explained" by
  // the +60 N alone, and both faults went unnamed (a review's probe).
  int members = 0;
  for (std::size_t i = 0; i < feet_points_; ++i) members += channels_[foot * feet_points_ + i].relation_member ? 1 : 0;
  for (std::size_t i = 0; i < feet_points_ && members >= 2; ++i) {
    const Channel& c = channels_[foot * feet_points_ + i];
    if (!c.relation_member) continue;
    const double jump = in_residual(c.type, c.gain, c.relation_jump_size);
    bool fits = true;
    double alone = 0.0;
    for (std::size_t r = 0; r < relations; ++r) {
      const double sigma = step_sigma(r);
      const double e = unmeasured_.relation_weight(i, r) * jump;
      fits = fits && std::abs(relation_step_[foot * relations + r] - e) <= relation_z_ * sigma;
      alone += (e / sigma) * (e / sigma);
    }
    if (fits && alone >= z2) return false;
  }
  // A pad whose offset may yet be a gain moves the plane by (k - 1) times its load's change, which
  // a landing's load transfer makes as large as a sensor's step: on a 48 kg biped, a gain x 1.5
  // was read as its offset's end at the other foot's landing, and its neighbours' load steps as
  // onsets. Read through the gain instead, is the plane's step within its noise?
  bool may_be_gain = false;
  for (std::size_t i = 0; i < feet_points_; ++i) {
    may_be_gain = may_be_gain || offset_may_be_gain(channels_[foot * feet_points_ + i]);
  }
  if (!may_be_gain) return true;
  for (std::size_t r = 0; r < relations; ++r) {
    const double sigma = step_sigma(r);
    double step = relation_step_[foot * relations + r];
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const std::size_t j = foot * feet_points_ + i;
      const Channel& c = channels_[j];
      const auto k = offset_may_be_gain(c) ? onset_gain(c) : std::nullopt;
      if (!k || !std::isfinite(measured[j]) || !std::isfinite(c.relation_reading_before)) continue;
      step -= unmeasured_.relation_weight(i, r) * (measured[j] - c.relation_reading_before) * (1.0 - 1.0 / *k);
    }
    if (std::abs(step) > relation_z_ * sigma) return true;  // not its load alone: a sensor stepped
  }
  return false;
}

}  // namespace ftsense::biped
