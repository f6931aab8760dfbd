#include "ftsense/generic/residual_statistics.hpp"

#include <cmath>
#include <limits>

namespace ftsense::generic {

void ResidualStatistics::add(double r) noexcept {
  if (!std::isfinite(r)) {
    has_previous_ = false;
    return;
  }
  if (n_ == 0) shift_ = r;
  const double x = r - shift_;
  ++n_;
  sum_ += x;
  sum2_ += x * x;
  if (has_previous_) {
    ++pairs_;
    pair_a_ += x;
    pair_b_ += previous_;
    pair_ab_ += x * previous_;
    pair_aa_ += x * x;
    pair_bb_ += previous_ * previous_;
  }
  previous_ = x;
  has_previous_ = true;
}

double ResidualStatistics::centre() const noexcept {
  return n_ > 0 ? shift_ + sum_ / static_cast<double>(n_) : std::numeric_limits<double>::quiet_NaN();
}

double ResidualStatistics::standard_deviation() const noexcept {
  if (n_ < 2) return std::numeric_limits<double>::quiet_NaN();
  const double mean = sum_ / static_cast<double>(n_);
  const double variance = sum2_ / static_cast<double>(n_) - mean * mean;
  return std::sqrt(variance > 0.0 ? variance : 0.0);
}

double ResidualStatistics::lag_one_correlation() const noexcept {
  if (pairs_ < 2) return std::numeric_limits<double>::quiet_NaN();
  // About the overall mean, as defined in the header.
  const double m = sum_ / static_cast<double>(n_);
  const double p = static_cast<double>(pairs_);
  const double covariance = pair_ab_ - m * (pair_a_ + pair_b_) + p * m * m;
  const double variance = 0.5 * (pair_aa_ + pair_bb_) - m * (pair_a_ + pair_b_) + p * m * m;
  return variance > 0.0 ? covariance / variance : std::numeric_limits<double>::quiet_NaN();
}

double ResidualStatistics::correlation_time_s() const noexcept {
  const double rho = lag_one_correlation();
  if (!(rho > 0.0)) return std::isnan(rho) ? rho : 0.0;
  if (rho >= 1.0) return std::numeric_limits<double>::infinity();
  return -period_s_ / std::log(rho);
}

}  // namespace ftsense::generic
