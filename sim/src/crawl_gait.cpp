#include "ftsense/sim/crawl_gait.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/LU>

namespace ftsense::sim {

namespace {

double smooth(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The point nearest p whose distance from every edge of triangle v is at least m (inside).
/// Candidates: p itself, p projected onto one inset edge line, or a corner of the inset triangle.
Eigen::Vector2d project_into_triangle(const Eigen::Vector2d& p, std::array<Eigen::Vector2d, 3> v, double m) {
  if (cross(v[1] - v[0], v[2] - v[0]) < 0.0) std::swap(v[1], v[2]);  // counter-clockwise
  std::array<Eigen::Vector2d, 3> n;
  std::array<double, 3> c{};
  for (std::size_t i = 0; i < 3; ++i) {
    const Eigen::Vector2d d = (v[(i + 1) % 3] - v[i]).normalized();
    n[i] = Eigen::Vector2d(-d.y(), d.x());  // inward for a counter-clockwise triangle
    c[i] = n[i].dot(v[i]) + m;
  }
  const auto feasible = [&](const Eigen::Vector2d& x) {
    for (std::size_t i = 0; i < 3; ++i)
      if (n[i].dot(x) < c[i] - 1e-12) return false;
    return true;
  };
  if (feasible(p)) return p;
  Eigen::Vector2d best = p;
  double best_d = std::numeric_limits<double>::infinity();
  const auto consider = [&](const Eigen::Vector2d& x) {
    if (feasible(x) && (x - p).norm() < best_d) {
      best = x;
      best_d = (x - p).norm();
    }
  };
  for (std::size_t i = 0; i < 3; ++i) consider(p + (c[i] - n[i].dot(p)) * n[i]);
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 1) % 3;
    Eigen::Matrix2d A;
    A << n[i].transpose(), n[j].transpose();
    consider(A.inverse() * Eigen::Vector2d(c[i], c[j]));
  }
  if (!std::isfinite(best_d))
    throw std::invalid_argument("crawl: stability_margin_m leaves no room inside the support triangle");
  return best;
}

}  // namespace

double support_margin_m(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& points) {
  if (points.empty()) return -std::numeric_limits<double>::infinity();
  // Convex hull, Andrew's monotone chain, counter-clockwise.
  std::vector<Eigen::Vector2d> pts = points;
  std::sort(pts.begin(), pts.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d> hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], pts[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 1] - hull[k - 2], pts[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  if (hull.size() < 3) {
    if (hull.size() == 1) return -(p - hull[0]).norm();
    const Eigen::Vector2d d = hull[1] - hull[0];
    const double s = std::clamp((p - hull[0]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return -(p - (hull[0] + s * d)).norm();
  }
  double margin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d d = (hull[(i + 1) % hull.size()] - hull[i]).normalized();
    margin = std::min(margin, cross(d, p - hull[i]));
  }
  return margin;
}

CrawlPlan::CrawlPlan(const CrawlParams& params, double hip_x_m, double foot_radius_m, double duration_s)
    : p_(params), r_(foot_radius_m) {
  const double shift = (1.0 - p_.swing_ratio) * 0.25 * p_.cycle_s;
  cycles_ = p_.num_cycles >= 0
                ? p_.num_cycles
                : std::max(0, static_cast<int>(std::floor((duration_s - 1.0 - p_.initial_stand_s - shift) / p_.cycle_s)));
  std::array<Eigen::Vector2d, 4> feet;
  for (int leg = 0; leg < 4; ++leg)
    feet[static_cast<std::size_t>(leg)] =
        Eigen::Vector2d(leg < 2 ? hip_x_m : -hip_x_m, leg % 2 == 0 ? p_.stance_half_width_m : -p_.stance_half_width_m);
  const auto centre = [](const std::array<Eigen::Vector2d, 4>& f) { return 0.25 * (f[0] + f[1] + f[2] + f[3]); };
  Eigen::Vector2d com = centre(feet);
  min_margin_ = std::numeric_limits<double>::infinity();
  for (int n = 0; n < 4 * cycles_; ++n) {
    const int leg = kCrawlOrder[static_cast<std::size_t>(n % 4)];
    const auto L = static_cast<std::size_t>(leg);
    std::array<Eigen::Vector2d, 3> tri;
    Eigen::Vector2d nominal = feet[L] + Eigen::Vector2d(0.5 * p_.stride_m, 0.0);
    for (std::size_t i = 0, j = 0; i < 4; ++i)
      if (i != L) {
        tri[j++] = feet[i];
        nominal += feet[i];
      }
    const Eigen::Vector2d target = project_into_triangle(0.25 * nominal, tri, p_.stability_margin_m);
    min_margin_ = std::min(min_margin_, support_margin_m(target, {tri[0], tri[1], tri[2]}));
    slots_.push_back(Slot{leg, feet, com, target});
    com = target;
    feet[L].x() += p_.stride_m;
  }
  final_feet_ = feet;
  final_com_ = centre(feet);
  if (slots_.empty()) min_margin_ = support_margin_m(final_com_, {feet[0], feet[1], feet[2], feet[3]});
}

double CrawlPlan::walk_end_s() const {
  const double slot = 0.25 * p_.cycle_s;
  return p_.initial_stand_s + static_cast<double>(slots_.size()) * slot + (slots_.empty() ? 0.0 : (1.0 - p_.swing_ratio) * slot);
}

CrawlSample CrawlPlan::sample(double t) const {
  CrawlSample s;
  const double slot = 0.25 * p_.cycle_s;
  const double shift = (1.0 - p_.swing_ratio) * slot;
  const auto set_feet = [&](const std::array<Eigen::Vector2d, 4>& f) {
    for (std::size_t i = 0; i < 4; ++i) s.foot[i] = Eigen::Vector3d(f[i].x(), f[i].y(), r_);
  };
  const double tw = t - p_.initial_stand_s;
  if (slots_.empty() || tw < 0.0) {
    set_feet(slots_.empty() ? final_feet_ : slots_.front().feet);
    s.com = slots_.empty() ? final_com_ : slots_.front().com_from;
    return s;
  }
  const auto n = static_cast<std::size_t>(std::floor(tw / slot));
  if (n >= slots_.size()) {  // final shift to the centre, then stand
    set_feet(final_feet_);
    const double tau = (tw - static_cast<double>(slots_.size()) * slot) / shift;
    s.com = slots_.back().com_to + (final_com_ - slots_.back().com_to) * smooth(tau);
    return s;
  }
  const Slot& sl = slots_[n];
  set_feet(sl.feet);
  const double local = tw - static_cast<double>(n) * slot;
  if (local < shift) {
    s.com = sl.com_from + (sl.com_to - sl.com_from) * smooth(local / shift);
    return s;
  }
  s.com = sl.com_to;
  const auto L = static_cast<std::size_t>(sl.leg);
  const double tau = std::clamp((local - shift) / (slot - shift), 0.0, 1.0);
  s.foot[L].x() += p_.stride_m * smooth(tau);
  s.foot[L].z() += p_.step_height_m * 16.0 * tau * tau * (1.0 - tau) * (1.0 - tau);
  s.contact[L] = false;
  s.swing_leg = sl.leg;
  return s;
}

}  // namespace ftsense::sim
