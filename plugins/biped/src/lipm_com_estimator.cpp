#include "ftsense/biped/lipm_com_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ftsense/biped/cholesky_pivots.hpp"
#include "ftsense/biped/frames.hpp"

namespace ftsense::biped {

namespace {
// Initial state covariance: 0.1 m on c, 0.1 m/s on c', 1 m/s^2 on c'' (standard deviations).
Eigen::Matrix3d initial_covariance() noexcept { return Eigen::Vector3d(1e-2, 1e-2, 1.0).asDiagonal(); }
}  // namespace

void LipmComEstimator::Params::describe(ParamSchema<Params>& schema) {
  schema.add("com_height_m", &Params::com_height_m, "constant CoM height z_c of the LIPM")
      .unit("m").greater_than(0.0).required().plausible(0.05, 3.0, "CoM height: 0.1 m toys to 2 m machines");
  schema.add("gravity_m_s2", &Params::gravity_m_s2, "gravity g").unit("m/s^2").greater_than(0.0)
      .plausible(1.5, 15.0, "9.81 on Earth, 1.62 on the Moon, 3.71 on Mars");
  schema.add_choice("zmp_source", &Params::zmp_source,
                    "which ZMP feeds the LIPM: the gait plan's (independent of the force sensors) or "
                    "one measured by the force sensors (the paper's choice)",
                    {{"planned", ZmpSource::planned}, {"measured", ZmpSource::measured}});
  schema.add("use_kinematic_com", &Params::use_kinematic_com,
             "also correct with a kinematic CoM measurement (adds input kinematic_com)");
  schema.add("jerk_noise_m_s3", &Params::jerk_noise_m_s3,
             "process noise: standard deviation of the CoM jerk (drives c'' per tick)")
      .unit("m/s^3").greater_than(0.0).plausible(1e-3, 1e4, "a walking robot's CoM jerk is 1 to 100 m/s^3");
  schema.add("acc_noise_m_s2", &Params::acc_noise_m_s2,
             "standard deviation of the IMU's horizontal acceleration as a CoM acceleration")
      .unit("m/s^2").greater_than(0.0)
      .plausible(1e-4, 100.0, "accelerometer noise and trunk vibration: 1 mm/s^2 to 10 m/s^2");
  schema.add("zmp_noise_m", &Params::zmp_noise_m, "standard deviation of the ZMP in p = c - c''/omega0^2")
      .unit("m").greater_than(0.0).plausible(1e-5, 1.0, "micrometres to a foot length");
  schema.add("kinematic_com_noise_m", &Params::kinematic_com_noise_m,
             "standard deviation of the kinematic CoM (if used)")
      .unit("m").greater_than(0.0).plausible(1e-5, 1.0, "micrometres to centimetres");
  schema.add("max_com_std_ratio", &Params::max_com_std_ratio,
             "the CoM is not ready while its standard deviation exceeds this many times the steady "
             "state's with every measurement present (the ZMP missing, dropped or just started)")
      .unit("1").greater_than(1.0).plausible(1.2, 100.0, "a few times the filter's settled uncertainty");
}

LipmComEstimator::LipmComEstimator(const Params& params, const StageContext& context)
    : params_(params), period_s_(context.sample_period_s()), omega2_(params.gravity_m_s2 / params.com_height_m) {
  const double t = period_s_;
  transition_ << 1.0, t, 0.5 * t * t,
                 0.0, 1.0, t,
                 0.0, t * omega2_, 1.0;
  // Jerk noise j enters as [T^3/6, T^2/2, T] j; its covariance is that outer product times var(j).
  const Eigen::Vector3d g(t * t * t / 6.0, 0.5 * t * t, t);
  process_noise_ = g * g.transpose() * params.jerk_noise_m_s3 * params.jerk_noise_m_s3;
  // Keep Q positive definite: a small floor on each state's diagonal.
  process_noise_.diagonal() += Eigen::Vector3d(1e-12, 1e-10, 1e-8);
  ports_.add_input(PortSpec{"imu_acc", 3, "m/s^2", "IMU specific force f_imu (the IMU is on the trunk)"}
                       .in_frame("imu"));
  ports_.add_input(PortSpec{"base_rpy", 3, "rad", "trunk orientation roll, pitch, yaw (R_wb)"}
                       .in_frame("base in world"));
  if (params.zmp_source == ZmpSource::planned) {
    ports_.add_input(PortSpec{"planned_zmp", 2, "m", "the gait plan's ZMP p_ref (x, y) (zmp_source = planned)"}
                         .in_frame("world"));
  } else {
    ports_.add_input(PortSpec{"measured_zmp", 2, "m", "the ZMP measured by the force sensors (x, y) (zmp_source = measured)"}
                         .in_frame("world"));
  }
  if (params.use_kinematic_com) {
    ports_.add_input(PortSpec{"kinematic_com", 2, "m", "CoM (x, y) from forward kinematics (use_kinematic_com)"}
                         .in_frame("world"));
  }
  ports_.add_output(PortSpec{"com", 3, "m", "CoM position (x, y, z_c)"}.in_frame("world"));
  ports_.add_output(PortSpec{"com_velocity", 2, "m/s", "CoM velocity (x, y)"}.in_frame("world"));
  ports_.add_output(PortSpec{"com_acceleration", 2, "m/s^2", "CoM acceleration (x, y)"}.in_frame("world"));
  ports_.add_output(PortSpec{"com_variance", 2, "m^2", "posterior variance of the CoM position (x, y)"}
                        .in_frame("world"));
  ports_.add_output({"covariance_resets", 2, "1",
                     "restarts of each axis (x, y) since reset: non-finite state or covariance not positive definite"});
  ports_.add_output({"ready", 1, "1",
                     "1 when the CoM's variance is within max_com_std_ratio^2 of its steady state on both axes"});
  steady_state_com_variance_ = solve_steady_state_com_variance();
  // Valid parameters always give a positive, finite P_inf; should they not, readiness falls back
  // on the starting variance rather than never (or always) being ready.
  if (!(steady_state_com_variance_ > 0.0) || !std::isfinite(steady_state_com_variance_)) {
    steady_state_com_variance_ = initial_covariance()(0, 0);
  }
  reset();
}

void LipmComEstimator::reset() noexcept {
  for (Axis& a : axes_) {
    a.s.setZero();
    a.P = initial_covariance();
    a.previous_zmp = 0.0;
    a.last_good_com = 0.0;
    a.restarted = false;
    a.gated_zmp_ticks = 0;
    a.zmp_used_last_tick = true;
    a.resets = 0.0;
    a.recursion.valid = false;
  }
  initialised_ = false;
}

namespace {
// h x with h's zero entries skipped. The filter's rows are sparse ((0, 0, 1), (1, 0, -1/omega0^2),
// (1, 0, 0)); for a finite x a skipped term is an exact zero, so the value is the dense product's,
// in two multiplications instead of three. (A non-finite P fails the health check at the end of
// the tick either way.)
double sparse_dot(const Eigen::RowVector3d& h, const double* x) noexcept {
  double sum = 0.0;
  bool any = false;
  for (int m = 0; m < 3; ++m) {
    if (h[m] == 0.0) continue;
    sum = any ? sum + h[m] * x[m] : h[m] * x[m];
    any = true;
  }
  return sum;
}
}  // namespace

bool LipmComEstimator::update(Axis& axis, const Eigen::RowVector3d& h, double z, double variance, double& s_out,
                              Eigen::Vector3d& k_out) noexcept {
  // Written out in scalars, each value computed as the Eigen expressions
  // ph = P h^T, s = h ph + r, k = ph / s, x += k nu, P -= k ph^T, P = (P + P^T) / 2 compute it
  // (the same operations per element), without their packed loads and stores.
  double ph[3];
  for (int i = 0; i < 3; ++i) {
    const double row[3] = {axis.P(i, 0), axis.P(i, 1), axis.P(i, 2)};
    ph[i] = sparse_dot(h, row);
  }
  const double s = sparse_dot(h, ph) + variance;
  s_out = s;
  if (!(s > 0.0) || !std::isfinite(z)) return false;
  const double innovation = z - sparse_dot(h, axis.s.data());
  // Gate: an innovation beyond 100 standard deviations is a broken reading, not information.
  if (!(innovation * innovation <= kGateSigma2 * s)) return false;
  double k[3];
  for (int i = 0; i < 3; ++i) k[i] = ph[i] / s;
  for (int i = 0; i < 3; ++i) k_out(i) = k[i];
  for (int i = 0; i < 3; ++i) axis.s(i) += k[i] * innovation;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) axis.P(i, j) -= k[i] * ph[j];
  }
  for (int j = 0; j < 3; ++j) {
    for (int i = j + 1; i < 3; ++i) axis.P(i, j) = axis.P(j, i) = 0.5 * (axis.P(i, j) + axis.P(j, i));
  }
  for (int i = 0; i < 3; ++i) axis.P(i, i) = 0.5 * (axis.P(i, i) + axis.P(i, i));
  return true;
}

