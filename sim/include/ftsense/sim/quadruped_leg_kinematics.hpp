#pragma once
// Analytic kinematics of one 3-DOF quadruped leg: hip abduction (x), hip flexion (y), knee (y),
// the two hip axes intersecting at the hip point. q = [abd, flex, knee], foot = the foot sphere's
// centre, p = foot - hip point in the trunk frame.
// Forward:
//   p = Rx(q0) Ry(q1) [ (0,0,-L1) + Ry(q2) (0,0,-L2) ]
//   i.e. with u_x = -L1 sin q1 - L2 sin(q1+q2), u_z = -L1 cos q1 - L2 cos(q1+q2) (the leg in
//   its own sagittal plane): p = (u_x, -sin(q0) u_z, cos(q0) u_z).
// Inverse (the leg points down, u_z < 0; the knee bends backward, q2 <= 0):
//   D = sqrt(p_y^2 + p_z^2),  q0 = atan2(p_y, -p_z)           (u_z = -D)
//   C^2 = p_x^2 + D^2,        q2 = -acos((C^2 - L1^2 - L2^2) / (2 L1 L2))
//   phi = atan2(-p_x, D)      (direction of the foot from the hip in the sagittal plane)
//   q1 = phi - atan2(L2 sin q2, L1 + L2 cos q2)
// Units: m, rad.
#include <array>

#include <Eigen/Core>

namespace ftsense::sim {

struct QuadrupedLegGeometry {
  double thigh_m = 0.20;  ///< L1
  double shank_m = 0.20;  ///< L2
};

using QuadrupedLegAngles = std::array<double, 3>;

struct QuadrupedLegIk {
  QuadrupedLegAngles q{};
  bool reachable = true;  ///< false if C had to be clamped to [|L1-L2|, L1+L2] or D was 0
};

/// Foot centre relative to the hip point, trunk frame.
[[nodiscard]] Eigen::Vector3d quadruped_leg_forward(const QuadrupedLegGeometry& g, const QuadrupedLegAngles& q);

/// Joint angles placing the foot centre at p (relative to the hip point, trunk frame).
[[nodiscard]] QuadrupedLegIk quadruped_leg_inverse(const QuadrupedLegGeometry& g, const Eigen::Vector3d& p);

}  // namespace ftsense::sim
