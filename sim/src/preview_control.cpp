#include "ftsense/sim/preview_control.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/LU>

namespace ftsense::sim {

ZmpPreviewController::ZmpPreviewController(double dt, double com_height, double gravity,
                                           double preview_s, double qe, double r)
    : qe_(qe), r_(r) {
  if (!(dt > 0.0) || !(com_height > 0.0) || !(gravity > 0.0) || !(preview_s > 0.0) ||
      !(qe > 0.0) || !(r > 0.0))
    throw std::invalid_argument("ZmpPreviewController: all parameters must be positive");
  A_ << 1.0, dt, 0.5 * dt * dt, 0.0, 1.0, dt, 0.0, 0.0, 1.0;
  B_ << dt * dt * dt / 6.0, 0.5 * dt * dt, dt;
  C_ << 1.0, 0.0, -com_height / gravity;
  const Eigen::Matrix3d Q = qe_ * C_.transpose() * C_;
  Eigen::Matrix3d P = Q;
  bool converged = false;
  for (int it = 0; it < 2'000'000 && !converged; ++it) {
    const double s = r_ + B_.dot(P * B_);
    const Eigen::RowVector3d BtPA = B_.transpose() * P * A_;
    Eigen::Matrix3d Pn = A_.transpose() * P * A_ + Q - BtPA.transpose() * BtPA / s;
    Pn = 0.5 * (Pn + Pn.transpose());
    const double change = (Pn - P).cwiseAbs().maxCoeff();
    converged = change <= 1e-13 * std::max(1.0, Pn.cwiseAbs().maxCoeff());
    P = Pn;
  }
  if (!converged) throw std::runtime_error("ZmpPreviewController: Riccati iteration did not converge");
  P_ = P;
  const double s = r_ + B_.dot(P_ * B_);
  K_ = (B_.transpose() * P_ * A_) / s;
  const Eigen::Matrix3d Ac = A_ - B_ * K_;
  const auto n = static_cast<std::size_t>(std::lround(preview_s / dt));
  f_.resize(n);
  Eigen::Vector3d v = C_.transpose() * qe_;  // ((A - BK)')^{j-1} C' Qe
  for (std::size_t j = 0; j < n; ++j) {
    f_[j] = B_.dot(v) / s;
    v = Ac.transpose() * v;
  }
  // Reference assumed constant beyond the horizon: fold the geometric tail
  // sum_{j>N} f_j = (R + B'PB)^-1 B' (I - Ac')^-1 (Ac')^N C' Qe into the last gain, so a constant
  // reference is tracked without steady-state error.
  if (n > 0) {
    const Eigen::Vector3d tail = (Eigen::Matrix3d::Identity() - Ac.transpose()).partialPivLu().solve(v);
    f_.back() += B_.dot(tail) / s;
  }
}

double ZmpPreviewController::riccati_residual() const {
  const Eigen::Matrix3d Q = qe_ * C_.transpose() * C_;
  const double s = r_ + B_.dot(P_ * B_);
  const Eigen::RowVector3d BtPA = B_.transpose() * P_ * A_;
  const Eigen::Matrix3d res = A_.transpose() * P_ * A_ + Q - BtPA.transpose() * BtPA / s - P_;
  return res.cwiseAbs().maxCoeff();
}

std::vector<Eigen::Vector3d> ZmpPreviewController::track(std::span<const double> zmp_ref,
                                                         const Eigen::Vector3d& x0) const {
  std::vector<Eigen::Vector3d> out;
  if (zmp_ref.empty()) return out;
  const std::size_t n = zmp_ref.size();
  out.reserve(n);
  Eigen::Vector3d x = x0;
  for (std::size_t k = 0; k < n; ++k) {
    out.push_back(x);
    double u = -K_.dot(x);
    for (std::size_t j = 0; j < f_.size(); ++j) u += f_[j] * zmp_ref[std::min(k + j + 1, n - 1)];
    x = A_ * x + B_ * u;
  }
  return out;
}

}  // namespace ftsense::sim
