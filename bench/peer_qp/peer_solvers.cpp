// The peers this build was configured with (bench/peer_qp/CMakeLists.txt defines FTSENSE_PEER_*
// for each peer whose sources it found).
#include "solver_under_test.hpp"

namespace ftsense::peer_qp {

std::vector<SolverKind> peer_solvers() {
  std::vector<SolverKind> kinds;
  const auto add = [&kinds](std::vector<SolverKind> more) {
    for (auto& kind : more) kinds.push_back(std::move(kind));
  };
#ifdef FTSENSE_PEER_DAQP
  add(daqp_solvers());
#endif
#ifdef FTSENSE_PEER_EIQUADPROG
  add(eiquadprog_solvers());
#endif
#ifdef FTSENSE_PEER_QPOASES
  add(qpoases_solvers());
#endif
  (void)add;
  return kinds;
}

}  // namespace ftsense::peer_qp
