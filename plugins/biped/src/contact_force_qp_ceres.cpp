#include "ftsense/biped/contact_force_qp_ceres.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace ftsense::biped {
namespace {

// Residuals r = [C N - d ; sqrt(w) .* N] (2 + n), Jacobian constant [C ; diag(sqrt(w))].
class MomentResidual final : public ceres::CostFunction {
public:
  explicit MomentResidual(const ContactGeometry& geometry)
      : n_(geometry.size()), points_(geometry.points), sqrt_weights_(geometry.weights.cwiseSqrt()) {
    set_num_residuals(2 + n_);
    mutable_parameter_block_sizes()->push_back(n_);
  }

  void set_moment(const Eigen::Vector2d& d) noexcept { moment_ = d; }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::VectorXd> forces(parameters[0], n_);
    Eigen::Map<Eigen::VectorXd> r(residuals, 2 + n_);
    r.head<2>() = points_ * forces - moment_;
    r.tail(n_) = sqrt_weights_.cwiseProduct(forces);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> jacobian(jacobians[0],
                                                                                                  2 + n_, n_);
      jacobian.setZero();
      jacobian.topRows<2>() = points_;
      jacobian.bottomRows(n_).diagonal() = sqrt_weights_;
    }
    return true;
  }

private:
  int n_;
  ContactPoints points_;
  ContactVector sqrt_weights_;
  Eigen::Vector2d moment_ = Eigen::Vector2d::Zero();
};

// { N : N_l = 0 off F, sum_F N_l = const } with tangent basis e_{f_j} - e_{f_k}, j < k = |F| - 1.
// The free list may change between solves; the tangent size is fixed per object.
class AffineSubspaceManifold final : public ceres::Manifold {
public:
  AffineSubspaceManifold(int ambient, int tangent) : ambient_(ambient), tangent_(tangent) {}

  void set_free(const std::array<int, kMaxContactPoints>& free) noexcept { free_ = free; }

  int AmbientSize() const override { return ambient_; }
  int TangentSize() const override { return tangent_; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    std::copy(x, x + ambient_, x_plus_delta);
    for (int j = 0; j < tangent_; ++j) {
      x_plus_delta[free_[j]] += delta[j];
      x_plus_delta[free_[tangent_]] -= delta[j];
    }
    return true;
  }

  bool PlusJacobian(const double* /*x*/, double* jacobian) const override {
    std::fill(jacobian, jacobian + ambient_ * tangent_, 0.0); // row-major ambient x tangent
    for (int j = 0; j < tangent_; ++j) {
      jacobian[free_[j] * tangent_ + j] = 1.0;
      jacobian[free_[tangent_] * tangent_ + j] = -1.0;
    }
    return true;
  }

  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    for (int j = 0; j < tangent_; ++j) y_minus_x[j] = y[free_[j]] - x[free_[j]];
    return true;
  }

  bool MinusJacobian(const double* /*x*/, double* jacobian) const override {
    std::fill(jacobian, jacobian + tangent_ * ambient_, 0.0); // row-major tangent x ambient
    for (int j = 0; j < tangent_; ++j) jacobian[j * ambient_ + free_[j]] = 1.0;
    return true;
  }

private:
  int ambient_;
  int tangent_;
  std::array<int, kMaxContactPoints> free_{};
};

ceres::Problem::Options problem_options() {
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return options;
}

} // namespace

struct CeresContactQp::Impl final : detail::EqualityQpSubproblem {
  Impl(ContactGeometry geometry_in, Options options_in)
      : geometry(std::move(geometry_in)), options(options_in), n(geometry.size()), cost(geometry),
        problem(problem_options()) {
    ContactQpProblem unit{geometry, 0.0, Eigen::Vector2d::Zero()};
    hessian = unit.hessian();
    for (int k = 1; k < n; ++k) manifolds[k] = std::make_unique<AffineSubspaceManifold>(n, k);
    problem.AddParameterBlock(parameters.data(), n);
    problem.AddResidualBlock(&cost, nullptr, parameters.data());

    solver_options.minimizer_type = ceres::TRUST_REGION;
    solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    solver_options.linear_solver_type = ceres::DENSE_QR;
    solver_options.initial_trust_region_radius = 1e16; // LM damping 1e-16: a Gauss-Newton step
    solver_options.max_trust_region_radius = 1e16;
    solver_options.max_num_iterations = options.max_ceres_iterations;
    solver_options.function_tolerance = 1e-15;
    solver_options.parameter_tolerance = 1e-15;
    solver_options.num_threads = 1;
    solver_options.logging_type = ceres::SILENT;
    solver_options.minimizer_progress_to_stdout = false;
  }

