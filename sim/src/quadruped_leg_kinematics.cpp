#include "ftsense/sim/quadruped_leg_kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace ftsense::sim {

Eigen::Vector3d quadruped_leg_forward(const QuadrupedLegGeometry& g, const QuadrupedLegAngles& q) {
  const double ux = -g.thigh_m * std::sin(q[1]) - g.shank_m * std::sin(q[1] + q[2]);
  const double uz = -g.thigh_m * std::cos(q[1]) - g.shank_m * std::cos(q[1] + q[2]);
  return {ux, -std::sin(q[0]) * uz, std::cos(q[0]) * uz};
}

QuadrupedLegIk quadruped_leg_inverse(const QuadrupedLegGeometry& g, const Eigen::Vector3d& p) {
  QuadrupedLegIk r;
  const double L1 = g.thigh_m, L2 = g.shank_m;
  const double D = std::hypot(p.y(), p.z());
  if (!(D > 0.0)) r.reachable = false;
  r.q[0] = std::atan2(p.y(), -p.z());
  double C = std::hypot(p.x(), D);
  // A hair inside the workspace so acos stays finite; the flag reports real clamping only.
  const double lo = std::abs(L1 - L2) + 1e-9, hi = L1 + L2 - 1e-9;
  if (C < lo || C > hi) {
    r.reachable = false;
    C = std::clamp(C, lo, hi);
  }
  const double c2 = std::clamp((C * C - L1 * L1 - L2 * L2) / (2.0 * L1 * L2), -1.0, 1.0);
  r.q[2] = -std::acos(c2);
  const double phi = std::atan2(-p.x(), D);
  r.q[1] = phi - std::atan2(L2 * std::sin(r.q[2]), L1 + L2 * std::cos(r.q[2]));
  return r;
}

}  // namespace ftsense::sim
