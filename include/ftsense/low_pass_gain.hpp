#pragma once
// The gain of a first-order low-pass y_k = y_{k-1} + a (x_k - y_{k-1}) of cut-off f_c [Hz] at
// tick period T [s], exp-discretised so that its time constant 1 / (2 pi f_c) holds at any rate:
//
//   a = 1 - exp(-2 pi f_c T)
//
// f_c at or above the Nyquist frequency 1 / (2 T) is a ConfigError at /params/<parameter>, the
// name of the plugin's parameter that states f_c.

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

}  // namespace ftsense
