#pragma once
// An accelerometer on a free-floating body (a robot's trunk) that measures the motion the
// simulation actually integrates.
//
// MuJoCo's accelerometer sensor reads the acceleration of the forward dynamics, mjData.qacc. But
// the Euler integrator treats joint damping implicitly: it advances the velocities by
// (M + T D)^-1 (...) rather than by qacc T, so with the stiff, heavily damped joint servos of a
// walking robot (1000 N m s/rad) the trunk moves otherwise than qacc says: on the simulated
// SURALP the total force m (R f)_z from that sensor was 21.4 and 36.6 N RMS off the pads' true
// sum at the two gaits, 10.1 and 14.1 N with this model (sim/README.md). A real IMU measures the
// body's true motion, so this model reads the second difference of the site's position
// p_s = p_o + R r over the ticks the integrator produced:
//
//   a_s(t) = (p_s(t + T) - 2 p_s(t) + p_s(t - T)) / T^2     the site's acceleration, world frame
//   f(t)   = R_s(t)^T (a_s(t) - g_W)                          specific force, site frame [m/s^2]
//
// p_o is the free joint's position (qpos[0..2]), R the body's orientation (qpos[3..6]), r the
// site's position in the body frame, R_s = R R_bs the site's orientation, g_W = MuJoCo's gravity
// (0, 0, -g). At the first tick, p_s(t - T) is extrapolated back with the state's velocity
// v_o + R (omega x r). The logged base pose and the IMU then agree: the IMU site's position, twice
// differenced, gives the same acceleration (sim/README.md, "Log").

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <mujoco/mujoco.h>

namespace ftsense::sim {

class FreeBodyAccelerometer {
 public:
  /// `site` must be fixed in a body whose parent joint is a free joint (throws ModelError).
  FreeBodyAccelerometer(const mjModel* m, int site);

  /// Records the body's state at time t: call right before mj_step.
  void before_step(const mjData* d);

  /// The specific force at time t [m/s^2, site frame] once mj_step has advanced the state to t + T.
  [[nodiscard]] Eigen::Vector3d after_step(const mjData* d);

 private:
  [[nodiscard]] Eigen::Quaterniond orientation(const mjData* d) const;
  [[nodiscard]] Eigen::Vector3d site_position(const mjData* d) const;
  [[nodiscard]] Eigen::Vector3d site_velocity(const mjData* d) const;

  int qpos_adr_ = 0;
  int dof_adr_ = 0;
  double period_s_ = 0.0;
  Eigen::Vector3d site_in_body_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond site_orientation_in_body_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d position_before_ = Eigen::Vector3d::Zero();          // p_s(t)
  Eigen::Vector3d velocity_before_ = Eigen::Vector3d::Zero();          // (p_s(t) - p_s(t - T)) / T
  bool has_velocity_ = false;
  Eigen::Quaterniond orientation_before_ = Eigen::Quaterniond::Identity();  // R(t)
};

}  // namespace ftsense::sim
