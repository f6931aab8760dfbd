#include "ftsense/generic/chi_square.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ftsense::generic {

double normal_quantile(double p) noexcept {
  // P(Z <= z) = erfc(-z / sqrt 2) / 2 is increasing in z; |z| <= 40 covers every double p.
  double lo = -40.0;
  double hi = 40.0;
  for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::numbers::sqrt2) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double chi_square_quantile(double nu, double p) noexcept { return chi_square_quantile_at_z(nu, normal_quantile(p)); }

double chi_square_quantile_at_z(double nu, double z) noexcept {
  const double c = 2.0 / (9.0 * nu);
  const double root = 1.0 - c + z * std::sqrt(c);
  return nu * std::pow(std::max(root, 0.0), 3);
}

}  // namespace ftsense::generic
