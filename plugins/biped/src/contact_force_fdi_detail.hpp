#pragma once
// What the files of contact_force_fdi share (private to them, not installed): which evidence wins
// when tests disagree, the fault types corrected from their own reading, and small arithmetic.
#include <cstddef>

#include "ftsense/fault_type.hpp"

namespace ftsense::biped::contact_force_fdi_detail {

// Which evidence wins when several tests fire on one channel.
inline int priority(FaultType type) {
  switch (type) {
    case FaultType::invalid: return 6;
    case FaultType::frozen:
    case FaultType::saturation: return 5;
    case FaultType::noise: return 4;
    case FaultType::spikes: return 3;
    case FaultType::gain: return 2;
    case FaultType::drift:
    case FaultType::offset: return 1;
    case FaultType::none:
    case FaultType::unclassified: return 0;  // never raised here
  }
  return 0;
}

// The smallest |k| of a gain fault: a reading under a tenth of its force carries no usable
// scale of it (and the recovery N / k must stay bounded).
constexpr double kMinGain = 0.1;

// Tick counters stop here (about 12 days at 1 kHz): past it they would overflow.
constexpr int kCountCap = 1'000'000'000;

// sum (a - mean a)(b - mean b) over samples of total weight w, from sum a b, sum a and sum b.
inline double centred(double sum_ab, double sum_a, double sum_b, double w) { return sum_ab - sum_a * sum_b / w; }

inline bool corrects(FaultType type) {
  return type == FaultType::offset || type == FaultType::drift || type == FaultType::gain;
}

// Recovered from its own reading (corrected, low-passed or median-filtered) rather than
// substituted from the total force.
inline bool own_estimate(FaultType type) {
  return corrects(type) || type == FaultType::noise || type == FaultType::spikes;
}

// A channel's reading step as the jump test's sum residual takes it: a gain fault's reading is
// taken corrected (x / k), any other as read.
inline double in_residual(FaultType type, double gain, double step) { return type == FaultType::gain ? step / gain : step; }

// Ring buffers without an integer division per access (a 64-bit division costs tens of cycles;
// the window sums read two jump windows of each ring every tick): the slot `back` ticks before
// the newest of a ring of `size` whose next write goes to slot `next` (back < size), and the
// slot after `i`.
inline std::size_t ring_back(std::size_t next, std::size_t size, std::size_t back) noexcept {
  return next > back ? next - 1 - back : next + size - 1 - back;
}
inline std::size_t ring_after(std::size_t i, std::size_t size) noexcept { return i + 1 == size ? 0 : i + 1; }


// The variance, in units of its input's (white), of a low-pass y += a (r - y) seeded with its first
// value, which keeps the weight w = (1 - a)^k after k ticks: w^2 + a (1 - w^2) / (2 - a).
inline double seeded_low_pass_variance(double a, double seed_weight) {
  const double w2 = seed_weight * seed_weight;
  return w2 + a * (1.0 - w2) / (2.0 - a);
}

}  // namespace ftsense::biped::contact_force_fdi_detail
