#pragma once
// Distribution of one foot's normal force over its contact points (method.md section 4; paper
// eq. 13-23, corrected), as a pipeline stage:
//
//   minimise || C N - d ||^2 + N^T W N   subject to   sum_l N_l = F_z,  N_l >= 0
//   C = [x_1 .. x_n; y_1 .. y_n],  d = F_z r,  W = diag(weights)
//
// The weights default to 1e-6 m^2, not the paper's 0.01: in SI units W competes with C^T C
// (sum x_l^2 = 0.058 m^2 for SURALP's 0.240 x 0.150 m sole), so W = 0.01 I leaves the realised
// CoP at 85 % (x) and 69 % (y) of the requested one even inside the polygon. A small W meets the
// moment equations to within sqrt(w) F_z (1 mm of CoP for 1e-6) and keeps the problem strictly
// convex, which is what method.md section 4 intends ("the moment equations are met exactly and W
// picks the least-norm split").
//
// Two solvers behind one interface (contact_force_qp.hpp): `active_set`, exact and
// allocation-free (the default, for the control loop), and `ceres`, an active-set loop whose
// equality-constrained subproblems Ceres solves (as the user asked; Ceres allocates internally,
// so it is for offline runs and cross-checks). Outputs N [N] in the order of `points`, and the
// solver status code (0 optimal, 1 zero load, 2 invalid input, 3 iteration limit, 4 solver
// failure). Forces are NaN exactly when there is no answer (status 2 or more): an invalid input
// means the virtual sensor upstream is not ready, and NaN makes the fault filter hold its state
// instead of judging the sensors against a made-up zero.

#include <array>
#include <memory>
#include <string_view>
#include <vector>

#include "ftsense/biped/contact_force_qp.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class ContactForceDistribution {
 public:
  static constexpr std::string_view name = "contact_force_distribution";
  static constexpr std::string_view summary =
      "contact-point normal forces of one foot from F_z and the CoP: bounded least squares (eq. 13-23)";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"({"points": [[0.12, 0.075], [0.12, -0.075], [-0.12, 0.075], [-0.12, -0.075]]})";

  enum class Solver { active_set, ceres };

  struct Params {
    std::vector<std::array<double, 2>> points;
    std::vector<double> weights{1e-6};
    Solver solver = Solver::active_set;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kCop, kNormalForce };
  enum Output : std::size_t { kForces, kStatus };

  ContactForceDistribution(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  std::unique_ptr<ContactForceQpSolver> solver_;
  ContactQpSolution solution_;
};

}  // namespace ftsense::biped
