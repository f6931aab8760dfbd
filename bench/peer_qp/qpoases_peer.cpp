// qpOASES (github.com/coin-or/qpOASES): QProblem with H and A fixed, initialised once at set-up;
// each instance is a hotstart (new g and equality bounds, the previous working set and
// factorisations carried over). Default options, output off.
#include <vector>

#include <qpOASES.hpp>

#include "solver_under_test.hpp"

namespace ftsense::peer_qp {
namespace {

class QpOasesSolver final : public SolverUnderTest {
 public:
  explicit QpOasesSolver(const biped::ContactGeometry& geometry)
      : geometry_(geometry), n_(geometry.size()), problem_(n_, 1), h_(n_ * n_), g_(n_, 0.0), a_(n_, 1.0),
        lower_(n_, 0.0), upper_(n_, qpOASES::INFTY), x_(n_) {
    const biped::ContactMatrix h = biped::ContactQpProblem{geometry, 0.0, Eigen::Vector2d::Zero()}.hessian();
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < n_; ++j) h_[i * n_ + j] = h(i, j);
    }
    qpOASES::Options options;
    options.printLevel = qpOASES::PL_NONE;
    problem_.setOptions(options);
    qpOASES::real_t load = 1.0;
    qpOASES::int_t working_set_changes = 100;
    ok_ = problem_.init(h_.data(), g_.data(), a_.data(), lower_.data(), upper_.data(), &load, &load,
                        working_set_changes) == qpOASES::SUCCESSFUL_RETURN;
  }

  bool solve(double fz, const Eigen::Vector2d& cop, double* forces) noexcept override {
    if (!ok_) return false;
    linear_term(geometry_, fz, cop, g_.data());
    qpOASES::real_t load = fz;
    qpOASES::int_t working_set_changes = 100;
    const qpOASES::returnValue status =
        problem_.hotstart(g_.data(), lower_.data(), upper_.data(), &load, &load, working_set_changes);
    problem_.getPrimalSolution(x_.data());
    for (int l = 0; l < n_; ++l) forces[l] = x_[l];
    return status == qpOASES::SUCCESSFUL_RETURN;
  }

 private:
  biped::ContactGeometry geometry_;
  int n_;
  qpOASES::QProblem problem_;
  std::vector<qpOASES::real_t> h_, g_, a_, lower_, upper_, x_;
  bool ok_ = false;
};

}  // namespace

std::vector<SolverKind> qpoases_solvers() {
  return {{"qpOASES, hotstart", [](const biped::ContactGeometry& g) -> std::unique_ptr<SolverUnderTest> {
             return std::make_unique<QpOasesSolver>(g);
           }}};
}

}  // namespace ftsense::peer_qp
