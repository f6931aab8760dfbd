// ftsense-peer-qp: the contact-force QP solver against peer QP solvers on the very instances the
// pipeline solves (docs/performance.md). Usage:
//
//   ftsense-peer-qp [--seconds S] [--passes P]      (defaults: a 35 s walk, 31 passes)
//
// Instances (walk_instances.hpp): every loaded tick of each foot of a simulated walk through
// configs/suralp.json. 4-point instances: the config's foot (4 sole corners, W = 0.01 I). 8-point
// instances: the same loads on the 8-point outline of the same sole
// (plugins/biped/bench/bench_soles.hpp). Each solver gets one object per foot and that foot's
// instances in time order, so warm starts see what they would see in the pipeline.
//
// Agreement (one untimed pass): the largest |N_l - N_l(ftsense)| [N] over all instances and
// points, per solver; and ftsense's solver here against the forces the pipeline output (4
// points; 0 expected: same solver, same inputs, same warm-start sequence). Exit status 1 when a
// solver failed or disagreed by more than kAgreement_N, or ftsense's differs from the pipeline.
// Timing: P passes; in each pass every solver solves every instance once, the solvers taking
// turns, so the load of a shared machine falls on all alike. Per pass: its wall time / instances;
// reported: the median over passes and the fastest pass (on a busy machine other work only adds
// time, so the fastest pass is the least disturbed), each also as a ratio to ftsense's.
//
// The peers are compiled in when the build was configured with FTSENSE_PEER_QP_SOURCES (see
// bench/peer_qp/CMakeLists.txt); without them only ftsense's own solver runs.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bench_soles.hpp"
#include "solver_under_test.hpp"
#include "walk_instances.hpp"

#ifndef FTSENSE_SOURCE_DIR
#define FTSENSE_SOURCE_DIR "."
#endif

namespace {

using ftsense::biped::ActiveSetContactQp;
using ftsense::biped::ContactGeometry;
using ftsense::biped::ContactQpSolution;
using ftsense::peer_qp::FootInstance;
using ftsense::peer_qp::SolverKind;
using ftsense::peer_qp::SolverUnderTest;
using ftsense::peer_qp::WalkInstances;

constexpr std::uint64_t kSeed = 1;
// Forces are 0..~1000 N; solvers that agree to 1e-6 N found the same optimum.
constexpr double kAgreement_N = 1e-6;

// The larger of a running maximum and a difference; NaN once either is NaN.
double max_difference(double so_far, double d) {
  return std::isnan(so_far) || std::isnan(d) ? std::numeric_limits<double>::quiet_NaN() : std::max(so_far, d);
}

// ftsense's exact active-set solver, as the pipeline runs it (warm start on).
class FtsenseSolver final : public SolverUnderTest {
 public:
  explicit FtsenseSolver(const ContactGeometry& geometry) : solver_(geometry) {}
  bool solve(double fz, const Eigen::Vector2d& cop, double* forces) noexcept override {
    solver_.solve(fz, cop, solution_);
    for (Eigen::Index l = 0; l < solution_.forces.size(); ++l) forces[l] = solution_.forces(l);
    return solution_.ok();
  }

 private:
  ActiveSetContactQp solver_;
  ContactQpSolution solution_;
};

struct Contender {
  std::string name;
  std::array<std::unique_ptr<SolverUnderTest>, 2> feet;
  double max_difference_N = 0.0;
  std::size_t failures = 0;
  std::vector<double> ns_per_solve;  // one per pass
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

std::size_t parse_count(const char* flag, const char* text) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(value >= 1.0) || value > 1e6) {
    std::fprintf(stderr, "ftsense-peer-qp: %s '%s' is not a positive number\n", flag, text);
    std::exit(2);
  }
  return static_cast<std::size_t>(value);
}

