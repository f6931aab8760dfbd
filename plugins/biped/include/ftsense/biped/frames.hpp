#pragma once
// Frames and small geometry used by the biped plugins (method.md section 0).
//
// World frame: z up, x forward, y left. Orientations are logged as roll, pitch, yaw [rad] with
// R = Rz(yaw) Ry(pitch) Rx(roll), mapping body coordinates to world coordinates.

#include <array>
#include <cmath>
#include <cstring>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace ftsense::biped {

[[nodiscard]] inline Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) noexcept {
  const double cr = std::cos(roll), sr = std::sin(roll);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  Eigen::Matrix3d r;
  r << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
       sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
       -sp, cp * sr, cp * cr;
  return r;
}

[[nodiscard]] inline Eigen::Matrix3d rotation_from_rpy(std::span<const double> rpy) noexcept {
  return rotation_from_rpy(rpy[0], rpy[1], rpy[2]);
}

// The same rotation, remembered per thread for the angles it was last asked for, compared bit for
// bit (so the result is rotation_from_rpy's, bit for bit, in a build that compiles both alike):
// stages that read one orientation on one tick (the trunk's, in the CoM filter and in the leg
// split) build it once: three sincos fewer per tick (docs/performance.md, "Rotations"). Any three
// angles are remembered alike, non-finite ones included. Not async-signal-safe (a handler calling it mid-update would see a torn memo).
[[nodiscard]] inline Eigen::Matrix3d rotation_from_rpy_remembered(std::span<const double> rpy) noexcept {
  struct Last {
    double rpy[3] = {0.0, 0.0, 0.0};
    double rotation[9] = {};  // column-major, as Eigen::Matrix3d
    bool known = false;
  };
  // Constant-initialised: no initialisation guard on the per-tick path.
  constinit thread_local Last last;
  const std::span<const double, 3> angles = rpy.first<3>();
  if (!last.known || std::memcmp(last.rpy, angles.data(), sizeof last.rpy) != 0) {
    Eigen::Map<Eigen::Matrix3d>(last.rotation) = rotation_from_rpy(angles);
    std::memcpy(last.rpy, angles.data(), sizeof last.rpy);
    last.known = true;
  }
  return Eigen::Map<const Eigen::Matrix3d>(last.rotation);
}

// The inverse of rotation_from_rpy: roll, pitch, yaw with pitch in [-pi/2, pi/2]. At pitch = +-pi/2
// (where only roll - yaw or roll + yaw is defined) yaw is set to 0; the rotation still round-trips.
[[nodiscard]] inline Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& r) noexcept {
  const double cos_pitch = std::hypot(r(0, 0), r(1, 0));
  const double pitch = std::atan2(-r(2, 0), cos_pitch);
  if (cos_pitch > 1e-12) return {std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))};
  return {std::atan2(-r(1, 2), r(1, 1)), pitch, 0.0};
}

[[nodiscard]] inline Eigen::Vector3d vector3(std::span<const double> v) noexcept {
  return {v[0], v[1], v[2]};
}

// The total ground reaction force F = m R_wb f_imu [N], world frame (method.md section 2): the
// IMU's specific force f_imu [m/s^2] includes gravity, limb inertia is neglected.
[[nodiscard]] inline Eigen::Vector3d ground_reaction_force(double mass_kg, std::span<const double> base_rpy,
                                                           std::span<const double> imu_acc) noexcept {
  return mass_kg * (rotation_from_rpy_remembered(base_rpy) * vector3(imu_acc));
}

[[nodiscard]] inline bool all_finite(std::span<const double> v) noexcept {
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

// A convex support polygon (the convex hull of a foot's contact points), counter-clockwise.
class SupportPolygon {
 public:
  explicit SupportPolygon(const std::vector<std::array<double, 2>>& points);
  // The closest point of the polygon (itself when inside). Allocation-free.
  [[nodiscard]] Eigen::Vector2d clamp(const Eigen::Vector2d& p) const noexcept;
  [[nodiscard]] bool contains(const Eigen::Vector2d& p) const noexcept;
  [[nodiscard]] Eigen::Vector2d centroid() const noexcept { return centroid_; }
  [[nodiscard]] const std::vector<Eigen::Vector2d>& vertices() const noexcept { return hull_; }

 private:
  std::vector<Eigen::Vector2d> hull_;
  Eigen::Vector2d centroid_ = Eigen::Vector2d::Zero();
};

}  // namespace ftsense::biped
