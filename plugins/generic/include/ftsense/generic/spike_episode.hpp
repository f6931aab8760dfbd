// A spike episode: how long a spikes flag holds after the last spike seen.
//
// A faulty sensor's spikes come at random, about as a Poisson process of rate lambda; a flag
// that dropped after each spike would let the next one through before a test sees it. So the
// flag holds h after the last spike, h the gap that a running process leaves only with
// probability p_gap:
//
//   P(gap > h) = exp(-lambda h) = p_gap   =>   h = ln(1 / p_gap) / lambda^,
//   lambda^ = (n - 1) / D,
//
// n the spikes of the episode and D the time seen since its first (the time the spike test could
// see: ticks inside a guard are not counted). The first spike (rate unknown) holds `first_hold`;
// later ones h clamped to [min_hold, first_hold]. The episode runs while fewer than h of seen time
// have passed since its last spike; a spike after that starts a new one.
//
// Time is in whatever unit the caller counts (ticks or seconds), the same for all four numbers.
// Used by signal_validator (generic) and contact_force_fdi (biped): one rule, one place.

#pragma once

#include <algorithm>

namespace ftsense::generic {

// The hold rule's constants, shared by every channel of a stage.
struct SpikeHoldRule {
  double first_hold = 0.0;  // h of an episode's first spike (rate unknown), and the longest h
  double min_hold = 0.0;    // the shortest h
  double gap_log = 0.0;     // ln(1 / p_gap)
};

// One channel's episode. Plain data: no allocation, copyable.
struct SpikeEpisode {
  static constexpr double kCountCap = 1e9;  // n saturates here (a counter that never overflows)

  double count = 0.0;  // n: spikes in the episode (0: none yet)
  double seen = 0.0;   // D: seen time since its first spike
  double quiet = 0.0;  // seen time since its last spike
  double hold = 0.0;   // h: the episode runs while quiet < hold

  // A tick the spike test could see, `dt` long.
  void see(double dt) noexcept {
    seen += dt;
    quiet += dt;
  }
  // A spike seen now: it starts an episode (none running) or counts in the running one.
  void spike(const SpikeHoldRule& rule) noexcept {
    if (!running()) {
      count = 1.0;
      seen = 0.0;
      quiet = 0.0;
      hold = rule.first_hold;
      return;
    }
    count = std::min(count + 1.0, kCountCap);
    quiet = 0.0;
    hold = seen > 0.0 ? std::clamp(rule.gap_log * seen / (count - 1.0), rule.min_hold, rule.first_hold)
                      : rule.first_hold;
  }
  [[nodiscard]] bool running() const noexcept { return count > 0.0 && quiet < hold; }
  void end() noexcept { count = 0.0; }
};

}  // namespace ftsense::generic
