#pragma once
// ZMP preview control on the cart-table model (Kajita et al., ICRA 2003), one horizontal axis.
//
// State x = [c, c', c''] (CoM position, velocity, acceleration), input u = c''' (jerk), period T:
//   x_{k+1} = A x_k + B u_k,   A = [1 T T^2/2; 0 1 T; 0 0 1],   B = [T^3/6; T^2/2; T]
//   p_k     = C x_k,           C = [1 0 -z_c/g]            (cart-table ZMP)
// Cost J = sum_k Qe (p_k - p_ref,k)^2 + R u_k^2. With P the stabilising solution of the discrete
// algebraic Riccati equation P = A'PA + C'QeC - A'PB (R + B'PB)^-1 B'PA (solved here by fixed-point
// iteration), the optimal control with an N-step preview is
//   u_k = -K x_k + sum_{j=1..N} f_j p_ref,{k+j}
//   K   = (R + B'PB)^-1 B'PA,   f_j = (R + B'PB)^-1 B' ((A - BK)')^{j-1} C' Qe,
// with the reference held at p_ref,{k+N} beyond the horizon (f_N absorbs the tail of the series),
// so a constant reference is tracked without steady-state error. Defaults Qe = 1, R = 1e-10 at
// T = 1 ms (R = 1e-6, right for T = 5 ms, leaves centimetre errors at 1 ms).
#include <span>
#include <vector>

#include <Eigen/Core>

namespace ftsense::sim {

class ZmpPreviewController {
 public:
  /// dt: period (s); com_height: z_c (m); preview_s: horizon N*dt (s); qe, r: cost weights.
  ZmpPreviewController(double dt, double com_height, double gravity, double preview_s,
                       double qe = 1.0, double r = 1e-10);

  [[nodiscard]] const Eigen::Matrix3d& riccati_solution() const { return P_; }
  [[nodiscard]] const Eigen::RowVector3d& state_gain() const { return K_; }
  [[nodiscard]] const std::vector<double>& preview_gains() const { return f_; }
  [[nodiscard]] const Eigen::Matrix3d& A() const { return A_; }
  [[nodiscard]] const Eigen::Vector3d& B() const { return B_; }
  [[nodiscard]] const Eigen::RowVector3d& C() const { return C_; }
  /// Residual of the Riccati equation at the returned P (max abs entry), for checks.
  [[nodiscard]] double riccati_residual() const;

  /// Closed-loop CoM states for a whole ZMP reference (the reference is held at its last value
  /// beyond its end). Element k is the state at tick k, starting from x0.
  [[nodiscard]] std::vector<Eigen::Vector3d> track(std::span<const double> zmp_ref,
                                                   const Eigen::Vector3d& x0) const;

 private:
  Eigen::Matrix3d A_;
  Eigen::Vector3d B_;
  Eigen::RowVector3d C_;
  double qe_, r_;
  Eigen::Matrix3d P_;
  Eigen::RowVector3d K_;
  std::vector<double> f_;
};

}  // namespace ftsense::sim
