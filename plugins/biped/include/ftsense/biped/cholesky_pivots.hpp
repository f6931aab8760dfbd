#pragma once
// Whether a symmetric 3x3 matrix is positive definite, as the CoM filter checks its covariance
// every tick.
//
// The Cholesky factorisation A = L L^T of the lower triangle, pivot by pivot:
//   x_0 = a_00,                     l_00 = sqrt(x_0),  l_i0 = a_i0 / l_00
//   x_1 = a_11 - l_10^2,            l_11 = sqrt(x_1),  l_21 = (a_21 - l_20 l_10) / l_11
//   x_2 = a_22 - (l_20^2 + l_21^2)
// A is positive definite iff every pivot x_k > 0. These are Eigen::LLT's own operations in its
// order (Eigen/src/Cholesky/LLT.h, llt_inplace::unblocked), so the answer is the same as
// `Eigen::LLT<Eigen::Matrix3d>(a).info() == Eigen::Success` for every input, NaN included (a NaN
// pivot is not "<= 0": it passes, as in Eigen), without the factor's stores and loop: in a 1 kHz
// tick the general routine cost a third of the filter's update. (On a build that fuses
// multiply-adds, e.g. -march=native, either side may be contracted differently: the identity is
// for the default x86-64 target.)

#include <cmath>

#include <Eigen/Core>

namespace ftsense::biped {

[[nodiscard]] inline bool cholesky_pivots_positive(const Eigen::Matrix3d& a) noexcept {
  const double x0 = a(0, 0);
  if (x0 <= 0.0) return false;
  const double l00 = std::sqrt(x0);
  const double l10 = a(1, 0) / l00;
  const double l20 = a(2, 0) / l00;
  const double x1 = a(1, 1) - l10 * l10;
  if (x1 <= 0.0) return false;
  const double l11 = std::sqrt(x1);
  const double l21 = (a(2, 1) - l20 * l10) / l11;
  const double x2 = a(2, 2) - (l20 * l20 + l21 * l21);
  return !(x2 <= 0.0);
}

}  // namespace ftsense::biped
