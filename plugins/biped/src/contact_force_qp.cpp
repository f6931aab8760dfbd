#include "ftsense/biped/contact_force_qp.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace ftsense::biped {
namespace {

constexpr std::array<std::pair<ContactQpStatus, std::string_view>, 5> kStatusNames{{
    {ContactQpStatus::optimal, "optimal"},
    {ContactQpStatus::zero_load, "zero_load"},
    {ContactQpStatus::invalid_input, "invalid_input"},
    {ContactQpStatus::iteration_limit, "iteration_limit"},
    {ContactQpStatus::solver_failure, "solver_failure"},
}};

std::string format_double(double value) {
  std::ostringstream os;
  os.precision(17);
  os << value;
  return os.str();
}

double nan_max(double a, double b) noexcept {
  if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<double>::quiet_NaN();
  return std::max(a, b);
}

// ||H||_inf for H = 2 (C^T C + W), without forming H.
double hessian_inf_norm(const ContactGeometry& geometry) noexcept {
  double norm = 0.0;
  const int n = geometry.size();
  for (int l = 0; l < n; ++l) {
    double row = 2.0 * geometry.weights(l);
    for (int k = 0; k < n; ++k) row += 2.0 * std::abs(geometry.points.col(l).dot(geometry.points.col(k)));
    norm = std::max(norm, row);
  }
  return norm;
}

ContactQpKkt evaluate_kkt(const ContactQpProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& forces,
                          const ContactVector& gradient, double lambda, const ContactVector& mu, double tolerance) {
  const ContactMatrix hessian = problem.hessian();
  const ContactVector g = problem.linear_term();
  ContactQpKkt kkt;
  kkt.sum_multiplier = lambda;
  kkt.bound_multipliers = mu;
  kkt.tolerance = tolerance;
  kkt.force_scale = std::max(1.0, std::abs(problem.fz));
  const double h_norm = hessian.cwiseAbs().rowwise().sum().maxCoeff();
  kkt.gradient_scale = std::max({1.0, g.lpNorm<Eigen::Infinity>(), h_norm * forces.lpNorm<Eigen::Infinity>(),
                                 std::abs(lambda)});
  double stationarity = 0.0;
  double primal = std::abs(forces.sum() - problem.fz);
  double dual = 0.0;
  double complementarity = 0.0;
  for (Eigen::Index l = 0; l < forces.size(); ++l) {
    stationarity = nan_max(stationarity, std::abs(gradient(l) - lambda - mu(l)));
    primal = nan_max(primal, std::max(-forces(l), 0.0));
    dual = nan_max(dual, std::max(-mu(l), 0.0));
    complementarity = nan_max(complementarity, std::abs(mu(l) * forces(l)));
  }
  kkt.stationarity = stationarity / kkt.gradient_scale;
  kkt.primal_feasibility = primal / kkt.force_scale;
  kkt.dual_feasibility = dual / kkt.gradient_scale;
  kkt.complementarity = complementarity / (kkt.gradient_scale * kkt.force_scale);
  return kkt;
}

void check_kkt_inputs(const ContactQpProblem& problem, Eigen::Index forces_size) {
  problem.geometry.validate();
  if (forces_size != problem.geometry.size()) {
    throw std::invalid_argument("check_kkt: forces.size() = " + std::to_string(forces_size) +
                                ". Violated constraint: == number of contact points (" +
                                std::to_string(problem.geometry.size()) + ")");
  }
}

} // namespace

// ---------------------------------------------------------------------------------------------
// Geometry, problem, status

void ContactGeometry::validate() const {
  const int n = size();
  if (n < 1 || n > kMaxContactPoints) {
    throw std::invalid_argument("ContactGeometry.points: number of points = " + std::to_string(n) +
                                ". Violated constraint: 1 <= n <= " + std::to_string(kMaxContactPoints));
  }
  if (weights.size() != n) {
    throw std::invalid_argument("ContactGeometry.weights: size = " + std::to_string(weights.size()) +
                                ". Violated constraint: == number of points (" + std::to_string(n) + ")");
  }
  for (int l = 0; l < n; ++l) {
    for (int axis = 0; axis < 2; ++axis) {
      if (!std::isfinite(points(axis, l))) {
        throw std::invalid_argument("ContactGeometry.points(" + std::to_string(axis) + ", " + std::to_string(l) +
                                    ") = " + format_double(points(axis, l)) + ". Violated constraint: finite");
      }
    }
    if (!(weights(l) > 0.0) || !std::isfinite(weights(l))) {
      throw std::invalid_argument("ContactGeometry.weights(" + std::to_string(l) + ") = " + format_double(weights(l)) +
                                  ". Violated constraint: 0 < w < inf");
    }
  }
}

