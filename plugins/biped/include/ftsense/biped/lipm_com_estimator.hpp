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
// readings mean the filter is lost, and the axis restarts on the ZMP (counted too).
//
// Physics gate on the ZMP: c'' = omega0^2 (c - p) and no sole holds a horizontal force above its
// normal force (friction coefficient mu <= 1), so |c'' | <= g and |c - p| <= z_c. A ZMP farther
// than z_c + 3 sigma_c from the CoM (sigma_c = sqrt(P(0,0))) asks for the impossible and is
// dropped like a broken one.
//
// Readiness: the ZMP is what makes c observable; without it the IMU only integrates and P(0,0)
// grows. P_inf, the steady-state posterior variance of c with every measurement present, is
// computed at construction from the Riccati recursion (so it follows T and the noise parameters).
// While P(0,0) > max_com_std_ratio^2 P_inf on either axis (the ZMP missing or dropped for a while,
// or the filter just started) the CoM is not known well enough to split forces by: com x, y are
// NaN (the virtual sensor is not ready) and output `ready` is 0. When the ZMP comes back to a CoM
// that is not ready, the axis re-acquires as at the start but mid-motion, c'' from the IMU and
// c = p + c''/omega0^2, c' = 0 with the initial covariance: the state that drifted on the IMU alone
// has a velocity error that would otherwise take seconds to correct. Allocation-free.
//
// Cost: the covariance recursion (prediction and updates) depends on P and on which updates
// apply, not on the data; once P sits at its fixed point (every entry equal from tick to tick, most
// ticks of a walk) each tick replays the gains recorded on the last tick that ran it, and updates
// only the state (exact: the same operations on the same numbers).

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
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"([{"com_height_m": 0.7, "zmp_source": "planned"},
       {"com_height_m": 0.7, "zmp_source": "measured", "use_kinematic_com": true}])";

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
    double max_com_std_ratio = 2.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kImuAcc, kBaseRpy, kZmp, kKinematicCom };
  enum Output : std::size_t { kCom, kComVelocity, kComAcceleration, kComVariance, kCovarianceResets, kReady };

  // P_inf: the steady-state posterior variance of c [m^2] with every measurement present.
  [[nodiscard]] double steady_state_com_variance() const noexcept { return steady_state_com_variance_; }

  // The state covariance P of axis 0 (x) or 1 (y) after the last tick [m^2, m^2/s, ...].
  [[nodiscard]] const Eigen::Matrix3d& covariance(std::size_t axis) const noexcept { return axes_[axis].P; }
  // Drops the covariance recursion kept for replay (Axis::CovarianceTick): the next tick runs it
  // in full. The outputs do not change (the replay is exact); tests compare the two paths by it.
  void forget_covariance_recursion() noexcept {
    for (Axis& a : axes_) a.recursion.valid = false;
  }

  LipmComEstimator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  // The scalar updates of a tick, in order: IMU acceleration, ZMP, kinematic CoM.
  static constexpr std::size_t kUpdates = 3;
  struct Axis {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
    double previous_zmp = 0.0;
    double last_good_com = 0.0;  // the CoM of the last healthy tick, where a restart begins
    bool restarted = false;
    int gated_zmp_ticks = 0;  // consecutive ZMP readings rejected by the gate
    bool zmp_used_last_tick = true;  // false while the ZMP is missing or dropped
    double resets = 0.0;  // restarts after a non-finite state or a covariance that is not positive definite
    // The covariance recursion of the last tick that ran it, to replay: it depends on P and on
    // which updates applied, never on the data. When P before the prediction equals, entry by
    // entry, what it was then (at its fixed point, most ticks of a walk), the same updates give the
    // same gains and the same P, so only the state is updated; an update that applies now and did
    // not then (or the reverse: a gate, a missing reading) runs the recursion from there. Exact: a
    // replayed tick computes what the recursion would (-0.0 and +0.0 match, and give equal values).
    struct CovarianceTick {
      bool valid = false;
      Eigen::Matrix3d P_in = Eigen::Matrix3d::Zero();  // P before the prediction
      std::array<Eigen::Matrix3d, kUpdates> P_before{};  // P before each update
      std::array<bool, kUpdates> applied{};              // the update changed the state and P
      std::array<double, kUpdates> innovation_variance{};  // s = h P h^T + r
      std::array<Eigen::Vector3d, kUpdates> gain{};      // k = P h^T / s
      Eigen::Matrix3d P_out = Eigen::Matrix3d::Zero();
    } recursion;
  };
  // One scalar Kalman update; skipped when z is not finite or its innovation fails the 100-sigma
  // gate. Returns whether it applied; s and k as it computed them (s always, k when applied).
  bool update(Axis& axis, const Eigen::RowVector3d& h, double z, double variance, double& s_out,
              Eigen::Vector3d& k_out) noexcept;
  // Iterates the covariance recursion with every measurement until P(0,0) settles.
  [[nodiscard]] double solve_steady_state_com_variance() const noexcept;
  static constexpr double kGateSigma2 = 1e4;
  static constexpr int kGatedTicksBeforeRestart = 200;

  Ports ports_;
  Params params_;
  double period_s_;
  double omega2_;
  Eigen::Matrix3d transition_;
  Eigen::Matrix3d process_noise_;
  double steady_state_com_variance_ = 0.0;
  std::array<Axis, 2> axes_;
  bool initialised_ = false;
};

}  // namespace ftsense::biped
