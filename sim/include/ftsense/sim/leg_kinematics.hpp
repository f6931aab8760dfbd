#pragma once
// Analytic kinematics of one 6-DOF leg (hip yaw-roll-pitch, knee pitch, ankle pitch-roll).
//
// With q = [q0..q5] = [hip yaw, hip roll, hip pitch, knee, ankle pitch, ankle roll] and the pelvis
// orientation R_b, hip point h (world):
//   R_foot = R_b Rz(q0) Rx(q1) Ry(q2) Ry(q3) Ry(q4) Rx(q5)
//   ankle  = h + R_b Rz(q0) Rx(q1) Ry(q2) [ (0,0,-A) + Ry(q3) (0,0,-B) ]
//   sole   = ankle - R_foot (0,0,h_s)
// Inverse: with v = R_foot^T (h - ankle) (ankle-to-hip in the foot frame), C = |v|,
//   q3 = acos((C^2 - A^2 - B^2) / (2AB))            (knee bent forward, q3 >= 0)
//   q5 = atan2(v_y, v_z)
//   q4 = atan2(-A sin q3, A cos q3 + B) - atan2(v_x, sqrt(v_y^2 + v_z^2))
//   Rz(q0) Rx(q1) Ry(q2) = R_b^T R_foot (Ry(q3 + q4) Rx(q5))^T  decomposed as Z-X-Y Euler angles.
// Units: m, rad.
#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ftsense::sim {

struct LegGeometry {
  double upper_m = 0.280;  ///< A
  double lower_m = 0.270;  ///< B
  double sole_m = 0.124;   ///< h_s
};

/// Position and orientation of a frame in world coordinates.
struct Pose {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};

using LegAngles = std::array<double, 6>;

struct LegIkResult {
  LegAngles q{};
  bool reachable = true;  ///< false if the hip-ankle distance had to be clamped to [|A-B|, A+B]
};

[[nodiscard]] Eigen::Matrix3d rot_x(double a);
[[nodiscard]] Eigen::Matrix3d rot_y(double a);
[[nodiscard]] Eigen::Matrix3d rot_z(double a);
/// R = Rz(yaw) Ry(pitch) Rx(roll) and back (the log's rpy convention).
[[nodiscard]] Eigen::Matrix3d rpy_to_matrix(double roll, double pitch, double yaw);
[[nodiscard]] Eigen::Vector3d matrix_to_rpy(const Eigen::Matrix3d& R);

/// Sole (foot) frame pose from the hip point pose (hip.p: hip point, hip.R: pelvis orientation).
[[nodiscard]] Pose leg_forward(const LegGeometry& g, const Pose& hip, const LegAngles& q);

/// Joint angles placing the sole frame at `sole` for the given hip point pose.
[[nodiscard]] LegIkResult leg_inverse(const LegGeometry& g, const Pose& hip, const Pose& sole);

}  // namespace ftsense::sim