ContactGeometry ContactGeometry::rectangle(double length, double width, double weight) {
  ContactGeometry geometry;
  const double hx = 0.5 * length;
  const double hy = 0.5 * width;
  geometry.points.resize(2, 4);
  geometry.points << hx, -hx, -hx, hx, //
      hy, hy, -hy, -hy;
  geometry.weights = ContactVector::Constant(4, weight);
  return geometry;
}

ContactMatrix ContactQpProblem::hessian() const {
  ContactMatrix h = 2.0 * geometry.points.transpose() * geometry.points;
  h.diagonal() += 2.0 * geometry.weights;
  return h;
}

ContactVector ContactQpProblem::linear_term() const {
  const Eigen::Vector2d d = fz * cop;
  return -2.0 * geometry.points.transpose() * d;
}

double ContactQpProblem::objective(const Eigen::Ref<const Eigen::VectorXd>& forces) const {
  const Eigen::Vector2d moment_error = geometry.points * forces - fz * cop;
  return moment_error.squaredNorm() + forces.dot(geometry.weights.cwiseProduct(forces));
}

std::string_view to_string(ContactQpStatus status) noexcept {
  for (const auto& [value, name] : kStatusNames) {
    if (value == status) return name;
  }
  return "unknown";
}

std::optional<ContactQpStatus> contact_qp_status_from_string(std::string_view name) noexcept {
  for (const auto& [value, text] : kStatusNames) {
    if (text == name) return value;
  }
  return std::nullopt;
}

