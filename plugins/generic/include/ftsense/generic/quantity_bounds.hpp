#pragma once
// What a measured quantity can take, per channel: [floor_j, ceiling_j] in the reading's unit (a
// force pad that is pressed, never pulled: floor 0), each given as one value for all channels,
// one per channel, or none (empty: -inf, +inf). A ceiling not above its floor is a ConfigError at
// /params/ceiling/<j>. physical_range_detector flags a reading beyond them; fault_recovery holds
// a flagged channel's recovered value within them.
//
// The margin a healthy reading may stray beyond a bound: b = z m sigma + q / 2, sigma the
// reading's white noise, q its quantisation step, z at the false-alarm target
// (false_alarm_target.hpp), m = noise_margin.

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "ftsense/channel_values.hpp"
#include "ftsense/params.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

struct QuantityBounds {
  std::vector<double> floor, ceiling;  // per channel; -inf, +inf where none is given
};

[[nodiscard]] inline QuantityBounds quantity_bounds(const std::vector<double>& floor,
                                                    const std::vector<double>& ceiling, std::size_t channels) {
  QuantityBounds bounds{channel_values(floor, channels, "floor", true),
                        channel_values(ceiling, channels, "ceiling", true)};
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < channels; ++j) {
    if (std::isnan(bounds.floor[j])) bounds.floor[j] = -kInfinity;
    if (std::isnan(bounds.ceiling[j])) bounds.ceiling[j] = kInfinity;
    if (!(bounds.ceiling[j] > bounds.floor[j])) {
      throw ConfigError("/params/ceiling/" + std::to_string(j), " = " + format_number(bounds.ceiling[j]) +
                                                                    " is not above the floor (" +
                                                                    format_number(bounds.floor[j]) + ")");
    }
  }
  return bounds;
}

// The parameters `noise_std` (sigma) and `resolution` (q) of a part that takes the margin b (both
// per channel, one value applying to all; `ftsense calibrate` measures them as tick_noise and
// resolution).
template <class P>
void describe_reading_noise(ParamSchema<P>& schema) {
  schema
      .add("noise_std", &P::noise_std,
           "standard deviation sigma of a healthy reading's noise, in its unit; one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema
      .add("resolution", &P::resolution,
           "quantisation step q of the reading, in its unit (0: continuous); one value applies to all")
      .at_least(0.0)
      .count_at_least(1);
}

// b = z m sigma + q / 2 (header).
[[nodiscard]] inline double reading_margin(double z, double noise_margin, double noise_std, double resolution) noexcept {
  return z * noise_margin * noise_std + 0.5 * resolution;
}

}  // namespace ftsense::generic
