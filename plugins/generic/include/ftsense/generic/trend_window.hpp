#pragma once
// A signal's line and bend over a window of samples taken at ticks of a fixed period T, not
// necessarily consecutive (a test that skips unusable ticks keeps the time between the ones it
// takes): is the signal flat, or does it slope or bend beyond its own scatter?
//
// Sample i is the value r_i [the signal's unit] at abscissa k_i = round((t_i - t_0) / T) [ticks],
// t_0 the window's first sample's time. The fit is r ~ c0 + c1 p1(k) + c2 p2(k) by least squares on
// the polynomials of the window's abscissae orthogonal to 1 and to each other:
//
//   p1 = k - m,  p2 = p1^2 - a p1 - b,   m the abscissae's mean, mu_j their central moments,
//   b = mu2,  a = mu3 / mu2,   sum p1^2 = n mu2,  sum p2^2 = n (mu4 - a mu3 - mu2^2),
//   c_j = sum r p_j / sum p_j^2,  se_j = s / sqrt(sum p_j^2),
//   s^2 = (sum r^2 - (sum r)^2 / n - c1 sum r p1 - c2 sum r p2) / (n - 3)   (n - 3 degrees of freedom).
//
// c1 is the plain least-squares slope [unit per tick] (p1 is orthogonal to p2), c2 the bend, the
// coefficient of k^2 in the quadratic fit. On consecutive ticks (k = 0 .. n-1) these are the
// discrete orthogonal polynomials: a = 0, b = (n^2 - 1) / 12, sum p2^2 = n (n^2 - 1) (n^2 - 4) / 180.
// A coefficient whose polynomial vanishes on the window (all samples at one time: no slope can be
// seen) has an infinite standard error, and the window is then not flat: nothing was shown.
//
// Kept as running sums of k^0..k^4, r, k r, k^2 r and r^2: O(1) per sample, no allocation. The
// moments are taken from the raw sums, which loses a few digits to cancellation: relative error
// 6e-13 on sum p2^2 over 1e5 consecutive ticks, 1.2e-10 over 3.6e6 (an hour at 1 kHz), as
// tests/test_trend_window.cpp (LongWindowsKeepTheirPrecision) prints and bounds them.

namespace ftsense::generic {

class TrendWindow {
 public:
  struct Fit {
    double c1, se1;  // slope [unit / tick] and its standard error
    double c2, se2;  // bend [unit / tick^2] and its standard error
    double s;        // the samples' standard deviation about the line and the bend [unit]
    // Neither the slope nor the bend beyond z of its standard error, both standard errors finite.
    [[nodiscard]] bool flat(double z) const noexcept;
  };
  // Sample `value` at time t_s [s], on ticks of period_s [s] > 0.
  void add(double value, double t_s, double period_s) noexcept;
  void restart() noexcept;
  [[nodiscard]] int count() const noexcept { return count_; }
  // The values' mean (0 before the first sample).
  [[nodiscard]] double mean() const noexcept;
  // c1 [unit / tick] (0 before the abscissae span two ticks).
  [[nodiscard]] double slope() const noexcept;
  // The fit; meaningful from 4 samples on (s has n - 3 degrees of freedom).
  [[nodiscard]] Fit fit() const noexcept;

 private:
  struct Basis {
    double n, m, a, b, p1p1, p2p2;
  };
  [[nodiscard]] Basis basis() const noexcept;
  [[nodiscard]] double value_p1(const Basis& q) const noexcept;
  [[nodiscard]] double value_p2(const Basis& q) const noexcept;

  int count_ = 0;
  double t0_s_ = 0.0;
  double k_ = 0.0, kk_ = 0.0, kkk_ = 0.0, kkkk_ = 0.0;  // sums of the abscissae's powers
  double r_ = 0.0, kr_ = 0.0, kkr_ = 0.0, rr_ = 0.0;    // sums of r, k r, k^2 r, r^2
};

}  // namespace ftsense::generic