std::string contact_qp_status_choices() {
  std::string out;
  for (const auto& [value, name] : kStatusNames) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// KKT checker

double ContactQpKkt::max_residual() const noexcept {
  return nan_max(nan_max(stationarity, primal_feasibility), nan_max(dual_feasibility, complementarity));
}

std::string ContactQpKkt::describe() const {
  std::ostringstream os;
  os.precision(3);
  os << "KKT{stationarity=" << stationarity << ", primal=" << primal_feasibility << ", dual=" << dual_feasibility
     << ", complementarity=" << complementarity << ", tolerance=" << tolerance << ", lambda=" << sum_multiplier
     << ", mu=[" << bound_multipliers.transpose() << "], scales(force=" << force_scale
     << ", gradient=" << gradient_scale << ")}";
  return os.str();
}

ContactQpKkt check_kkt(const ContactQpProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& forces,
                       double tolerance) {
  check_kkt_inputs(problem, forces.size());
  const ContactVector gradient = problem.hessian() * forces + problem.linear_term();
  const double free_threshold = tolerance * std::max(1.0, std::abs(problem.fz));
  double lambda = 0.0;
  int free_count = 0;
  for (Eigen::Index l = 0; l < forces.size(); ++l) {
    if (forces(l) > free_threshold) {
      lambda += gradient(l);
      ++free_count;
    }
  }
  lambda = free_count > 0 ? lambda / free_count : gradient.minCoeff();
  ContactVector mu = ContactVector::Zero(forces.size());
  for (Eigen::Index l = 0; l < forces.size(); ++l) {
    if (!(forces(l) > free_threshold)) mu(l) = gradient(l) - lambda;
  }
  return evaluate_kkt(problem, forces, gradient, lambda, mu, tolerance);
}

ContactQpKkt check_kkt(const ContactQpProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& forces,
                       double sum_multiplier, const Eigen::Ref<const Eigen::VectorXd>& bound_multipliers,
                       double tolerance) {
  check_kkt_inputs(problem, forces.size());
  if (bound_multipliers.size() != forces.size()) {
    throw std::invalid_argument("check_kkt: bound_multipliers.size() = " + std::to_string(bound_multipliers.size()) +
                                ". Violated constraint: == forces.size() (" + std::to_string(forces.size()) + ")");
  }
  const ContactVector gradient = problem.hessian() * forces + problem.linear_term();
  return evaluate_kkt(problem, forces, gradient, sum_multiplier, bound_multipliers, tolerance);
}

// ---------------------------------------------------------------------------------------------
// Shared active-set loop

namespace detail {

bool load_is_valid(double fz, const Eigen::Vector2d& cop) noexcept {
  return std::isfinite(fz) && fz >= 0.0 && cop.allFinite() && std::isfinite(fz * cop.x()) &&
         std::isfinite(fz * cop.y());
}

void set_zero_solution(int n, ContactQpStatus status, ContactQpSolution& out) noexcept {
  out.forces.setZero(n);
  out.bound_multipliers.setZero(n);
  out.sum_multiplier = 0.0;
  out.status = status;
  out.iterations = 0;
  out.active_set = 0;
}

void run_primal_active_set(int n, double fz, double gradient_scale, int max_iterations,
                           EqualityQpSubproblem& subproblem, ContactQpSolution& out) noexcept {
  const std::uint32_t all = detail::contact_bit(n) - 1U;
  std::uint32_t fixed = out.active_set & all;
  if (fixed == all) fixed = 0;
  const int free_count = n - std::popcount(fixed);
  // Points that reach this fraction of fz in a blocked step are fixed too (ties, rounding).
  const double zero_tolerance = 1e-14 * fz;
  const double release_tolerance = 1e-10 * gradient_scale;

  ContactVector forces(n);
  for (int l = 0; l < n; ++l) forces(l) = (fixed & detail::contact_bit(l)) != 0U ? 0.0 : fz / free_count;
  ContactVector x(n);
  ContactVector mu(n);
  double lambda = 0.0;

  int iteration = 0;
  while (iteration < max_iterations) {
    ++iteration;
    if (!subproblem.solve(fixed, forces, x, lambda, mu)) {
      set_zero_solution(n, ContactQpStatus::solver_failure, out);
      out.iterations = iteration;
      return;
    }
    double alpha = 1.0;
    int blocking = -1;
    for (int l = 0; l < n; ++l) {
      if ((fixed & detail::contact_bit(l)) != 0U || !(x(l) < 0.0)) continue;
      const double ratio = forces(l) / (forces(l) - x(l)); // denominator > 0: forces(l) >= 0 > x(l)
      if (ratio < alpha) {
        alpha = ratio;
        blocking = l;
      }
    }
    if (blocking >= 0) {
      for (int l = 0; l < n; ++l) {
        if ((fixed & detail::contact_bit(l)) != 0U) continue;
        forces(l) += alpha * (x(l) - forces(l));
        if (l == blocking || (x(l) < 0.0 && forces(l) <= zero_tolerance)) {
          forces(l) = 0.0;
          fixed |= detail::contact_bit(l);
        }
      }
      continue;
    }
    forces = x;
    int release = -1;
    double most_negative = -release_tolerance;
    for (int l = 0; l < n; ++l) {
      if ((fixed & detail::contact_bit(l)) != 0U && mu(l) < most_negative) {
        most_negative = mu(l);
        release = l;
      }
    }
    if (release < 0) {
      out.forces = forces;
      out.bound_multipliers = mu;
      out.sum_multiplier = lambda;
      out.status = ContactQpStatus::optimal;
      out.iterations = iteration;
      out.active_set = fixed;
      return;
    }
    fixed &= ~detail::contact_bit(release);
  }
  out.forces = forces; // primal feasible, not proven optimal
  out.bound_multipliers.setZero(n);
  for (int l = 0; l < n; ++l) {
    if ((fixed & detail::contact_bit(l)) != 0U) out.bound_multipliers(l) = mu(l);
  }
  out.sum_multiplier = lambda;
  out.status = ContactQpStatus::iteration_limit;
  out.iterations = iteration;
  out.active_set = fixed;
}

} // namespace detail

// ---------------------------------------------------------------------------------------------
// ActiveSetContactQp

void ActiveSetContactQp::Options::validate() const {
  if (max_iterations < 1) {
    throw std::invalid_argument("ActiveSetContactQp::Options.max_iterations = " + std::to_string(max_iterations) +
                                ". Violated constraint: >= 1");
  }
}

ActiveSetContactQp::Subproblem::Subproblem(const ContactGeometry& geometry)
    : n_(geometry.size()), outer_(6, geometry.size()), points_(geometry.points), weights_(geometry.weights) {
  for (int l = 0; l < n_; ++l) {
    const double x = points_(0, l);
    const double y = points_(1, l);
    const double w = weights_(l); // > 0, validated
    outer_.col(l) << 1.0 / w, x / w, y / w, x * x / w, x * y / w, y * y / w;
  }
}

bool ActiveSetContactQp::Subproblem::solve(std::uint32_t fixed, const ContactVector& /*start*/, ContactVector& x,
                                           double& lambda, ContactVector& mu) noexcept {
  Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
  for (int l = 0; l < n_; ++l) {
    if ((fixed & detail::contact_bit(l)) == 0U) sum += outer_.col(l);
  }
  Eigen::Matrix3d k;
  k << sum(0), sum(1), sum(2), //
      sum(1), sum(3) + 1.0, sum(4), //
      sum(2), sum(4), sum(5) + 1.0;
  const Eigen::LLT<Eigen::Matrix3d> llt(k);
  if (llt.info() != Eigen::Success) return false; // K is SPD for non-empty F; defensive only
  const Eigen::Vector3d p = llt.solve(rhs);
  for (int l = 0; l < n_; ++l) {
    const double s = p(0) + points_(0, l) * p(1) + points_(1, l) * p(2);
    if ((fixed & detail::contact_bit(l)) == 0U) {
      x(l) = s / weights_(l);
      mu(l) = 0.0;
    } else {
      x(l) = 0.0;
      mu(l) = -2.0 * s;
    }
  }
  lambda = 2.0 * p(0);
  return true;
}

namespace {
ContactGeometry validated(ContactGeometry geometry) {
  geometry.validate();
  return geometry;
}
} // namespace

ActiveSetContactQp::ActiveSetContactQp(ContactGeometry geometry) : ActiveSetContactQp(std::move(geometry), Options{}) {}

ActiveSetContactQp::ActiveSetContactQp(ContactGeometry geometry, Options options)
    : geometry_(validated(std::move(geometry))), options_((options.validate(), options)), subproblem_(geometry_),
      hessian_norm_(hessian_inf_norm(geometry_)) {
  for (int l = 0; l < geometry_.size(); ++l) {
    moment_norm_ = std::max(moment_norm_, geometry_.points.col(l).lpNorm<1>());
  }
}

void ActiveSetContactQp::solve(double fz, const Eigen::Vector2d& cop, ContactQpSolution& out) noexcept {
  const int n = geometry_.size();
  if (!detail::load_is_valid(fz, cop)) {
    detail::set_zero_solution(n, ContactQpStatus::invalid_input, out);
    return;
  }
  if (fz == 0.0) {
    detail::set_zero_solution(n, ContactQpStatus::zero_load, out);
    return;
  }
  subproblem_.rhs << fz, fz * cop.x(), fz * cop.y();
  // Bound on ||H N||_inf + ||g||_inf, which sets the release tolerance on mu.
  const double gradient_scale = fz * (hessian_norm_ + 2.0 * moment_norm_ * cop.lpNorm<Eigen::Infinity>());
  out.active_set = options_.warm_start ? warm_active_set_ : 0U;
  detail::run_primal_active_set(n, fz, gradient_scale, options_.max_iterations, subproblem_, out);
  if (!out.forces.allFinite() || !out.bound_multipliers.allFinite() || !std::isfinite(out.sum_multiplier)) {
    detail::set_zero_solution(n, ContactQpStatus::invalid_input, out); // overflow for extreme inputs
    return;
  }
  if (out.status == ContactQpStatus::optimal) warm_active_set_ = out.active_set;
}

} // namespace ftsense::biped
