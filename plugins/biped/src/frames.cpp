#include "ftsense/biped/frames.hpp"

#include <algorithm>

namespace ftsense::biped {

namespace {
double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}
}  // namespace

SupportPolygon::SupportPolygon(const std::vector<std::array<double, 2>>& points) {
  std::vector<Eigen::Vector2d> p;
  for (const auto& q : points) p.emplace_back(q[0], q[1]);
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  // Andrew's monotone chain: lower hull, then upper hull, counter-clockwise.
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  hull_ = std::move(hull);
  for (const auto& v : hull_) centroid_ += v;
  if (!hull_.empty()) centroid_ /= static_cast<double>(hull_.size());
}

bool SupportPolygon::contains(const Eigen::Vector2d& p) const noexcept {
  if (hull_.size() < 3) return false;
  for (std::size_t i = 0; i < hull_.size(); ++i) {
    if (cross(hull_[i], hull_[(i + 1) % hull_.size()], p) < 0) return false;
  }
  return true;
}

Eigen::Vector2d SupportPolygon::clamp(const Eigen::Vector2d& p) const noexcept {
  if (hull_.empty()) return p;
  if (contains(p)) return p;
  Eigen::Vector2d best = hull_.front();
  double best_distance = (p - best).squaredNorm();
  for (std::size_t i = 0; i < hull_.size(); ++i) {
    const Eigen::Vector2d a = hull_[i];
    const Eigen::Vector2d edge = hull_[(i + 1) % hull_.size()] - a;
    const double length2 = edge.squaredNorm();
    const double t = length2 > 0 ? std::clamp((p - a).dot(edge) / length2, 0.0, 1.0) : 0.0;
    const Eigen::Vector2d q = a + t * edge;
    const double d = (p - q).squaredNorm();
    if (d < best_distance) {
      best_distance = d;
      best = q;
    }
  }
  return best;
}

}  // namespace ftsense::biped