// Compares and times every contender on one geometry; prints a Markdown table. Returns false
// when a solver failed or disagreed (see kAgreement_N), or ftsense's differs from the pipeline.
bool compare(const char* title, const ContactGeometry& geometry, const WalkInstances& walk,
             const std::vector<SolverKind>& kinds, std::size_t passes, bool against_pipeline) {
  const int n = geometry.size();
  const std::size_t instances = walk.feet[0].size() + walk.feet[1].size();
  std::vector<Contender> contenders;
  for (const SolverKind& kind : kinds) {
    Contender c{kind.name, {kind.make(geometry), kind.make(geometry)}, 0.0, 0, {}};
    if (!c.feet[0] || !c.feet[1]) {
      std::printf("(%s skipped: no %d-point variant)\n", kind.name.c_str(), n);
      continue;
    }
    contenders.push_back(std::move(c));
  }

  // Agreement, untimed: contender 0 is ftsense's solver, the reference.
  std::array<std::vector<double>, 2> reference;
  std::vector<double> forces(static_cast<std::size_t>(n));
  double pipeline_difference_N = 0.0;
  for (std::size_t k = 0; k < contenders.size(); ++k) {
    Contender& c = contenders[k];
    for (std::size_t foot = 0; foot < 2; ++foot) {
      const std::vector<FootInstance>& list = walk.feet[foot];
      if (k == 0) reference[foot].resize(list.size() * forces.size());
      for (std::size_t i = 0; i < list.size(); ++i) {
        if (!c.feet[foot]->solve(list[i].fz, list[i].cop, forces.data())) ++c.failures;
        for (std::size_t l = 0; l < forces.size(); ++l) {
          double& ref = reference[foot][i * forces.size() + l];
          if (k == 0) {
            ref = forces[l];
            if (against_pipeline) {
              pipeline_difference_N = max_difference(
                  pipeline_difference_N, std::abs(forces[l] - walk.pipeline_forces[foot][i * forces.size() + l]));
            }
          }
          c.max_difference_N = max_difference(c.max_difference_N, std::abs(forces[l] - ref));
        }
      }
    }
  }

  for (std::size_t pass = 0; pass < passes; ++pass) {
    for (Contender& c : contenders) {
      const auto start = std::chrono::steady_clock::now();
      for (std::size_t foot = 0; foot < 2; ++foot) {
        SolverUnderTest& solver = *c.feet[foot];
        for (const FootInstance& instance : walk.feet[foot]) solver.solve(instance.fz, instance.cop, forces.data());
      }
      const auto stop = std::chrono::steady_clock::now();
      c.ns_per_solve.push_back(std::chrono::duration<double, std::nano>(stop - start).count() /
                               static_cast<double>(instances));
    }
  }

  std::printf("\n%s: %zu instances (left %zu, right %zu)\n", title, instances, walk.feet[0].size(),
              walk.feet[1].size());
  if (against_pipeline) {
    std::printf("ftsense here vs the pipeline's own output: max |N difference| = %.3g N\n", pipeline_difference_N);
  }
  std::printf("\n| solver | ns per solve, median of %zu passes | x ftsense | fastest pass | x ftsense | "
              "max abs(N - N_ftsense) [N] | failed |\n",
              passes);
  std::printf("|---|---|---|---|---|---|---|\n");
  const double ftsense_median = median(contenders.front().ns_per_solve);
  const double ftsense_fastest =
      *std::min_element(contenders.front().ns_per_solve.begin(), contenders.front().ns_per_solve.end());
  for (const Contender& c : contenders) {
    const double ns = median(c.ns_per_solve);
    const double fastest = *std::min_element(c.ns_per_solve.begin(), c.ns_per_solve.end());
    std::printf("| %s | %.0f | %.2f | %.0f | %.2f | %.1e | %zu |\n", c.name.c_str(), ns, ns / ftsense_median, fastest,
                fastest / ftsense_fastest, c.max_difference_N, c.failures);
  }
  bool agree = pipeline_difference_N == 0.0;
  for (const Contender& c : contenders) {
    if (c.failures > 0 || !(c.max_difference_N <= kAgreement_N)) {
      std::printf("DISAGREEMENT: %s (%zu failed, max difference %.3g N > %.0e N)\n", c.name.c_str(), c.failures,
                  c.max_difference_N, kAgreement_N);
      agree = false;
    }
  }
  return agree;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 35.0;
  std::size_t passes = 31;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
      seconds = static_cast<double>(parse_count("--seconds", argv[++i]));
    } else if (std::strcmp(argv[i], "--passes") == 0 && i + 1 < argc) {
      passes = parse_count("--passes", argv[++i]);
    } else {
      std::fprintf(stderr, "usage: ftsense-peer-qp [--seconds S] [--passes P]\n");
      return 2;
    }
  }
  std::vector<SolverKind> kinds{{"ftsense active set", [](const ContactGeometry& g) -> std::unique_ptr<SolverUnderTest> {
                                   return std::make_unique<FtsenseSolver>(g);
                                 }}};
  const std::vector<SolverKind> peers = ftsense::peer_qp::peer_solvers();
  kinds.insert(kinds.end(), peers.begin(), peers.end());

  const WalkInstances walk = ftsense::peer_qp::record_walk_instances(FTSENSE_SOURCE_DIR, seconds, kSeed);
  std::printf("walk: configs/scenarios/clean.json, %.0f s, seed %llu, %zu ticks through configs/suralp.json\n",
              seconds, static_cast<unsigned long long>(kSeed), walk.ticks);
  std::printf("peers compiled in:%s\n",
              peers.empty() ? " none (configure with -DFTSENSE_PEER_QP_SOURCES=<dir>, see bench/peer_qp_compare.sh)" : "");
  for (const SolverKind& peer : peers) std::printf("  %s\n", peer.name.c_str());

  const bool four = compare("4-point instances (the config's foot: sole corners)", walk.geometry, walk, kinds, passes, true);
  const bool eight = compare("8-point instances (the same loads on the 8-point outline of the sole)",
                             ftsense::biped::bench::sole(8), walk, kinds, passes, false);
  return four && eight ? 0 : 1;
}