double LipmComEstimator::solve_steady_state_com_variance() const noexcept {
  // The covariance recursion does not depend on the data: predict, then every scalar update.
  const Eigen::RowVector3d h_acc(0.0, 0.0, 1.0);
  const Eigen::RowVector3d h_zmp(1.0, 0.0, -1.0 / omega2_);
  const Eigen::RowVector3d h_com(1.0, 0.0, 0.0);
  const auto apply = [](Eigen::Matrix3d& p, const Eigen::RowVector3d& h, double variance) {
    const Eigen::Vector3d ph = p * h.transpose();
    const double s = h.dot(ph) + variance;
    p -= ph * ph.transpose() / s;
    p = (0.5 * (p + p.transpose())).eval();  // evaluated first: assigned in place, p^T would read written entries
  };
  Eigen::Matrix3d p = initial_covariance();
  double previous = p(0, 0);
  // The filter settles in a few time constants; 10^6 ticks bounds the loop for any sane T.
  for (int k = 0; k < 1000000; ++k) {
    p = transition_ * p * transition_.transpose() + process_noise_;
    apply(p, h_acc, params_.acc_noise_m_s2 * params_.acc_noise_m_s2);
    apply(p, h_zmp, params_.zmp_noise_m * params_.zmp_noise_m);
    if (params_.use_kinematic_com) apply(p, h_com, params_.kinematic_com_noise_m * params_.kinematic_com_noise_m);
    if (std::abs(p(0, 0) - previous) <= 1e-15 * p(0, 0)) break;
    previous = p(0, 0);
  }
  return p(0, 0);
}

