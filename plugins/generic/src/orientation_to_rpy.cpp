#include "ftsense/generic/orientation_to_rpy.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ftsense::generic {
namespace {

using Matrix = std::array<std::array<double, 3>, 3>;  // r[row][column]

bool all_finite(std::span<const double> v) noexcept {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// R of the unit quaternion q / |q| (header); false when q is no unit quaternion.
bool rotation_of_quaternion(double x, double y, double z, double w, Matrix& r) noexcept {
  const double norm = std::sqrt(x * x + y * y + z * z + w * w);
  if (!(norm >= OrientationToRpy::kMinQuaternionNorm && norm <= OrientationToRpy::kMaxQuaternionNorm)) return false;
  x /= norm, y /= norm, z /= norm, w /= norm;
  r = {{{1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)},
        {2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)},
        {2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)}}};
  return true;
}

bool is_rotation(const Matrix& r) noexcept {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double dot = r[0][i] * r[0][j] + r[1][i] * r[1][j] + r[2][i] * r[2][j];  // (R^T R)_ij
      if (!(std::abs(dot - (i == j ? 1.0 : 0.0)) <= OrientationToRpy::kOrthonormalTolerance)) return false;
    }
  }
  const double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                     r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                     r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
  return det > 0.0;
}

// Below this cos(pitch) yaw is not observable (frames.hpp's rpy_from_rotation uses the same).
constexpr double kGimbalLockCosPitch = 1e-12;

void rpy_of_rotation(const Matrix& r, std::span<double, 3> rpy) noexcept {
  const double cos_pitch = std::hypot(r[0][0], r[1][0]);
  const double yaw = cos_pitch > kGimbalLockCosPitch ? std::atan2(r[1][0], r[0][0]) : 0.0;
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const double m11 = cy * r[1][1] - sy * r[0][1];
  const double minus_m12 = sy * r[0][2] - cy * r[1][2];
  // 0.0 - r20 rather than -r20, and minus_m12 as a difference: the identity gives +0, not -0.
  rpy[0] = std::atan2(minus_m12, m11);
  rpy[1] = std::atan2(0.0 - r[2][0], cos_pitch);
  rpy[2] = yaw;
}

}  // namespace

void OrientationToRpy::Params::describe(ParamSchema<Params>& schema) {
  schema.add_choice("from", &Params::from,
                    "layout of input orientation: a Hamilton quaternion (x, y, z, w) or (w, x, y, z), or a "
                    "rotation matrix R (body to world) listed by rows or by columns",
                    {{"quaternion_xyzw", From::quaternion_xyzw},
                     {"quaternion_wxyz", From::quaternion_wxyz},
                     {"rotation_matrix_row_major", From::rotation_matrix_row_major},
                     {"rotation_matrix_column_major", From::rotation_matrix_column_major}});
}

OrientationToRpy::OrientationToRpy(const Params& params, const StageContext& /*context*/) : from_(params.from) {
  const bool quaternion = from_ == From::quaternion_xyzw || from_ == From::quaternion_wxyz;
  ports_.add_input(PortSpec{"orientation", quaternion ? 4u : 9u, std::string(kDimensionless),
                            quaternion ? "unit quaternion, in the order of parameter from"
                                       : "rotation matrix R (body to world), in the layout of parameter from"}
                       .in_frame("body in world")
                       .sized_by("4 (quaternion) or 9 (rotation matrix), by params.from"));
  ports_.add_output(PortSpec{"rpy", 3, "rad",
                             "roll, pitch, yaw with R = Rz(yaw) Ry(pitch) Rx(roll); NaN when the input is no orientation"}
                        .in_frame("body in world"));
}

void OrientationToRpy::to_rpy(From from, std::span<const double> o, std::span<double, 3> rpy) noexcept {
  Matrix r{};
  bool ok = all_finite(o);
  if (ok) {
    switch (from) {
      case From::quaternion_xyzw: ok = rotation_of_quaternion(o[0], o[1], o[2], o[3], r); break;
      case From::quaternion_wxyz: ok = rotation_of_quaternion(o[1], o[2], o[3], o[0], r); break;
      case From::rotation_matrix_row_major:
      case From::rotation_matrix_column_major: {
        const bool by_rows = from == From::rotation_matrix_row_major;
        for (std::size_t i = 0; i < 3; ++i) {
          for (std::size_t j = 0; j < 3; ++j) r[i][j] = by_rows ? o[3 * i + j] : o[3 * j + i];
        }
        ok = is_rotation(r);
        break;
      }
    }
  }
  if (ok) {
    rpy_of_rotation(r, rpy);
  } else {
    std::fill(rpy.begin(), rpy.end(), std::numeric_limits<double>::quiet_NaN());
  }
}

void OrientationToRpy::step(const StepIO& io) noexcept {
  to_rpy(from_, io.in(kOrientation), io.out(kRpy).first<3>());
}

}  // namespace ftsense::generic
