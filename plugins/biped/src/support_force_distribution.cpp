#include "ftsense/biped/support_force_distribution.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "ftsense/biped/contact_force_qp.hpp"
#include "ftsense/biped/stacked_feet.hpp"

namespace ftsense::biped {

void SupportForceDistribution::Params::describe(ParamSchema<Params>& schema) {
  schema.add("weight_m2", &Params::weight_m2,
             "w of the least-norm term w ||f||^2; small against the support's sum of squared offsets, so the "
             "moment about the ZMP is met")
      .unit("m^2").greater_than(0.0).plausible(1e-12, 1e-2, "a square micrometre to a tenth of a support's size");
}

SupportForceDistribution::SupportForceDistribution(const Params& params, const StageContext& context)
    : weight_m2_(params.weight_m2) {
  // Nothing wired sizes it for two feet; the pipeline reports the wire.
  feet_ = stacked_feet(context, 2);
  const std::size_t dim = 3 * feet_;
  if (feet_ > static_cast<std::size_t>(kMaxContactPoints)) {
    throw ConfigError("/inputs/foot_pos", "stacks " + std::to_string(feet_) + " feet; at most " +
                                              std::to_string(kMaxContactPoints) + " are supported");
  }
  ports_.add_input(PortSpec{"total_force", 3, "N", "total ground reaction force F (its z part is spread)"}
                       .in_frame("world"));
  ports_.add_input(PortSpec{"cop", 2, "m", "where the vertical force acts (x, y): the ZMP, or the CoM's projection"}
                       .in_frame("world"));
  ports_.add_input(PortSpec{"foot_pos", dim, "m", "foot frame origins (x, y, z) stacked foot after foot"}
                       .in_frame("world")
                       .sized_by("as wired: 3 per foot"));
  ports_.add_input(PortSpec{"contact", feet_, "1", "per foot: 1 in contact, 0 in swing"}
                       .sized_by("feet (foot_pos / 3)"));
  ports_.add_output(PortSpec{"forces", feet_, "N", "normal force per foot (0 in swing); NaN when not ready"}
                        .sized_by("feet (foot_pos / 3)"));
}

void SupportForceDistribution::step(const StepIO& io) noexcept {
  const auto total = io.in(kTotalForce);
  const auto cop = io.in(kCop);
  const auto foot_pos = io.in(kFootPos);
  const auto contact = io.in(kContact);
  const auto forces = io.out(kForces);
  const auto not_ready = [&forces] {
    for (double& f : forces) f = std::numeric_limits<double>::quiet_NaN();
  };
  std::array<std::size_t, kMaxContactPoints> stance{};
  int n = 0;
  for (std::size_t i = 0; i < feet_; ++i) {
    if (!std::isfinite(contact[i])) return not_ready();
    forces[i] = 0.0;
    if (contact[i] > 0.5) {
      if (!std::isfinite(foot_pos[3 * i]) || !std::isfinite(foot_pos[3 * i + 1])) return not_ready();
      stance[static_cast<std::size_t>(n++)] = i;
    }
  }
  if (n == 0) return;  // flight: no foot carries anything
  const double fz = total[2];
  if (!std::isfinite(fz) || !std::isfinite(cop[0]) || !std::isfinite(cop[1])) return not_ready();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (int k = 0; k < n; ++k) {
    const std::size_t i = stance[static_cast<std::size_t>(k)];
    centre += Eigen::Vector2d(foot_pos[3 * i], foot_pos[3 * i + 1]);
  }
  centre /= n;
  ContactGeometry geometry;
  geometry.points.resize(2, n);
  geometry.weights.setConstant(n, weight_m2_);
  for (int k = 0; k < n; ++k) {
    const std::size_t i = stance[static_cast<std::size_t>(k)];
    geometry.points(0, k) = foot_pos[3 * i] - centre.x();
    geometry.points(1, k) = foot_pos[3 * i + 1] - centre.y();
  }
  // The geometry is valid by construction (1..8 finite points, w > 0), so the solver's
  // constructor cannot throw here; it allocates nothing (fixed-capacity matrices).
  ActiveSetContactQp solver(geometry);
  ContactQpSolution solution;
  solver.solve(fz, Eigen::Vector2d(cop[0], cop[1]) - centre, solution);
  if (!solution.ok()) return not_ready();  // F_z < 0 or an overflow: no answer, not zeros
  for (int k = 0; k < n; ++k) forces[stance[static_cast<std::size_t>(k)]] = solution.forces(k);
}

}  // namespace ftsense::biped
