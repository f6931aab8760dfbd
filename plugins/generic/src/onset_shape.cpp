#include "ftsense/generic/onset_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ftsense/generic/chi_square.hpp"

namespace ftsense::generic {

void LevelHistory::push(const LevelPoint& point) noexcept {
  points_[next_] = point;
  next_ = (next_ + 1) % kCapacity;
  count_ = std::min(count_ + 1, kCapacity);
}

std::size_t LevelHistory::ordered(std::span<LevelPoint> out) const noexcept {
  const std::size_t n = std::min(count_, out.size());
  const std::size_t first = (next_ + kCapacity - count_) % kCapacity;
  for (std::size_t i = 0; i < n; ++i) out[i] = points_[(first + i) % kCapacity];
  return n;
}

namespace {

constexpr double kMinLevelVariance = 1e-12;  // a level known to 1e-6 units: keeps the weights finite

// Weighted sums of one regressor u against the level over a range of points.
struct LevelSums {
  double w = 0.0, u = 0.0, y = 0.0, uu = 0.0, uy = 0.0, yy = 0.0;
  void add(double weight, double ui, double yi) noexcept {
    w += weight;
    u += weight * ui;
    y += weight * yi;
    uu += weight * ui * ui;
    uy += weight * ui * yi;
    yy += weight * yi * yi;
  }
  // chi-square of the constant fit y = c, and c.
  [[nodiscard]] double constant_chi2(double& c) const noexcept {
    if (!(w > 0.0)) return c = 0.0;
    c = y / w;
    return std::max(0.0, yy - w * c * c);
  }
  // chi-square of the line y = a + s u, and (a, s); a constant where u does not vary.
  [[nodiscard]] double line_chi2(double& a, double& s) const noexcept {
    if (!(w > 0.0)) return a = s = 0.0;
    const double um = u / w, ym = y / w;
    const double suu = uu - w * um * um, suy = uy - w * um * ym, syy = yy - w * ym * ym;
    s = suu > 1e-12 * std::max(1.0, uu) ? suy / suu : 0.0;
    a = ym - s * um;
    return std::max(0.0, syy - s * suy);
  }
};

double level_weight(const LevelPoint& p) noexcept { return 1.0 / std::max(p.variance, kMinLevelVariance); }

// Points [from, to) with u = their time from `origin`, or with u = max(0, t - hinge) when hinged,
// and their levels less `shift` (the last point's: no cancellation).
LevelSums level_sums(std::span<const LevelPoint> p, std::size_t from, std::size_t to, double origin, double shift,
                     bool hinged, double hinge) noexcept {
  LevelSums s;
  for (std::size_t i = from; i < to; ++i) {
    const double u = hinged ? std::max(0.0, p[i].t_s - hinge) : p[i].t_s - origin;
    s.add(level_weight(p[i]), u, p[i].level - shift);
  }
  return s;
}

}  // namespace

OnsetShape onset_shape(std::span<const LevelPoint> points, double z) noexcept {
  OnsetShape best;
  const std::size_t m = points.size();
  if (m < 2) return best;
  for (const LevelPoint& p : points) {
    if (!(p.variance > 0.0) || !std::isfinite(p.variance)) return best;
  }
  const double origin = points.back().t_s;  // times about the last point (no cancellation)
  const double shift = points.back().level;  // levels about the last (no cancellation)
  // The healthy points [0, j): their chi-square about their level c (less the shift).
  const auto healthy_chi2 = [&](std::size_t j, double& c) {
    return level_sums(points, 0, j, origin, shift, false, 0.0).constant_chi2(c);
  };
  // The step at its best j (j = 0: one level throughout).
  best.step_chi2 = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < m; ++j) {
    double c = 0.0, f = 0.0;
    const double chi2 = healthy_chi2(j, c) + level_sums(points, j, m, origin, shift, false, 0.0).constant_chi2(f);
    if (chi2 < best.step_chi2) {
      best.step_chi2 = chi2;
      best.first_faulty = j;
      best.onset_s = points[j].t_s;
      best.healthy_level = (j > 0 ? c : f) + shift;
    }
  }
  best.ramp_chi2 = best.step_chi2;
  if (m < 3) return best;
  // The ramp at its best j and onset.
  double ramp_chi2 = std::numeric_limits<double>::infinity();
  OnsetShape ramp;
  const auto consider = [&](double chi2, std::size_t j, double onset, double c, double s) {
    if (chi2 < ramp_chi2 && s != 0.0) {
      ramp_chi2 = chi2;
      ramp.first_faulty = j;
      ramp.onset_s = onset;
      ramp.healthy_level = c + shift;
      ramp.slope = s;
    }
  };
  {  // j = 0: a line through all points, its onset before the first
    double a = 0.0, s = 0.0;
    const double chi2 = level_sums(points, 0, m, origin, shift, false, 0.0).line_chi2(a, s);
    consider(chi2, 0, points.front().t_s, a + s * (points.front().t_s - origin), s);
  }
  for (std::size_t j = 1; j + 2 <= m; ++j) {
    // Unconstrained: the healthy points' level and a free line through the rest; it is the ramp
    // when that line leaves the level between the last healthy point and the first faulty one.
    double c = 0.0, a = 0.0, s = 0.0;
    const double chi2 = healthy_chi2(j, c) + level_sums(points, j, m, origin, shift, false, 0.0).line_chi2(a, s);
    if (s != 0.0) {
      const double onset = origin + (c - a) / s;
      if (onset >= points[j - 1].t_s && onset <= points[j].t_s) {
        consider(chi2, j, onset, c, s);
        continue;
      }
    }
    // Otherwise the best ramp of this j has its onset at an end of that interval: c and s fitted
    // on max(0, t - t0).
    for (const double hinge : {points[j - 1].t_s, points[j].t_s}) {
      double hc = 0.0, hs = 0.0;
      const double hinge_chi2 = level_sums(points, 0, m, origin, shift, true, hinge).line_chi2(hc, hs);
      consider(hinge_chi2, j, hinge, hc, hs);
    }
  }
  if (!std::isfinite(ramp_chi2)) return best;
  // Parameters fitted: c, the ramp's slope and its onset.
  const double dof = std::max(1.0, static_cast<double>(m) - 3.0);
  const double fits_within = chi_square_quantile_at_z(dof, z);
  ramp.step_chi2 = best.step_chi2;
  ramp.ramp_chi2 = ramp_chi2;
  if (best.step_chi2 - ramp_chi2 > z * z && ramp_chi2 <= fits_within) {
    ramp.ramp = true;
    return ramp;
  }
  best.ramp_chi2 = ramp_chi2;
  return best;
}

double step_within_a_point_chi2(std::span<const LevelPoint> points) noexcept {
  const std::size_t m = points.size();
  double best = std::numeric_limits<double>::infinity();
  if (m < 3) return best;
  for (const LevelPoint& p : points) {
    if (!(p.variance > 0.0) || !std::isfinite(p.variance)) return best;
  }
  const double origin = points.back().t_s;
  const double shift = points.back().level;
  for (std::size_t k = 1; k + 1 < m; ++k) {
    double c = 0.0, f = 0.0;
    const double chi2 = level_sums(points, 0, k, origin, shift, false, 0.0).constant_chi2(c) +
                        level_sums(points, k + 1, m, origin, shift, false, 0.0).constant_chi2(f);
    best = std::min(best, chi2);
  }
  return best;
}

}  // namespace ftsense::generic
