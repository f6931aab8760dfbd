#include "ftsense/generic/tick_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ftsense::generic {

namespace {
// median(|Z|) for a standard normal Z: the 75 % quantile.
constexpr double kMedianAbsNormal = 0.6744897501960817;
}  // namespace

void TickNoise::add(double x) {
  if (!std::isfinite(x)) {
    break_sequence();
    return;
  }
  if (held_ == 2 && !(x == previous_ && previous_ == before_)) abs_d2_.push_back(std::abs(x - 2.0 * previous_ + before_));
  before_ = previous_;
  previous_ = x;
  held_ = std::min(held_ + 1, 2);
}

double TickNoise::standard_deviation() const {
  if (abs_d2_.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> sorted = abs_d2_;
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  double median = *middle;
  if (sorted.size() % 2 == 0) median = 0.5 * (median + *std::max_element(sorted.begin(), middle));
  return median / (kMedianAbsNormal * std::sqrt(6.0));
}

}  // namespace ftsense::generic
