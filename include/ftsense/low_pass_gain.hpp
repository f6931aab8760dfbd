#pragma once
// The gain of a first-order low-pass y_k = y_{k-1} + a (x_k - y_{k-1}) of cut-off f_c [Hz] at
// tick period T [s], exp-discretised so that its time constant 1 / (2 pi f_c) holds at any rate:
//
//   a = 1 - exp(-2 pi f_c T)
//
// f_c at or above the Nyquist frequency 1 / (2 T) is a ConfigError at /params/<parameter>, the
// name of the plugin's parameter that states f_c. Stated by its time constant tau [s] instead:
// a = 1 - exp(-T / tau), tau shorter than a tick a ConfigError (a low-pass that does not smooth).
// White noise of standard deviation sigma leaves the low-pass with sigma sqrt(a / (2 - a))
// (low_pass_noise_ratio).

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

#include "ftsense/plugin.hpp"

namespace ftsense {

[[nodiscard]] inline double low_pass_gain(double cutoff_hz, double period_s,
                                          std::string_view parameter = "cutoff_hz") {
  const double nyquist_hz = 0.5 / period_s;
  if (!(cutoff_hz < nyquist_hz)) {
    throw ConfigError("/params/" + std::string(parameter), " = " + format_number(cutoff_hz) + " violates < " +
                                               format_number(nyquist_hz) +
                                               " (Nyquist frequency 1 / (2 T) of the pipeline, Hz)");
  }
  return -std::expm1(-2.0 * std::numbers::pi * cutoff_hz * period_s);
}

[[nodiscard]] inline double low_pass_gain_from_time_constant(double time_constant_s, double period_s,
                                                             std::string_view parameter) {
  if (!(time_constant_s >= period_s)) {
    throw ConfigError("/params/" + std::string(parameter), " = " + format_number(time_constant_s) +
                                                               " s is shorter than a tick (" + format_number(period_s) +
                                                               " s): a low-pass that does not smooth");
  }
  return -std::expm1(-period_s / time_constant_s);
}

[[nodiscard]] inline double low_pass_noise_ratio(double gain) { return std::sqrt(gain / (2.0 - gain)); }

}  // namespace ftsense
