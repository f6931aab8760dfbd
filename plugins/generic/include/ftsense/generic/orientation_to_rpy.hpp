#pragma once
// An orientation as logged (a quaternion or a rotation matrix) to roll, pitch, yaw [rad], the
// convention of the biped plugins (plugins/biped/include/ftsense/biped/frames.hpp):
//
//   R = Rz(yaw) Ry(pitch) Rx(roll),   mapping body coordinates to world coordinates.
//
// Inputs (`from`), all dimensionless:
//   quaternion_xyzw, quaternion_wxyz   a Hamilton quaternion q = w + x i + y j + z k (w the scalar
//       part, as ROS, Eigen and most IMUs log it) rotating body to world. It is normalised first,
//       q / |q|, and then
//         R = [1 - 2(y^2 + z^2)   2(x y - z w)       2(x z + y w)
//              2(x y + z w)       1 - 2(x^2 + z^2)   2(y z - x w)
//              2(x z - y w)       2(y z + x w)       1 - 2(x^2 + y^2)],
//       so q and -q give the same R. A JPL quaternion (the conjugate) must be conjugated first.
//   rotation_matrix_row_major          R as r00 r01 r02 r10 ... r22
//   rotation_matrix_column_major       R as r00 r10 r20 r01 ... r22
//
// Output rpy, the inverse of rotation_from_rpy:
//   pitch = atan2(-r20, hypot(r00, r10))                 in [-pi/2, pi/2]
//   yaw   = atan2(r10, r00), or 0 when hypot(r00, r10) <= 1e-12 (gimbal lock, pitch = +-pi/2,
//           where only roll - yaw or roll + yaw is defined: the choice of frames.hpp)
//   roll  = atan2(-m12, m11) with M = Rz(yaw)^T R = Ry(pitch) Rx(roll), whose row 1 is
//           (0, cos roll, -sin roll): m11 = cos(yaw) r11 - sin(yaw) r01, m12 = cos(yaw) r12 -
//           sin(yaw) r02. Unlike atan2(r21, r22) (= cos pitch (sin roll, cos roll)) these entries
//           have magnitude 1 at any pitch, so roll stays consistent with the yaw chosen and the
//           rotation round-trips near gimbal lock too.
//
// NaN (no value) on all three outputs when the input is not finite, a quaternion's norm is
// outside [0.5, 2], or a matrix is not a rotation: max |R^T R - I| > 1e-3 or det R < 0.
// Stateless; allocation-free.

#include <span>
#include <string_view>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class OrientationToRpy {
 public:
  static constexpr std::string_view name = "orientation_to_rpy";
  static constexpr std::string_view summary =
      "quaternion (xyzw or wxyz) or rotation matrix to roll, pitch, yaw with R = Rz(yaw) Ry(pitch) Rx(roll)";

  enum class From { quaternion_xyzw, quaternion_wxyz, rotation_matrix_row_major, rotation_matrix_column_major };

  struct Params {
    From from = From::quaternion_xyzw;
    static void describe(ParamSchema<Params>& schema);
  };

  // A logged unit quaternion has norm 1 up to rounding and quantisation; a norm beyond these is a
  // wrong column (a position, an angular rate), not a quaternion to normalise.
  static constexpr double kMinQuaternionNorm = 0.5;
  static constexpr double kMaxQuaternionNorm = 2.0;
  // A logged rotation matrix is orthonormal to its print precision; beyond this it is no rotation.
  static constexpr double kOrthonormalTolerance = 1e-3;

  enum Input : std::size_t { kOrientation };
  enum Output : std::size_t { kRpy };

  OrientationToRpy(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

  // roll, pitch, yaw of `orientation` in the layout `from` (NaN when it is no orientation).
  static void to_rpy(From from, std::span<const double> orientation, std::span<double, 3> rpy) noexcept;

 private:
  Ports ports_;
  From from_;
};

}  // namespace ftsense::generic
