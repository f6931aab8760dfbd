// RtEiquadprog (github.com/stack-of-tasks/eiquadprog, header-only, sizes fixed at compile time):
// the Goldfarb-Idnani dual active-set method, which starts every solve from the unconstrained
// minimum (no warm start). Two ways to call it:
//   - factor per solve: Cholesky of H and L^-T on every instance (its default);
//   - factor reused: L^-T computed once here and handed in each time (is_inverse_provided_). The
//     solver rotates m_J in place while it works, so the saved factor is copied back before each
//     solve (64 doubles at n = 8, inside the timed solve).
// With is_inverse_provided_, RtEiquadprog (at least up to 11a688b) forms the unconstrained start
// as m_J m_J^T g0 = +H^-1 g0 where its own factorising branch computes -H^-1 g0; g0 enters nothing
// else but the reported objective value, so that mode gets -g0 and yields the minimiser of the
// stated problem (the agreement check in peer_qp_compare verifies the forces).
#include <eiquadprog/eiquadprog-rt.hpp>

#include "solver_under_test.hpp"

namespace ftsense::peer_qp {
namespace {

template <int N>
class RtEiquadprogSolver final : public SolverUnderTest {
 public:
  RtEiquadprogSolver(const biped::ContactGeometry& geometry, bool reuse_factor)
      : geometry_(geometry), reuse_factor_(reuse_factor) {
    hessian_ = biped::ContactQpProblem{geometry, 0.0, Eigen::Vector2d::Zero()}.hessian();
    equality_.setOnes();
    inequality_.setIdentity();
    inequality_offset_.setZero();
    const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(hessian_);
    inverse_factor_.setIdentity();
    llt.matrixU().solveInPlace(inverse_factor_);
  }

  bool solve(double fz, const Eigen::Vector2d& cop, double* forces) noexcept override {
    Eigen::Matrix<double, N, 1> g;
    linear_term(geometry_, fz, cop, g.data());
    equality_offset_(0) = -fz;  // 1^T N - F_z = 0
    if (reuse_factor_) {
      solver_.m_J = inverse_factor_;
      solver_.is_inverse_provided_ = true;
      g = -g;  // see the note at the top of this file
    }
    const auto status = solver_.solve_quadprog(hessian_, g, equality_, equality_offset_, inequality_,
                                               inequality_offset_, x_);
    for (int l = 0; l < N; ++l) forces[l] = x_(l);
    return status == eiquadprog::solvers::RT_EIQUADPROG_OPTIMAL;
  }

 private:
  biped::ContactGeometry geometry_;
  bool reuse_factor_;
  eiquadprog::solvers::RtEiquadprog<N, 1, N> solver_;
  Eigen::Matrix<double, N, N> hessian_, inequality_, inverse_factor_;
  Eigen::Matrix<double, 1, N> equality_;
  Eigen::Matrix<double, 1, 1> equality_offset_;
  Eigen::Matrix<double, N, 1> inequality_offset_, x_;
};

template <bool ReuseFactor>
std::unique_ptr<SolverUnderTest> make(const biped::ContactGeometry& geometry) {
  switch (geometry.size()) {
    case 4: return std::make_unique<RtEiquadprogSolver<4>>(geometry, ReuseFactor);
    case 8: return std::make_unique<RtEiquadprogSolver<8>>(geometry, ReuseFactor);
    default: return nullptr;  // sizes are template arguments; the comparison uses 4 and 8
  }
}

}  // namespace

std::vector<SolverKind> eiquadprog_solvers() {
  return {{"RtEiquadprog, factor per solve", &make<false>}, {"RtEiquadprog, factor reused", &make<true>}};
}

}  // namespace ftsense::peer_qp
