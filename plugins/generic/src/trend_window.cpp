#include "ftsense/generic/trend_window.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ftsense::generic {

bool TrendWindow::Fit::flat(double z) const noexcept {
  return std::isfinite(se1) && std::isfinite(se2) && std::abs(c1) <= z * se1 && std::abs(c2) <= z * se2;
}

void TrendWindow::add(double value, double t_s, double period_s) noexcept {
  if (count_ == 0) t0_s_ = t_s;
  const double k = std::max(0.0, std::round((t_s - t0_s_) / period_s));
  k_ += k, kk_ += k * k, kkk_ += k * k * k, kkkk_ += k * k * k * k;
  r_ += value, kr_ += k * value, kkr_ += k * k * value, rr_ += value * value;
  count_ = count_ < std::numeric_limits<int>::max() ? count_ + 1 : count_;
}

void TrendWindow::restart() noexcept { *this = TrendWindow{}; }

double TrendWindow::mean() const noexcept { return count_ > 0 ? r_ / static_cast<double>(count_) : 0.0; }

TrendWindow::Basis TrendWindow::basis() const noexcept {
  const double n = static_cast<double>(count_);
  const double m = k_ / n;
  const double e2 = kk_ / n, e3 = kkk_ / n, e4 = kkkk_ / n;
  const double mu2 = std::max(e2 - m * m, 0.0);
  const double mu3 = e3 - 3.0 * m * e2 + 2.0 * m * m * m;
  const double mu4 = e4 - 4.0 * m * e3 + 6.0 * m * m * e2 - 3.0 * m * m * m * m;
  const double a = mu2 > 0.0 ? mu3 / mu2 : 0.0;
  return {n, m, a, mu2, n * mu2, std::max(n * (mu4 - a * mu3 - mu2 * mu2), 0.0)};
}

double TrendWindow::value_p1(const Basis& q) const noexcept { return kr_ - q.m * r_; }

double TrendWindow::value_p2(const Basis& q) const noexcept {
  const double r_p1p1 = kkr_ - 2.0 * q.m * kr_ + q.m * q.m * r_;
  return r_p1p1 - q.a * value_p1(q) - q.b * r_;
}

double TrendWindow::slope() const noexcept {
  if (count_ < 2) return 0.0;
  const Basis q = basis();
  return q.p1p1 > 0.0 ? value_p1(q) / q.p1p1 : 0.0;
}

TrendWindow::Fit TrendWindow::fit() const noexcept {
  const Basis q = basis();
  const double rp1 = value_p1(q), rp2 = value_p2(q);
  const double c1 = q.p1p1 > 0.0 ? rp1 / q.p1p1 : 0.0;
  const double c2 = q.p2p2 > 0.0 ? rp2 / q.p2p2 : 0.0;
  const double ssr = rr_ - r_ * r_ / q.n - c1 * rp1 - c2 * rp2;
  const double s = std::sqrt(std::max(ssr, 0.0) / (q.n - 3.0));
  const double inf = std::numeric_limits<double>::infinity();
  return {c1, q.p1p1 > 0.0 ? s / std::sqrt(q.p1p1) : inf, c2, q.p2p2 > 0.0 ? s / std::sqrt(q.p2p2) : inf, s};
}

}  // namespace ftsense::generic
