#pragma once
// A reading's one-tick jump against its own noise, as the parts that look for steps judge it.
//
// A reading x with white noise sigma and quantisation step q has a second difference
// d = x(t) - 2 x(t-1) + x(t-2) of variance 6 sigma^2 + q^2 / 2 where the signal itself is smooth
// (a load between a landing's transients); a step b at tick t makes d(t) = b. A jump is beyond
// the noise when |d| > z sqrt(6 sigma^2 + q^2 / 2), z from the part's false-alarm target.

#include <cmath>

#include "ftsense/params.hpp"

namespace ftsense::generic {

[[nodiscard]] inline double second_difference_variance(double noise_std, double resolution) noexcept {
  return 6.0 * noise_std * noise_std + 0.5 * resolution * resolution;
}

// The parameters `noise_std` and `resolution` of a part that judges readings' jumps (both per
// channel, one value applying to all; `ftsense calibrate` measures them as tick_noise and
// resolution).
template <class P>
void describe_jump_noise(ParamSchema<P>& schema) {
  schema
      .add("noise_std", &P::noise_std,
           "white noise sigma of each reading, in its unit (its second difference has variance 6 sigma^2); one "
           "value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema
      .add("resolution", &P::resolution,
           "quantisation step q of each reading, in its unit (0: continuous; adds q^2 / 2 to the second "
           "difference's variance); one value applies to all")
      .at_least(0.0)
      .count_at_least(1);
}

// The parameter `residual_step_std` of a part that confirms a reading's jump by its residual row's
// window step (window_step_noise.hpp; `ftsense calibrate` measures it as window_step).
template <class P>
void describe_residual_step(ParamSchema<P>& schema) {
  schema
      .add("residual_step_std", &P::residual_step_std,
           "s_r: how much each fault-free residual row steps between two consecutive 10 ms windows (standard "
           "deviation, in its unit); one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
}

}  // namespace ftsense::generic
