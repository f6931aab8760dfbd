#pragma once
// The median of a sample, for the robust noise statistics measured on fault-free logs
// (tick_noise.hpp, window_step_noise.hpp): sigma = median(|v|) / kMedianAbsStandardNormal for
// zero-mean normal v, which a few large values (a landing's impact) barely move.

#include <vector>

namespace ftsense::generic {

// median(|Z|) of a standard normal Z: Phi^-1(3/4).
inline constexpr double kMedianAbsStandardNormal = 0.6744897501960817;

// The middle value of a non-empty sample; the mean of the two middle values for an even count.
// Takes a copy: it reorders it.
[[nodiscard]] double sample_median(std::vector<double> values);

}  // namespace ftsense::generic
