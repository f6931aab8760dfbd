// Recovery, before the leave-one-out virtual sensor: each flagged channel's value from its own
// reading by its fault model (offset and drift x - b, gain x / k, noise v + LP(x - v), spikes the
// median of three), and those that must be substituted from what the total force leaves,
// apportioned by a rigid sole's plane (unmeasured_contact_loads.hpp), within what a lifting foot
// can carry.
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "contact_force_fdi_detail.hpp"
#include "ftsense/generic/median_of_three.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

double ContactForceFdi::recover(std::span<const double> measured, std::span<const double> height, double fz,
                                double t, std::span<double> recovered, int& unknown_loaded) noexcept {
  const bool fz_ok = std::isfinite(fz);
  double known_sum = 0.0;
  unknown_loaded = 0;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    const bool airborne = height[j] > params_.airborne_height_m;
    double value = x;
    bool unknown = false;
    if (c.type == FaultType::offset || c.type == FaultType::drift) {
      value = airborne ? 0.0 : x - fault_at(c, t);
    } else if (c.type == FaultType::gain) {
      value = airborne ? 0.0 : x / c.gain;
    } else if (c.type == FaultType::noise) {
      value = airborne ? 0.0 : c.smoothed;
    } else if (c.type == FaultType::spikes) {
      value = airborne ? 0.0 : generic::median_of_three(x, c.previous, c.previous2);
    } else if (c.type != FaultType::none) {
      value = 0.0;
      unknown = !airborne;
    }
    recovered[j] = value;
    if (unknown) {
      ++unknown_loaded;
    } else {
      known_sum += value;
    }
  }
  // A noise burst's channel, loaded: its leave-one-out force carries the load's fast moves, which
  // a low-pass of the reading lags by tens of newtons in a step; the low-pass is kept for what
  // that force misses, the slow part of reading - force (complementary: v + LP(x - v)). Only while
  // no loaded channel is substituted: their loads are what the total force leaves, so the noise
  // channel's own share is then unknown, and the low-pass of its reading stands.
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    if (!fz_ok || unknown_loaded > 0 || c.type != FaultType::noise || height[j] > params_.airborne_height_m ||
        !std::isfinite(x)) {
      c.noise_bias_set = false;
      continue;
    }
    const double v = std::max(0.0, fz - (known_sum - recovered[j]));
    c.noise_bias = c.noise_bias_set ? c.noise_bias + smoothing_ * ((x - v) - c.noise_bias) : c.smoothed - v;
    c.noise_bias_set = true;
    known_sum += (v + c.noise_bias) - recovered[j];
    recovered[j] = v + c.noise_bias;
  }
  // Channels that must be substituted carry what the total force leaves, apportioned by the
  // plane of a rigid sole where it holds (unmeasured_contact_loads.hpp); each at least 0, a
  // saturated pad at least its ceiling (its reading, when it reads a load).
  if (fz_ok && unknown_loaded > 0) {
    for (std::size_t f = 0; f < feet_; ++f) plane_usable_[f] = 1;
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      const Channel& c = channels_[j];
      const bool airborne = height[j] > params_.airborne_height_m;
      const bool unknown = c.type != FaultType::none && !own_estimate(c.type) && !airborne;
      unknown_[j] = unknown ? 1 : 0;
      const double x = measured[j];
      lower_bound_[j] = unknown && c.type == FaultType::saturation && std::isfinite(x) &&
                                x > params_.airborne_threshold_N
                            ? x
                            : 0.0;
      // The plane holds in full contact only: every pad on the ground, every known one loaded.
      if (airborne || (!unknown && !(recovered[j] > params_.airborne_threshold_N))) {
        plane_usable_[channel_foot_[j]] = 0;
      }
    }
    // A foot whose readable pads on the ground all read their air level, past its landing's
    // guard, carries next to nothing (its sole is lifting): while another foot not seen unloaded
    // holds an unknown pad too, that pad takes what the total force leaves, and this foot's
    // unknown pads (but a saturated one, which reads its load) carry 0. Else they share as before.
    bool loaded_foot_unknown = false;
    for (std::size_t f = 0; f < feet_; ++f) {
      foot_reads_unloaded_[f] = 0;
      bool holds_unknown = false, shows_load = false;
      for (std::size_t i = 0; i < feet_points_; ++i) {
        const std::size_t j = f * feet_points_ + i;
        if (unknown_[j] != 0) {
          holds_unknown = true;
        } else if (!(height[j] > params_.airborne_height_m)) {
          if (recovered[j] > params_.airborne_threshold_N) shows_load = true;
          foot_reads_unloaded_[f] = 1;
        }
      }
      // A sole landing may stand on its substituted pad alone (a heel first): lifting ones only.
      if (shows_load || foot_landing(f, t)) foot_reads_unloaded_[f] = 0;
      loaded_foot_unknown = loaded_foot_unknown || (holds_unknown && foot_reads_unloaded_[f] == 0);
    }
    for (std::size_t j = 0; j < channels_.size() && loaded_foot_unknown; ++j) {
      if (unknown_[j] != 0 && foot_reads_unloaded_[channel_foot_[j]] != 0 && lower_bound_[j] == 0.0) {
        unknown_[j] = 0;
        recovered[j] = 0.0;
      }
    }
    unmeasured_.solve(recovered, unknown_, lower_bound_, plane_usable_, fz - known_sum);
    // Left the only one to take what the total force leaves, a lifting foot's unknown pad may
    // still carry its foot's last load (a sole rolling off it), but no more than it carried a tick
    // before: a sole that lifts takes on no load. What the total force leaves beyond that is
    // another channel's error (a correction gone wrong elsewhere), left in the sum residual.
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      if (unknown_[j] != 0 && foot_reads_unloaded_[channel_foot_[j]] != 0 && lower_bound_[j] == 0.0 &&
          std::isfinite(channels_[j].recovered)) {
        recovered[j] = std::min(recovered[j], std::max(0.0, channels_[j].recovered));
      }
    }
  }
  return known_sum;
}

}  // namespace ftsense::biped
