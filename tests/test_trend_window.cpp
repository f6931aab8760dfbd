// TrendWindow: the slope and bend of samples on ticks with gaps, against the least-squares fits
// computed directly (two-pass, Cramer's rule for the quadratic), and the closed forms on
// consecutive ticks; exact values on small traces.

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/generic/trend_window.hpp"

namespace ftsense::generic {
namespace {

constexpr double kPeriod = 0.005;  // [s]

// The least-squares line and quadratic of (k_i, r_i), computed directly.
struct DirectFit {
  double slope, slope_se, bend, bend_se, s;
};
DirectFit direct_fit(const std::vector<double>& k, const std::vector<double>& r) {
  const double n = static_cast<double>(k.size());
  double km = 0.0, rm = 0.0;
  for (std::size_t i = 0; i < k.size(); ++i) km += k[i] / n, rm += r[i] / n;
  // Centred powers u = k - km: the quadratic r = a0 + a1 u + a2 u^2 by Cramer's rule.
  double s0 = n, s1 = 0, s2 = 0, s3 = 0, s4 = 0, t0 = 0, t1 = 0, t2 = 0, su = 0, sur = 0;
  for (std::size_t i = 0; i < k.size(); ++i) {
    const double u = k[i] - km;
    s1 += u, s2 += u * u, s3 += u * u * u, s4 += u * u * u * u;
    t0 += r[i], t1 += u * r[i], t2 += u * u * r[i];
    su += u * u, sur += u * (r[i] - rm);
  }
  const auto det3 = [](double a, double b, double c, double d, double e, double f, double g, double h, double i) {
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  };
  const double d = det3(s0, s1, s2, s1, s2, s3, s2, s3, s4);
  const double a0 = det3(t0, s1, s2, t1, s2, s3, t2, s3, s4) / d;
  const double a1 = det3(s0, t0, s2, s1, t1, s3, s2, t2, s4) / d;
  const double a2 = det3(s0, s1, t0, s1, s2, t1, s2, s3, t2) / d;
  double ssr = 0.0;
  for (std::size_t i = 0; i < k.size(); ++i) {
    const double u = k[i] - km;
    const double e = r[i] - (a0 + a1 * u + a2 * u * u);
    ssr += e * e;
  }
  const double s = std::sqrt(ssr / (n - 3.0));
  // The bend's variance: s^2 times the (3,3) element of the inverse normal matrix, its cofactor / d.
  const double bend_cofactor = s0 * s2 - s1 * s1;
  return {sur / su, s / std::sqrt(su), a2, s * std::sqrt(bend_cofactor / d), s};
}

TEST(TrendWindow, OnTicksWithGapsItIsTheLeastSquaresLineAndQuadratic) {
  // Ticks 0-9, 30-34 and 200-219 (two gaps), r = 4 + 0.05 k - 0.0002 k^2 plus N(0, 1) noise.
  const unsigned seed = 11;
  std::printf("noise N(0, 1), std::mt19937(%u)\n", seed);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> k, r;
  TrendWindow window;
  const double t0 = 12.345;
  for (const auto [from, to] : {std::array<int, 2>{0, 10}, {30, 35}, {200, 220}}) {
    for (int tick = from; tick < to; ++tick) {
      const double x = static_cast<double>(tick);
      const double value = 4.0 + 0.05 * x - 0.0002 * x * x + noise(rng);
      k.push_back(x), r.push_back(value);
      window.add(value, t0 + x * kPeriod, kPeriod);
    }
  }
  const DirectFit direct = direct_fit(k, r);
  const TrendWindow::Fit fit = window.fit();
  EXPECT_EQ(window.count(), 35);
  EXPECT_NEAR(fit.c1, direct.slope, 1e-12 * std::abs(direct.slope) + 1e-15);
  EXPECT_NEAR(fit.se1, direct.slope_se, 1e-9 * direct.slope_se);
  EXPECT_NEAR(fit.c2, direct.bend, 1e-9 * std::abs(direct.bend));
  EXPECT_NEAR(fit.se2, direct.bend_se, 1e-9 * direct.bend_se);
  EXPECT_NEAR(fit.s, direct.s, 1e-9 * direct.s);
  EXPECT_NEAR(window.slope(), direct.slope, 1e-12 * std::abs(direct.slope) + 1e-15);
  double mean = 0.0;
  for (const double v : r) mean += v / static_cast<double>(r.size());
  EXPECT_NEAR(window.mean(), mean, 1e-12);
}

TEST(TrendWindow, OnConsecutiveTicksTheSumsAreTheDiscreteOrthogonalPolynomials) {
  // r = k^2 on k = 0..4: the bend is exactly 1 and nothing is left over; the slope is the plain
  // least-squares line's, sum (k - 2) k^2 / sum (k - 2)^2 = 40 / 10 = 4.
  TrendWindow window;
  for (int tick = 0; tick < 5; ++tick) window.add(tick * tick, tick * kPeriod, kPeriod);
  const TrendWindow::Fit fit = window.fit();
  EXPECT_NEAR(fit.c1, 4.0, 1e-12);
  EXPECT_NEAR(fit.c2, 1.0, 1e-12);
  EXPECT_NEAR(fit.s, 0.0, 1e-6);
  // A line 2 + 3 k with residuals +1, -1, +1, -1, +1 ... on k = 0..5: c1 is the line's slope
  // fitted to them, sum p1^2 = n (n^2 - 1) / 12 = 17.5, sum p2^2 = n (n^2 - 1) (n^2 - 4) / 180 = 37.33.
  TrendWindow alternating;
  std::vector<double> k, r;
  for (int tick = 0; tick < 6; ++tick) {
    const double value = 2.0 + 3.0 * tick + (tick % 2 == 0 ? 1.0 : -1.0);
    k.push_back(tick), r.push_back(value);
    alternating.add(value, 7.0 + tick * kPeriod, kPeriod);
  }
  const DirectFit direct = direct_fit(k, r);
  const TrendWindow::Fit a = alternating.fit();
  EXPECT_NEAR(a.c1, direct.slope, 1e-12);
  EXPECT_NEAR(a.se1, a.s / std::sqrt(17.5), 1e-12);
  EXPECT_NEAR(a.se2, a.s / std::sqrt(6.0 * 35.0 * 32.0 / 180.0), 1e-12);
  EXPECT_NEAR(a.c2, direct.bend, 1e-12);
}

TEST(TrendWindow, LongWindowsKeepTheirPrecision) {
  // The moments come from raw sums of k^4, which lose digits to cancellation as the window grows:
  // on consecutive ticks with alternating values (a healthy reading, flat), se_2 / s must still be
  // 1 / sqrt(n (n^2 - 1) (n^2 - 4) / 180) and se_1 / s 1 / sqrt(n (n^2 - 1) / 12): over 1e5 ticks
  // (100 s at 1 kHz) and 3.6e6 (an hour).
  for (const int n : {100000, 3600000}) {
    TrendWindow window;
    for (int tick = 0; tick < n; ++tick) window.add(tick % 2 == 0 ? 1.0 : -1.0, tick * 1e-3, 1e-3);
    const TrendWindow::Fit fit = window.fit();
    const double nd = n;
    const double p1p1 = nd * (nd * nd - 1.0) / 12.0, p2p2 = nd * (nd * nd - 1.0) * (nd * nd - 4.0) / 180.0;
    // se = s / sqrt(sum p^2): the sum's relative error is twice se's.
    const double rel1 = 2.0 * std::abs(fit.se1 * std::sqrt(p1p1) / fit.s - 1.0);
    const double rel2 = 2.0 * std::abs(fit.se2 * std::sqrt(p2p2) / fit.s - 1.0);
    std::printf("n = %d: relative error of sum p1^2 %.1e, of sum p2^2 %.1e\n", n, rel1, rel2);
    // What the header states: below 1e-12 on sum p2^2 over 1e5 ticks, 1e-9 over 3.6e6.
    EXPECT_LT(rel1, 1e-10) << n;
    EXPECT_LT(rel2, n <= 100000 ? 1e-12 : 1e-9) << n;
    EXPECT_TRUE(fit.flat(5.0)) << n;
  }
}

TEST(TrendWindow, SamplesAtOneTimeShowNoSlopeAndAreNotFlat) {
  // Four samples with no time between them: no slope can be seen, so the window is not flat
  // (a drift's end must not be taken on such a window), whatever the values.
  TrendWindow window;
  for (int i = 0; i < 4; ++i) window.add(1.0 + i, 3.0, kPeriod);
  const TrendWindow::Fit fit = window.fit();
  EXPECT_TRUE(std::isinf(fit.se1));
  EXPECT_TRUE(std::isinf(fit.se2));
  EXPECT_FALSE(fit.flat(5.0));
  EXPECT_EQ(window.slope(), 0.0);
  // A flat window, by contrast: 0, 1, 0, 1 ... on consecutive ticks, no slope, no bend.
  TrendWindow level;
  for (int tick = 0; tick < 40; ++tick) level.add(tick % 2, tick * kPeriod, kPeriod);
  EXPECT_TRUE(level.fit().flat(5.0));
  level.restart();
  EXPECT_EQ(level.count(), 0);
  EXPECT_EQ(level.mean(), 0.0);
}

}  // namespace
}  // namespace ftsense::generic
