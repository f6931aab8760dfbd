#pragma once
// One contact-force QP solver under comparison (bench/peer_qp). Every solver gets the same problem
// (include/ftsense/biped/contact_force_qp.hpp) in its own standard form:
//
//     minimise    1/2 N^T H N + g^T N,   H = 2 (C^T C + W),   g = -2 C^T (F_z r)
//     subject to  1^T N = F_z,   N >= 0
//
// with the foot geometry (C, W) fixed at construction and the load (F_z [N], CoP r [m]) given per
// instance. Forming g (and whatever else a solver needs per instance) is part of the timed solve.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ftsense/biped/contact_force_qp.hpp"

namespace ftsense::peer_qp {

class SolverUnderTest {
 public:
  virtual ~SolverUnderTest() = default;
  // Writes the n point forces [N]; false when the solver reports a failure.
  virtual bool solve(double fz, const Eigen::Vector2d& cop, double* forces) noexcept = 0;
};

// How to make one kind of solver for a geometry.
struct SolverKind {
  std::string name;
  std::unique_ptr<SolverUnderTest> (*make)(const biped::ContactGeometry& geometry);
};

// g = -2 C^T (F_z r), the linear term every standard-form peer takes.
inline void linear_term(const biped::ContactGeometry& geometry, double fz, const Eigen::Vector2d& cop,
                        double* g) noexcept {
  const double dx = fz * cop.x();
  const double dy = fz * cop.y();
  for (int l = 0; l < geometry.size(); ++l) {
    g[l] = -2.0 * (geometry.points(0, l) * dx + geometry.points(1, l) * dy);
  }
}

// The peers compiled into this build (FTSENSE_PEER_QP_SOURCES), ftsense's own solver excluded.
std::vector<SolverKind> peer_solvers();

// One per peer, defined only when that peer's sources were given (peer_solvers() lists them).
std::vector<SolverKind> daqp_solvers();
std::vector<SolverKind> eiquadprog_solvers();
std::vector<SolverKind> qpoases_solvers();

}  // namespace ftsense::peer_qp
