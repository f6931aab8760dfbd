#pragma once
// CoM estimation on the linear inverted pendulum (method.md section 1; paper eq. 1-3).
//
// Per horizontal axis (x, y), omega0^2 = g / z_c, LIPM  c'' = omega0^2 (c - p). Its jerk form,
// discretised with period T, is the Kalman filter's process model, state s = [c, c', c'']:
//
//   c_k   = c_{k-1} + T c'_{k-1} + T^2/2 c''_{k-1}
//   c'_k  = c'_{k-1} + T c''_{k-1}
//   c''_k = c''_{k-1} + T omega0^2 (c'_{k-1} - p'_{k-1}),   p'_{k-1} = (p_k - p_{k-1}) / T
//
// Measurements (scalar, sequential updates):
//   1. IMU: the horizontal CoM acceleration a = (R_wb f_imu)_xy (gravity is vertical, so the
//      horizontal specific force is the horizontal acceleration): H = [0 0 1], var acc_noise^2.
//   2. LIPM output equation p = c - c'' / omega0^2 with p the ZMP: H = [1 0 -1/omega0^2],
//      var zmp_noise^2. This makes c observable (the IMU alone does not).
//   3. Optional kinematic CoM c_kin (use_kinematic_com): H = [1 0 0], var kinematic_com_noise^2.
// `zmp_source` says which ZMP feeds it: the gait plan's (input `planned_zmp`, independent of the
// force sensors) or one measured from the force sensors (input `measured_zmp`, the paper's choice,
// which makes the virtual sensor depend on the sensors it judges: the pipeline then trips the
// independence rule unless the config allows it).
//
// Outputs: com = [c_x, c_y, z_c] in the world frame [m] (z_c above the ground plane z = 0),
// com_velocity [m/s], com_acceleration [m/s^2], com_variance = [P_x(0,0), P_y(0,0)] [m^2] (the
// posterior variance of c per axis, for health monitoring), covariance_resets = how many times each
// axis restarted since reset. The state starts at c = p (first ZMP), c' = c'' = 0. A non-finite
// measurement skips its update; the prediction always runs. P stays symmetric (symmetrised after
// each update); should the state stop being finite or P stop being positive definite (a Cholesky
// factorisation fails; hostile data), the axis restarts from its initial covariance and the restart
// is counted; it restarts at the last healthy CoM and takes the ZMP rate afresh. A measurement
// whose innovation exceeds 100 standard deviations (sqrt of H P H^T + R) is dropped as broken (a
// ZMP so dropped is treated as missing, in the prediction too); 200 consecutive dropped ZMP
// readings mean the filter is lost, and the axis restarts on the ZMP (counted too). Allocation-free.

#include <array>
#include <string_view>

#include <Eigen/Core>

#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class LipmComEstimator {
 public:
  static constexpr std::string_view name = "lipm_com_estimator";
  static constexpr std::string_view summary =
      "CoM Kalman filter on the jerk-form LIPM with IMU acceleration and ZMP (paper eq. 1-3)";

  enum class ZmpSource { planned, measured };

  struct Params {
    double com_height_m = 0.0;
    double gravity_m_s2 = 9.806;
    ZmpSource zmp_source = ZmpSource::planned;
    bool use_kinematic_com = false;
    double jerk_noise_m_s3 = 5.0;
    double acc_noise_m_s2 = 0.5;
    double zmp_noise_m = 0.03;
    double kinematic_com_noise_m = 0.01;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kImuAcc, kBaseRpy, kZmp, kKinematicCom };
  enum Output : std::size_t { kCom, kComVelocity, kComAcceleration, kComVariance, kCovarianceResets };

  LipmComEstimator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  struct Axis {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
    double previous_zmp = 0.0;
    double last_good_com = 0.0;  // the CoM of the last healthy tick, where a restart begins
    bool restarted = false;
    int gated_zmp_ticks = 0;  // consecutive ZMP readings rejected by the gate
    double resets = 0.0;  // restarts after a non-finite state or a covariance that is not positive definite
  };
  // One scalar Kalman update; skipped when z is not finite or its innovation fails the 100-sigma gate.
  void update(Axis& axis, const Eigen::RowVector3d& h, double z, double variance) noexcept;
  static constexpr double kGateSigma2 = 1e4;
  static constexpr int kGatedTicksBeforeRestart = 200;

  Ports ports_;
  Params params_;
  double period_s_;
  double omega2_;
  Eigen::Matrix3d transition_;
  Eigen::Matrix3d process_noise_;
  std::array<Axis, 2> axes_;
  bool initialised_ = false;
};

}  // namespace ftsense::biped