  bool solve(std::uint32_t fixed, const ContactVector& start, ContactVector& x, double& lambda,
             ContactVector& mu) noexcept override {
    std::array<int, kMaxContactPoints> free{};
    int free_count = 0;
    for (int l = 0; l < n; ++l) {
      if ((fixed & detail::contact_bit(l)) == 0U) free[free_count++] = l;
    }
    if (free_count == 1) {
      x.setZero(n);
      x(free[0]) = fz;
    } else {
      AffineSubspaceManifold& manifold = *manifolds[free_count - 1];
      manifold.set_free(free);
      problem.SetManifold(parameters.data(), &manifold);
      std::copy(start.data(), start.data() + n, parameters.begin());
      ceres::Solve(solver_options, &problem, &summary);
      if (summary.termination_type != ceres::CONVERGENCE) return false;
      for (int l = 0; l < n; ++l) x(l) = (fixed & detail::contact_bit(l)) != 0U ? 0.0 : parameters[static_cast<std::size_t>(l)];
    }
    if (!x.allFinite()) return false;
    const ContactVector gradient = hessian * x + linear_term;
    lambda = 0.0;
    for (int j = 0; j < free_count; ++j) lambda += gradient(free[j]);
    lambda /= free_count;
    for (int l = 0; l < n; ++l) mu(l) = (fixed & detail::contact_bit(l)) != 0U ? gradient(l) - lambda : 0.0;
    return true;
  }

  ContactGeometry geometry;
  Options options;
  int n;
  ContactMatrix hessian;
  ContactVector linear_term;
  double fz = 0.0;
  MomentResidual cost;
  std::array<std::unique_ptr<AffineSubspaceManifold>, kMaxContactPoints> manifolds;
  std::array<double, kMaxContactPoints> parameters{};
  ceres::Problem problem;
  ceres::Solver::Options solver_options;
  ceres::Solver::Summary summary;
  std::uint32_t warm_active_set = 0;
};

void CeresContactQp::Options::validate() const {
  if (max_iterations < 1) {
    throw std::invalid_argument("CeresContactQp::Options.max_iterations = " + std::to_string(max_iterations) +
                                ". Violated constraint: >= 1");
  }
  if (max_ceres_iterations < 2) {
    throw std::invalid_argument("CeresContactQp::Options.max_ceres_iterations = " +
                                std::to_string(max_ceres_iterations) + ". Violated constraint: >= 2");
  }
}

CeresContactQp::CeresContactQp(ContactGeometry geometry) : CeresContactQp(std::move(geometry), Options{}) {}

CeresContactQp::CeresContactQp(ContactGeometry geometry, Options options) {
  geometry.validate();
  options.validate();
  impl_ = std::make_unique<Impl>(std::move(geometry), options);
}

CeresContactQp::~CeresContactQp() = default;
CeresContactQp::CeresContactQp(CeresContactQp&&) noexcept = default;
CeresContactQp& CeresContactQp::operator=(CeresContactQp&&) noexcept = default;

const ContactGeometry& CeresContactQp::geometry() const noexcept { return impl_->geometry; }
const CeresContactQp::Options& CeresContactQp::options() const noexcept { return impl_->options; }
void CeresContactQp::reset() noexcept { impl_->warm_active_set = 0; }

void CeresContactQp::solve(double fz, const Eigen::Vector2d& cop, ContactQpSolution& out) noexcept {
  Impl& impl = *impl_;
  const int n = impl.n;
  if (!detail::load_is_valid(fz, cop)) {
    detail::set_zero_solution(n, ContactQpStatus::invalid_input, out);
    return;
  }
  if (fz == 0.0) {
    detail::set_zero_solution(n, ContactQpStatus::zero_load, out);
    return;
  }
  try {
    // The QP is positively homogeneous in F_z (N(F_z) = F_z N(1), multipliers likewise), so Ceres
    // always sees F_z = 1: its absolute tolerances then do not depend on the load.
    const Eigen::Vector2d d = cop;
    impl.fz = 1.0;
    impl.cost.set_moment(d);
    impl.linear_term = -2.0 * impl.geometry.points.transpose() * d;
    const double gradient_scale =
        impl.hessian.cwiseAbs().rowwise().sum().maxCoeff() + impl.linear_term.lpNorm<Eigen::Infinity>();
    impl.solver_options.gradient_tolerance = 1e-12 * gradient_scale;
    out.active_set = impl.options.warm_start ? impl.warm_active_set : 0U;
    detail::run_primal_active_set(n, 1.0, gradient_scale, impl.options.max_iterations, impl, out);
    out.forces *= fz;
    out.bound_multipliers *= fz;
    out.sum_multiplier *= fz;
  } catch (...) {
    detail::set_zero_solution(n, ContactQpStatus::solver_failure, out);
    return;
  }
  if (!out.forces.allFinite() || !out.bound_multipliers.allFinite() || !std::isfinite(out.sum_multiplier)) {
    detail::set_zero_solution(n, ContactQpStatus::invalid_input, out);
    return;
  }
  if (out.status == ContactQpStatus::optimal) impl.warm_active_set = out.active_set;
}

} // namespace ftsense::biped