void LipmComEstimator::step(const StepIO& io) noexcept {
  const auto imu = io.in(kImuAcc);
  const auto rpy = io.in(kBaseRpy);
  const auto zmp = io.in(kZmp);
  Eigen::Vector2d acc(std::nan(""), std::nan(""));
  if (all_finite(imu) && all_finite(rpy)) {
    const Eigen::Vector3d f = rotation_from_rpy_remembered(rpy) * vector3(imu);
    acc = f.head<2>();
  }
  if (!initialised_ && all_finite(zmp)) {
    for (int i = 0; i < 2; ++i) {
      axes_[i].s = Eigen::Vector3d(zmp[i], 0.0, 0.0);
      axes_[i].previous_zmp = zmp[i];
      axes_[i].last_good_com = zmp[i];
    }
    initialised_ = true;
  }
  const Eigen::RowVector3d h_acc(0.0, 0.0, 1.0);
  const Eigen::RowVector3d h_zmp(1.0, 0.0, -1.0 / omega2_);
  const Eigen::RowVector3d h_com(1.0, 0.0, 0.0);
  const std::array<Eigen::RowVector3d, kUpdates> h = {h_acc, h_zmp, h_com};
  const std::array<double, kUpdates> noise_variance = {params_.acc_noise_m_s2 * params_.acc_noise_m_s2,
                                                       params_.zmp_noise_m * params_.zmp_noise_m,
                                                       params_.kinematic_com_noise_m * params_.kinematic_com_noise_m};
  const double ready_variance = params_.max_com_std_ratio * params_.max_com_std_ratio * steady_state_com_variance_;
  for (int i = 0; i < 2; ++i) {
    Axis& a = axes_[i];
    // Predict with the ZMP rate of the last tick (zero when the ZMP is unavailable).
    // The ZMP, gated against the current state: a reading beyond 100 standard deviations is
    // broken and treated as missing (it must not drive the prediction's ZMP rate either).
    bool zmp_ok = std::isfinite(zmp[i]);
    if (zmp_ok) {
      const double zmp_variance = params_.zmp_noise_m * params_.zmp_noise_m;
      const double innovation = zmp[i] - h_zmp.dot(a.s);
      // |c - p| <= z_c (friction mu <= 1), widened by the CoM's own 3-sigma uncertainty.
      const bool physical = std::abs(zmp[i] - a.s(0)) <= params_.com_height_m + 3.0 * std::sqrt(std::max(a.P(0, 0), 0.0));
      if (physical && innovation * innovation <= kGateSigma2 * (h_zmp.dot(a.P * h_zmp.transpose()) + zmp_variance)) {
        a.gated_zmp_ticks = 0;
      } else if (++a.gated_zmp_ticks >= kGatedTicksBeforeRestart) {
        // The ZMP has disagreed absurdly for a while: take the filter, not the ZMP, as lost (were
        // the ZMP the broken one, the stages downstream see a CoM no stance foot can hold).
        a.s = Eigen::Vector3d(zmp[i], 0.0, 0.0);
        a.P = initial_covariance();
        a.previous_zmp = zmp[i];
        a.gated_zmp_ticks = 0;
        a.resets += 1.0;
      } else {
        zmp_ok = false;
      }
    }
    if (zmp_ok && !a.zmp_used_last_tick && a.P(0, 0) > ready_variance) {
      // The ZMP is back after the CoM lost track (not ready): the state drifted with the IMU for
      // a while, and its velocity would take seconds to correct. Re-acquire as at the start, but
      // mid-motion: c'' from the IMU and c = p + c'' / omega0^2 (the LIPM), c' learnt afresh.
      const double c_acc = std::isfinite(acc[i]) ? acc[i] : 0.0;
      a.s = Eigen::Vector3d(zmp[i] + c_acc / omega2_, 0.0, c_acc);
      a.P = initial_covariance();
      a.previous_zmp = zmp[i];
    }
    a.zmp_used_last_tick = zmp_ok;
    const double p = zmp_ok ? zmp[i] : a.previous_zmp;
    if (a.restarted) {
      a.previous_zmp = p;  // after a restart the rate starts again from this tick's ZMP
      a.restarted = false;
    }
    const double zmp_rate = (p - a.previous_zmp) / period_s_;
    a.s = transition_ * a.s;
    a.s(2) -= period_s_ * omega2_ * zmp_rate;
    a.previous_zmp = p;
    // The updates in order; one not made this tick reads NaN (update() skips it, P untouched).
    const std::array<double, kUpdates> z = {
        acc[i], zmp_ok ? p : std::numeric_limits<double>::quiet_NaN(),
        params_.use_kinematic_com ? io.in(kKinematicCom)[i] : std::numeric_limits<double>::quiet_NaN()};
    Axis::CovarianceTick& r = a.recursion;
    std::size_t u = 0;
    if (r.valid && a.P == r.P_in) {
      // Replay while each update applies exactly as it did then (its s and k are that tick's).
      for (; u < kUpdates; ++u) {
        const double s = r.innovation_variance[u];
        bool applies = s > 0.0 && std::isfinite(z[u]);
        double innovation = 0.0;
        if (applies) {
          innovation = z[u] - sparse_dot(h[u], a.s.data());
          applies = innovation * innovation <= kGateSigma2 * s;
        }
        if (applies != r.applied[u]) break;
        if (applies) {
          for (int m = 0; m < 3; ++m) a.s(m) += r.gain[u](m) * innovation;
        }
      }
      a.P = u == kUpdates ? r.P_out : r.P_before[u];
    } else {
      r.P_in = a.P;
      a.P = transition_ * a.P * transition_.transpose() + process_noise_;
    }
    if (u < kUpdates) {
      // The recursion from the first update that differs (all of them on a new P), recorded.
      for (; u < kUpdates; ++u) {
        r.P_before[u] = a.P;
        r.applied[u] = update(a, h[u], z[u], noise_variance[u], r.innovation_variance[u], r.gain[u]);
      }
      r.P_out = a.P;
      r.valid = true;
    }
  }
  const auto com = io.out(kCom);
  const auto vel = io.out(kComVelocity);
  const auto accel = io.out(kComAcceleration);
  const auto variance = io.out(kComVariance);
  bool ready = true;
  for (int i = 0; i < 2; ++i) {
    Axis& a = axes_[i];
    const bool healthy = a.s.allFinite() && a.P.allFinite() && cholesky_pivots_positive(a.P);
    if (!healthy) {
      // Hostile data overflowed the filter: restart this axis at its last good CoM, with the
      // initial covariance, and take the ZMP rate afresh on the next tick.
      a.s = Eigen::Vector3d(a.last_good_com, 0.0, 0.0);
      a.P = initial_covariance();
      a.restarted = true;
      a.resets += 1.0;
    }
    a.last_good_com = a.s(0);
    ready = ready && initialised_ && a.P(0, 0) <= ready_variance;  // never before a first ZMP
    com[i] = a.s(0);
    vel[i] = a.s(1);
    accel[i] = a.s(2);
    variance[i] = a.P(0, 0);
    io.out(kCovarianceResets)[i] = a.resets;
  }
  if (!ready) {
    // Not known well enough to split forces by: the virtual sensor is not ready.
    com[0] = com[1] = std::numeric_limits<double>::quiet_NaN();
  }
  com[2] = params_.com_height_m;
  io.out(kReady)[0] = ready ? 1.0 : 0.0;
}

}  // namespace ftsense::biped
