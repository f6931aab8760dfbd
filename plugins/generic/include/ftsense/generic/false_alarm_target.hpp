#pragma once
// The parameters every test with a false-alarm target reads the same way, checked once.
//
//   alpha = T / false_alarm_interval_s   the chance of a false alarm per tick of period T;
//                                        an interval of two ticks or less is a ConfigError
//   z = Phi^-1(1 - alpha / 2)            the two-sided bound in standard deviations
//   m = noise_margin >= 1                a healthy (or stuck) noise known within a factor m;
//                                        less than 1 or not finite is a ConfigError
//
// Both errors are reported at /params/<name> with the value given.

#include <cmath>

#include "ftsense/generic/chi_square.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

[[nodiscard]] inline double false_alarm_per_tick(double period_s, double false_alarm_interval_s) {
  const double alpha = period_s / false_alarm_interval_s;
  if (!(alpha < 0.5)) {
    throw ConfigError("/params/false_alarm_interval_s",
                      " = " + format_number(false_alarm_interval_s) + " s is not longer than two ticks");
  }
  return alpha;
}

// z of a two-sided test at alpha per tick, from the lower tail, which keeps its precision for a
// tiny alpha.
[[nodiscard]] inline double two_sided_z(double alpha) noexcept { return -normal_quantile(0.5 * alpha); }

inline void check_noise_margin(double noise_margin) {
  if (!(noise_margin >= 1.0 && std::isfinite(noise_margin))) {
    throw ConfigError("/params/noise_margin", " = " + format_number(noise_margin) + " is not a factor of at least 1");
  }
}

}  // namespace ftsense::generic
