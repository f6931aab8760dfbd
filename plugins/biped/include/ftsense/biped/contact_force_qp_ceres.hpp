#pragma once
// Ceres-based solver for the contact force QP of contact_force_qp.hpp (same model, units and
// KKT conventions; read that header first).
//
// Why not hand the whole QP to Ceres: Ceres has only box bounds on parameters and no general
// equality constraints. Measured: its bounds plus an equality penalty gave forces off by
// 100-490 N in 300-650 us, and an affine manifold alone ignores N >= 0. So the inequality logic
// stays outside Ceres:
//
//   outer loop  the same primal active-set method as ActiveSetContactQp
//               (detail::run_primal_active_set: ratio test, release most negative mu, cycle guard)
//   subproblem  for the current free set F (points in A held at zero) Ceres solves the linear
//               least-squares problem
//                   minimise || C N - d ||^2 + || sqrt(W) N ||^2       (2 + n residuals)
//               on the affine subspace S_F = { N : N_A = 0, sum_{l in F} N_l = F_z }.
//               S_F is a ceres::Manifold (AffineSubspaceManifold, ambient n, tangent |F| - 1,
//               basis e_f - e_last over F), so every Ceres iterate satisfies the equality and
//               the zero bounds of the working set exactly; the start point is the outer
//               iterate, which lies in S_F. Ceres runs Levenberg-Marquardt with DENSE_QR and an
//               effectively infinite initial trust region, so the first step is the exact
//               Gauss-Newton (= least-squares) step and the second iteration confirms
//               convergence by the gradient test. |F| = 1 needs no solve (N_f = F_z).
//               lambda and mu are then read from stationarity: lambda = mean_{l in F}(H N + g)_l,
//               mu_l = (H N + g)_l - lambda on A.
//   scaling     the QP is positively homogeneous in F_z (N, lambda, mu all scale with F_z), so
//               the loop runs with F_z = 1 and the result is multiplied by F_z; Ceres's absolute
//               gradient tolerance is then load-independent (needed for F_z down to 1e-300).
//
// Costs: the ceres::Problem (one parameter block of size n, one residual block with an analytic
// CostFunction, one manifold object per tangent size 1..7) is built once in the constructor; no
// residual or parameter block is added or removed per solve. Each subproblem still pays for
// ceres::Solve's preprocessing (reduced program, evaluator, linear solver, summary), which
// allocates on the heap and dominates the run time: measured ~4 us per loaded solve for n = 4
// and ~5.5 us for n = 8 (median, gait trajectory, dev machine; p99 ~10 us), i.e. ~50x the
// active-set solver, with first-call and page-fault outliers of 20-120 us. The outer loop is warm
// started from the previous active set, so on 1 kHz data one ceres::Solve per sample is typical
// (~1.03 per sample on the benchmark trajectory).
// ContactQpSolution::iterations counts outer iterations (= subproblem solves).
//
// solve() is noexcept: exceptions (e.g. std::bad_alloc) become status solver_failure with zero
// forces. Use ActiveSetContactQp where real-time guarantees matter; this class exists for
// cross-checking and for users who want Ceres in the loop.
//
// Threading: one object per thread (it owns a ceres::Problem and warm-start state).

#include "ftsense/biped/contact_force_qp.hpp"

#include <memory>

namespace ftsense::biped {

class CeresContactQp final : public ContactForceQpSolver {
public:
  struct Options {
    bool warm_start = true;       ///< start the outer loop from the previous optimal active set
    int max_iterations = 64;      ///< outer active-set iterations (cycle guard), >= 1
    int max_ceres_iterations = 10; ///< per subproblem, >= 2 (one step + convergence check)
    /// Throws std::invalid_argument naming the field on violation.
    void validate() const;
  };

  /// Throws std::invalid_argument if geometry or options are invalid.
  explicit CeresContactQp(ContactGeometry geometry);
  CeresContactQp(ContactGeometry geometry, Options options);
  ~CeresContactQp() override;
  CeresContactQp(const CeresContactQp&) = delete;
  CeresContactQp& operator=(const CeresContactQp&) = delete;
  CeresContactQp(CeresContactQp&&) noexcept;
  CeresContactQp& operator=(CeresContactQp&&) noexcept;

  void solve(double fz, const Eigen::Vector2d& cop, ContactQpSolution& out) noexcept override;
  void reset() noexcept override;
  const ContactGeometry& geometry() const noexcept override;
  const Options& options() const noexcept;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace ftsense::biped
