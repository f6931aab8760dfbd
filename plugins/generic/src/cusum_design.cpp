#include "ftsense/generic/cusum_design.hpp"

#include <cmath>

namespace ftsense::generic {

double cusum_overshoot(double step_std) noexcept { return 2.0 * 0.583 * step_std; }

double cusum_average_run_length(double drift, double boundary) noexcept {
  const double x = 2.0 * drift * boundary;
  // Near D = 0 the formula is 0/0; its limit is b^2 (series: (x^2/2 - x^3/6 + ...) / (2 D^2)).
  if (std::abs(x) < 1e-6) return boundary * boundary * (1.0 - x / 3.0);
  return (std::expm1(-x) + x) / (2.0 * drift * drift);
}

double cusum_threshold_for_arl(double reference_value, double in_control_arl, double overshoot) noexcept {
  const double drift = -reference_value;  // in control, mu = 0
  if (!(cusum_average_run_length(drift, overshoot) < in_control_arl)) return 0.0;
  double lo = overshoot;
  double hi = overshoot + 1.0;
  // ARL grows like exp(2 k b): doubling the bracket reaches any finite target quickly.
  while (cusum_average_run_length(drift, hi) < in_control_arl && hi < 1e6) hi = 2.0 * hi;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cusum_average_run_length(drift, mid) < in_control_arl ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) - overshoot;
}

}  // namespace ftsense::generic
