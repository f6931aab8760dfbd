#pragma once
// Attitude (roll, pitch, yaw [rad]) from an IMU's gyro and accelerometer, for logs that carry no
// orientation: a complementary filter on the unit quaternion (Mahony's, proportional part only).
//
// q is the Hamilton quaternion rotating body (IMU) to world, R(q) its matrix, z the world's up.
// Each tick, with gyro omega [rad/s] and specific force f [m/s^2], both in the body frame:
//
//   v = R(q)^T z                         the estimated up direction in the body frame
//   e = (f / |f|) x v                    the tilt error seen by the accelerometer
//   w = omega + e / tau                  when | |f| - g | <= accept_acc_fraction g, else omega
//   q <- q (x) [cos(|w| T / 2), sin(|w| T / 2) w / |w|]      (exact for a rate held over T)
//
// so a tilt error decays as exp(-t / tau) (tau = `tilt_time_constant_s`) while the accelerometer
// reads gravity alone, and the gyro carries the attitude through motion (a foot strike, a hop)
// where |f| departs from g. Yaw is not observable from gravity: it is the integrated gyro,
// starting at `initial_yaw_rad`, and drifts with the gyro's bias (no bias is estimated).
//
// Start: the first tick whose f reads gravity alone (| |f| - g | <= accept_acc_fraction g) takes
// roll and pitch from it,
// roll = atan2(f_y, f_z), pitch = atan2(-f_x, hypot(f_y, f_z)) (exact for a robot at rest); until
// then rpy is NaN (not ready). A non-finite gyro, or one turning more than half a turn in a tick
// (|w| T > pi: it would alias), holds the attitude for that tick; a non-finite f skips the
// correction. Output rpy in the convention of the biped plugins,
// R = Rz(yaw) Ry(pitch) Rx(roll) (orientation_to_rpy.hpp). Allocation-free.

#include <array>
#include <string_view>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class AttitudeFromImu {
 public:
  static constexpr std::string_view name = "attitude_from_imu";
  static constexpr std::string_view summary =
      "roll, pitch, yaw from gyro and accelerometer: a complementary filter (tilt from gravity, yaw from the gyro)";

  struct Params {
    double tilt_time_constant_s = 1.0;
    double accept_acc_fraction = 0.1;
    double gravity_m_s2 = 9.806;
    double initial_yaw_rad = 0.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kGyro, kImuAcc };
  enum Output : std::size_t { kRpy };

  AttitudeFromImu(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  Params params_;
  double period_s_;
  std::array<double, 4> q_{1.0, 0.0, 0.0, 0.0};  // w, x, y, z
  bool started_ = false;
};

}  // namespace ftsense::generic
