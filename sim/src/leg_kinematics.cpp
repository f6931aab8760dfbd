#include "ftsense/sim/leg_kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace ftsense::sim {

Eigen::Matrix3d rot_x(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix();
}
Eigen::Matrix3d rot_y(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
}
Eigen::Matrix3d rot_z(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Matrix3d rpy_to_matrix(double roll, double pitch, double yaw) {
  return rot_z(yaw) * rot_y(pitch) * rot_x(roll);
}

Eigen::Vector3d matrix_to_rpy(const Eigen::Matrix3d& R) {
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  return {roll, pitch, yaw};
}

Pose leg_forward(const LegGeometry& g, const Pose& hip, const LegAngles& q) {
  const Eigen::Matrix3d R_thigh = hip.R * rot_z(q[0]) * rot_x(q[1]) * rot_y(q[2]);
  const Eigen::Vector3d ankle =
      hip.p + R_thigh * (Eigen::Vector3d(0, 0, -g.upper_m) +
                         rot_y(q[3]) * Eigen::Vector3d(0, 0, -g.lower_m));
  Pose sole;
  sole.R = R_thigh * rot_y(q[3] + q[4]) * rot_x(q[5]);
  sole.p = ankle - sole.R * Eigen::Vector3d(0, 0, g.sole_m);
  return sole;
}

LegIkResult leg_inverse(const LegGeometry& g, const Pose& hip, const Pose& sole) {
  const double A = g.upper_m, B = g.lower_m;
  LegIkResult res;
  const Eigen::Vector3d ankle = sole.p + sole.R * Eigen::Vector3d(0, 0, g.sole_m);
  const Eigen::Vector3d v = sole.R.transpose() * (hip.p - ankle);
  double C = v.norm();
  const double cmin = std::abs(A - B) + 1e-9, cmax = A + B - 1e-9;
  if (C > cmax || C < cmin) {
    res.reachable = false;
    C = std::clamp(C, cmin, cmax);
  }
  auto& q = res.q;
  q[3] = std::acos(std::clamp((C * C - A * A - B * B) / (2.0 * A * B), -1.0, 1.0));
  q[5] = std::atan2(v.y(), v.z());
  q[4] = std::atan2(-A * std::sin(q[3]), A * std::cos(q[3]) + B) -
         std::atan2(v.x(), std::hypot(v.y(), v.z()));
  const Eigen::Matrix3d M =
      hip.R.transpose() * sole.R * (rot_y(q[3] + q[4]) * rot_x(q[5])).transpose();
  // M = Rz(a) Rx(b) Ry(c): column 1 = (-sa cb, ca cb, sb), row 2 = (-cb sc, sb, cb cc).
  q[0] = std::atan2(-M(0, 1), M(1, 1));
  q[1] = std::atan2(M(2, 1), std::hypot(M(0, 1), M(1, 1)));
  q[2] = std::atan2(-M(2, 0), M(2, 2));
  return res;
}

}  // namespace ftsense::sim
