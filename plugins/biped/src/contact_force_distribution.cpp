#include "ftsense/biped/contact_force_distribution.hpp"

#include <limits>
#include <stdexcept>

#include "ftsense/biped/contact_force_qp_ceres.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::biped {

void ContactForceDistribution::Params::describe(ParamSchema<Params>& schema) {
  schema.add("points", &Params::points, "contact points (x, y) of the foot, foot frame")
      .unit("m").count_at_least(1).count_at_most(kMaxContactPoints).required()
      .plausible(plausible::foot_point_m());
  schema.add("weights", &Params::weights,
             "diagonal of W, one value for all points or one per point (paper: 0.01, see README)")
      .unit("m^2").greater_than(0.0).count_at_least(1)
      .plausible(1e-12, 0.1, "sqrt(w) is about the CoP error W allows: a micrometre to 0.3 m");
  schema.add_choice("solver", &Params::solver,
                    "active_set: exact and allocation-free; ceres: Ceres-solved subproblems (offline)",
                    {{"active_set", Solver::active_set}, {"ceres", Solver::ceres}});
}

void ContactForceDistribution::Params::validate(Diagnostics& diag, std::string_view path) const {
  if (weights.size() != 1 && weights.size() != points.size()) {
    diag.error(std::string(path) + "/weights", "has " + std::to_string(weights.size()) + " entries for " +
                                                   std::to_string(points.size()) +
                                                   " points; give one weight for all or one per point");
  }
}

ContactForceDistribution::ContactForceDistribution(const Params& params, const StageContext& /*context*/) {
  const int n = static_cast<int>(params.points.size());
  ContactGeometry geometry;
  geometry.points.resize(2, n);
  geometry.weights.resize(n);
  for (int l = 0; l < n; ++l) {
    geometry.points(0, l) = params.points[l][0];
    geometry.points(1, l) = params.points[l][1];
    geometry.weights(l) = params.weights.size() == 1 ? params.weights[0] : params.weights[l];
  }
  try {
    if (params.solver == Solver::active_set) {
      solver_ = std::make_unique<ActiveSetContactQp>(geometry);
    } else {
      solver_ = std::make_unique<CeresContactQp>(geometry);
    }
  } catch (const std::invalid_argument& e) {
    throw ConfigError("/params", e.what());
  }
  solution_.forces.setZero(n);
  solution_.bound_multipliers.setZero(n);
  ports_.add_input(PortSpec{"cop", 2, "m", "centre of pressure r of the foot"}.in_frame("foot"));
  ports_.add_input(PortSpec{"normal_force", 1, "N", "the foot's normal force F_z"}.in_frame("foot"));
  ports_.add_output(PortSpec{"forces", static_cast<std::size_t>(n), "N", "normal force N_l per contact point"}
                        .sized_by("len(params.points)"));
  ports_.add_output({"status", 1, "1", "solver status code (0 optimal, 1 zero load, 2 invalid input, ...)"});
}

void ContactForceDistribution::reset() noexcept { solver_->reset(); }

void ContactForceDistribution::step(const StepIO& io) noexcept {
  const auto cop = io.in(kCop);
  solver_->solve(io.in(kNormalForce)[0], Eigen::Vector2d(cop[0], cop[1]), solution_);
  const auto forces = io.out(kForces);
  // No answer (invalid input: the virtual sensor upstream is not ready; or a solver failure) is
  // NaN, not zero: zero forces would be a confident, wrong virtual value.
  const bool answered = solution_.ok();
  for (std::size_t l = 0; l < forces.size(); ++l) {
    forces[l] = answered ? solution_.forces(static_cast<Eigen::Index>(l)) : std::numeric_limits<double>::quiet_NaN();
  }
  io.out(kStatus)[0] = static_cast<double>(solution_.status);
}

}  // namespace ftsense::biped
