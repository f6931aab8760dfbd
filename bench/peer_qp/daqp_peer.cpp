// DAQP (github.com/darnstrom/daqp, C) with one persistent workspace per foot: H is factored once at
// set-up; each instance updates only the linear term and the equality's bound
// (daqp_update_ldp with DAQP_UPDATE_v | DAQP_UPDATE_d), so the working set and its factorisation
// carry over from the previous instance (warm start).
#include <vector>

#include "api.h"
#include "constants.h"
#include "utils.h"  // daqp_update_ldp, as DAQP's own C++ interface uses it
#include "solver_under_test.hpp"

namespace ftsense::peer_qp {
namespace {

class DaqpSolver final : public SolverUnderTest {
 public:
  explicit DaqpSolver(const biped::ContactGeometry& geometry)
      : geometry_(geometry), n_(geometry.size()), h_(n_ * n_), f_(n_, 0.0), a_(n_, 1.0), upper_(n_ + 1, DAQP_INF),
        lower_(n_ + 1, 0.0), sense_(n_ + 1, 0), x_(n_), lambda_(n_ + 1) {
    const biped::ContactMatrix h = biped::ContactQpProblem{geometry, 0.0, Eigen::Vector2d::Zero()}.hessian();
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < n_; ++j) h_[i * n_ + j] = h(i, j);
    }
    // Rows 0..n-1: the simple bounds 0 <= N_l; row n: 1^T N = F_z (set per instance).
    upper_[n_] = lower_[n_] = 1.0;
    sense_[n_] = DAQP_ACTIVE + DAQP_IMMUTABLE;
    problem_ = DAQPProblem{n_, n_ + 1, n_, h_.data(), f_.data(), a_.data(), upper_.data(), lower_.data(),
                           sense_.data(), nullptr, 0, 0};
    ok_ = setup_daqp(&problem_, &work_, nullptr) >= 0;
  }
  DaqpSolver(const DaqpSolver&) = delete;
  DaqpSolver& operator=(const DaqpSolver&) = delete;
  ~DaqpSolver() override {
    free_daqp_workspace(&work_);
    free_daqp_ldp(&work_);
  }

  bool solve(double fz, const Eigen::Vector2d& cop, double* forces) noexcept override {
    if (!ok_) return false;
    linear_term(geometry_, fz, cop, f_.data());
    upper_[n_] = lower_[n_] = fz;
    if (daqp_update_ldp(DAQP_UPDATE_v + DAQP_UPDATE_d, &work_, &problem_) < 0) return false;
    DAQPResult result{};
    result.x = x_.data();
    result.lam = lambda_.data();
    daqp_solve(&result, &work_);
    for (int l = 0; l < n_; ++l) forces[l] = x_[l];
    return result.exitflag > 0;
  }

 private:
  biped::ContactGeometry geometry_;
  int n_;
  std::vector<double> h_, f_, a_, upper_, lower_;
  std::vector<int> sense_;
  std::vector<double> x_, lambda_;
  DAQPProblem problem_{};
  DAQPWorkspace work_{};
  bool ok_ = false;
};

}  // namespace

std::vector<SolverKind> daqp_solvers() {
  return {{"DAQP, warm workspace", [](const biped::ContactGeometry& g) -> std::unique_ptr<SolverUnderTest> {
             return std::make_unique<DaqpSolver>(g);
           }}};
}

}  // namespace ftsense::peer_qp
