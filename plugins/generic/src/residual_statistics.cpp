#include "ftsense/generic/residual_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ftsense::generic {

ResidualStatistics::ResidualStatistics(double sample_period_s, double max_lag_s) : period_s_(sample_period_s) {
  // Dyadic lags up to max_lag_s (lag one always); the ring holds the largest lag plus one.
  const double max_ticks = sample_period_s > 0.0 ? std::max(1.0, max_lag_s / sample_period_s) : 1.0;
  std::size_t lag = 1;
  lags_.emplace_back();
  while (static_cast<double>(2 * lag) <= max_ticks && lags_.size() < 40) {
    lag *= 2;
    lags_.emplace_back();
  }
  history_.assign(2 * lag, 0.0);
}

void ResidualStatistics::add(double r) noexcept {
  if (!std::isfinite(r)) {
    run_ = 0;
    return;
  }
  if (n_ == 0) shift_ = r;
  const double x = r - shift_;
  ++n_;
  sum_ += x;
  sum2_ += x * x;
  const std::size_t mask = history_.size() - 1;
  for (std::size_t i = 0, lag = 1; i < lags_.size() && lag <= run_; ++i, lag *= 2) {
    const double past = history_[(next_ - lag) & mask];
    LagSums& s = lags_[i];
    ++s.pairs;
    s.a += x;
    s.b += past;
    s.ab += x * past;
    s.aa += x * x;
    s.bb += past * past;
  }
  history_[next_] = x;
  next_ = (next_ + 1) & mask;
  if (run_ < history_.size()) ++run_;
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

double ResidualStatistics::lag_correlation(std::size_t i) const noexcept {
  if (i >= lags_.size() || lags_[i].pairs < 2) return std::numeric_limits<double>::quiet_NaN();
  const LagSums& s = lags_[i];
  // About the overall mean, as defined in the header.
  const double m = sum_ / static_cast<double>(n_);
  const double p = static_cast<double>(s.pairs);
  const double covariance = s.ab - m * (s.a + s.b) + p * m * m;
  const double variance = 0.5 * (s.aa + s.bb) - m * (s.a + s.b) + p * m * m;
  return variance > 0.0 ? covariance / variance : std::numeric_limits<double>::quiet_NaN();
}

double ResidualStatistics::correlation_time_s() const noexcept {
  const double rho1 = lag_correlation(0);
  if (!(rho1 > 0.0)) return std::isnan(rho1) ? rho1 : 0.0;
  const double e_fold = std::exp(-1.0);
  if (rho1 <= e_fold) return -period_s_ / std::log(rho1);
  // rho_1 above 1/e: walk the usable dyadic lags to the first at or below it.
  double lag_before = 1.0, log_before = std::log(rho1);
  for (std::size_t i = 1; i < lags_.size(); ++i) {
    const double lag = static_cast<double>(std::size_t{1} << i);
    if (static_cast<double>(lags_[i].pairs) < 2.0 * lag) break;  // not usable: too few pairs
    const double rho = lag_correlation(i);
    if (std::isnan(rho)) break;
    if (rho <= e_fold) {
      if (!(rho > 0.0)) {
        // Fell through zero: interpolate rho itself (its log is not defined) to 1/e.
        const double rho_before = std::exp(log_before);
        return period_s_ * (lag_before + (lag - lag_before) * (rho_before - e_fold) / (rho_before - rho));
      }
      const double log_rho = std::log(rho);
      return period_s_ * (lag_before + (lag - lag_before) * (log_before + 1.0) / (log_before - log_rho));
    }
    lag_before = lag;
    log_before = std::log(rho);
  }
  // No usable lag fell to 1/e: the first-order time at the largest usable one (a lower bound).
  if (log_before >= 0.0) return std::numeric_limits<double>::infinity();
  return -period_s_ * lag_before / log_before;
}

}  // namespace ftsense::generic
