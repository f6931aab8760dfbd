#include "ftsense/generic/attitude_from_imu.hpp"

#include <cmath>
#include <limits>

#include "ftsense/generic/orientation_to_rpy.hpp"

namespace ftsense::generic {

namespace {

constexpr double kHalfTurn = 3.14159265358979323846;

bool finite3(std::span<const double> v) noexcept {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// q for R = Rz(yaw) Ry(pitch) Rx(roll): q = q_z(yaw) q_y(pitch) q_x(roll), as w, x, y, z.
std::array<double, 4> quaternion_from_rpy(double roll, double pitch, double yaw) noexcept {
  const double cr = std::cos(0.5 * roll), sr = std::sin(0.5 * roll);
  const double cp = std::cos(0.5 * pitch), sp = std::sin(0.5 * pitch);
  const double cy = std::cos(0.5 * yaw), sy = std::sin(0.5 * yaw);
  return {cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
          cr * cp * sy - sr * sp * cy};
}

}  // namespace

void AttitudeFromImu::Params::describe(ParamSchema<Params>& schema) {
  schema.add("tilt_time_constant_s", &Params::tilt_time_constant_s,
             "time constant tau with which the accelerometer corrects the tilt (roll, pitch)")
      .unit("s").greater_than(0.0)
      .plausible(0.01, 100.0, "tens of milliseconds (trust gravity) to a minute (trust the gyro)");
  schema.add("accept_acc_fraction", &Params::accept_acc_fraction,
             "the accelerometer corrects the tilt only while | |f| - g | <= this fraction of g")
      .unit("1").greater_than(0.0).plausible(0.01, 1.0, "1 % to 100 % of g");
  schema.add("gravity_m_s2", &Params::gravity_m_s2, "gravity g").unit("m/s^2").greater_than(0.0)
      .plausible(1.5, 15.0, "9.81 on Earth, 1.62 on the Moon, 3.71 on Mars");
  schema.add("initial_yaw_rad", &Params::initial_yaw_rad,
             "yaw at the start (gravity does not tell it); the gyro carries it from there")
      .unit("rad").plausible(-7.0, 7.0, "an angle within a turn");
}

AttitudeFromImu::AttitudeFromImu(const Params& params, const StageContext& context)
    : params_(params), period_s_(context.sample_period_s()) {
  ports_.add_input(PortSpec{"gyro", 3, "rad/s", "angular rate omega of the IMU (body)"}.in_frame("imu"));
  ports_.add_input(PortSpec{"imu_acc", 3, "m/s^2", "specific force f of the IMU (body) (reads +g up at rest)"}
                       .in_frame("imu"));
  ports_.add_output(PortSpec{"rpy", 3, "rad", "roll, pitch, yaw of the IMU, R = Rz(yaw) Ry(pitch) Rx(roll); NaN until started"}
                        .in_frame("imu in world"));
  reset();
}

void AttitudeFromImu::reset() noexcept {
  q_ = {1.0, 0.0, 0.0, 0.0};
  started_ = false;
}

void AttitudeFromImu::step(const StepIO& io) noexcept {
  const auto gyro = io.in(kGyro);
  const auto f = io.in(kImuAcc);
  const double f_norm = finite3(f) ? std::hypot(f[0], f[1], f[2]) : 0.0;
  // The accelerometer tells the tilt only while it reads gravity alone (at rest, or nearly).
  const bool reads_gravity =
      f_norm > 0.0 && std::abs(f_norm - params_.gravity_m_s2) <= params_.accept_acc_fraction * params_.gravity_m_s2;
  if (!started_ && reads_gravity) {
    const double roll = std::atan2(f[1], f[2]);
    const double pitch = std::atan2(-f[0], std::hypot(f[1], f[2]));
    q_ = quaternion_from_rpy(roll, pitch, params_.initial_yaw_rad);
    started_ = true;
  } else if (started_ && finite3(gyro)) {
    const auto [w, x, y, z] = q_;
    std::array<double, 3> rate{gyro[0], gyro[1], gyro[2]};
    if (reads_gravity) {
      // v = R^T z is the third row of R; e = (f / |f|) x v.
      const double vx = 2.0 * (x * z - y * w);
      const double vy = 2.0 * (y * z + x * w);
      const double vz = 1.0 - 2.0 * (x * x + y * y);
      const double ax = f[0] / f_norm, ay = f[1] / f_norm, az = f[2] / f_norm;
      const double gain = 1.0 / params_.tilt_time_constant_s;
      rate[0] += gain * (ay * vz - az * vy);
      rate[1] += gain * (az * vx - ax * vz);
      rate[2] += gain * (ax * vy - ay * vx);
    }
    const double angle = period_s_ * std::hypot(rate[0], rate[1], rate[2]);
    // More than half a turn in one tick cannot be integrated (it aliases): such a rate is a
    // broken reading, and the attitude holds as for a missing gyro.
    if (angle > 0.0 && angle <= kHalfTurn) {
      const double c = std::cos(0.5 * angle);
      const double s = std::sin(0.5 * angle) * period_s_ / angle;  // sin(|w|T/2) / |w|
      const double dx = s * rate[0], dy = s * rate[1], dz = s * rate[2];
      q_ = {w * c - x * dx - y * dy - z * dz, w * dx + x * c + y * dz - z * dy, w * dy - x * dz + y * c + z * dx,
            w * dz + x * dy - y * dx + z * c};
      // Keep |q| = 1 against rounding over millions of ticks.
      const double n = std::sqrt(q_[0] * q_[0] + q_[1] * q_[1] + q_[2] * q_[2] + q_[3] * q_[3]);
      for (double& v : q_) v /= n;
      // An absurd rate (1e300 rad/s is finite) must not latch a NaN attitude: start again.
      if (!(std::isfinite(q_[0]) && std::isfinite(q_[1]) && std::isfinite(q_[2]) && std::isfinite(q_[3]))) reset();
    }
  }
  const auto rpy = io.out(kRpy);
  if (!started_) {
    rpy[0] = rpy[1] = rpy[2] = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  OrientationToRpy::to_rpy(OrientationToRpy::From::quaternion_wxyz, q_, rpy.first<3>());
}

}  // namespace ftsense::generic
