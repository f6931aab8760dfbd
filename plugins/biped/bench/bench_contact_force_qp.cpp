// Contact force QP solvers on realistic 1 kHz inputs: a walking-like stance (Fz rises, holds and
// falls to zero, then swing) while the CoP rolls heel to toe with lateral sway. The "wide" variant
// lets the CoP leave the support polygon (heel strike / push-off overshoot of the estimate), which
// exercises the bound constraints. Each benchmark iteration is one solve; time per iteration is the
// cost per sample. Run with --benchmark_repetitions=N --benchmark_report_aggregates_only=true for
// medians.
#include "ftsense/biped/contact_force_qp.hpp"
#include "ftsense/biped/contact_force_qp_ceres.hpp"
#include "bench_soles.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace {

using ftsense::biped::ActiveSetContactQp;
using ftsense::biped::CeresContactQp;
using ftsense::biped::ContactGeometry;
using ftsense::biped::ContactQpSolution;

struct Sample {
  double fz;
  Eigen::Vector2d cop;
};

// 1 kHz, 1.0 s gait cycle: 0.6 s stance, 0.4 s swing (Fz = 0), plus small sensor noise.
std::vector<Sample> gait_trajectory(double cop_reach, int cycles) {
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<Sample> samples;
  for (int k = 0; k < 1000 * cycles; ++k) {
    const double t = std::fmod(1e-3 * k, 1.0);
    Sample s{0.0, Eigen::Vector2d::Zero()};
    if (t < 0.6) {
      const double u = t / 0.6; // stance progress
      s.fz = 750.0 * std::sin(std::numbers::pi * u) * (1.0 + 0.25 * std::sin(2.0 * std::numbers::pi * u)) +
             2.0 * noise(rng);
      s.fz = std::max(s.fz, 0.0);
      s.cop = Eigen::Vector2d(-cop_reach + 2.0 * cop_reach * u, 0.3 * cop_reach * std::sin(std::numbers::pi * u)) +
              1e-3 * Eigen::Vector2d(noise(rng), noise(rng));
    }
    samples.push_back(s);
  }
  return samples;
}

ContactGeometry foot(int points) { return ftsense::biped::bench::sole(points); }

template <class Solver>
void run(benchmark::State& state, bool warm_start) {
  const int points = static_cast<int>(state.range(0));
  const double reach = state.range(1) == 0 ? 0.09 : 0.20; // inside vs. leaving the polygon
  const std::vector<Sample> samples = gait_trajectory(reach, 3);
  typename Solver::Options options;
  options.warm_start = warm_start;
  Solver solver(foot(points), options);
  ContactQpSolution solution;
  std::size_t k = 0;
  long iterations = 0;
  long loaded = 0;
  for (auto _ : state) {
    const Sample& s = samples[k];
    solver.solve(s.fz, s.cop, solution);
    benchmark::DoNotOptimize(solution.forces.data());
    benchmark::ClobberMemory();
    iterations += solution.iterations;
    loaded += s.fz > 0.0 ? 1 : 0;
    k = (k + 1 == samples.size()) ? 0 : k + 1;
  }
  state.counters["qp_iterations_per_loaded_solve"] =
      loaded > 0 ? static_cast<double>(iterations) / static_cast<double>(loaded) : 0.0;
  state.counters["loaded_fraction"] = static_cast<double>(loaded) / static_cast<double>(state.iterations());
}

// Only the loaded (stance) samples: the cost that matters for the 1 ms budget.
template <class Solver>
void run_stance_only(benchmark::State& state) {
  const int points = static_cast<int>(state.range(0));
  const double reach = state.range(1) == 0 ? 0.09 : 0.20;
  std::vector<Sample> samples = gait_trajectory(reach, 3);
  std::erase_if(samples, [](const Sample& s) { return s.fz <= 0.0; });
  Solver solver(foot(points));
  ContactQpSolution solution;
  std::size_t k = 0;
  long iterations = 0;
  for (auto _ : state) {
    const Sample& s = samples[k];
    solver.solve(s.fz, s.cop, solution);
    benchmark::DoNotOptimize(solution.forces.data());
    benchmark::ClobberMemory();
    iterations += solution.iterations;
    k = (k + 1 == samples.size()) ? 0 : k + 1;
  }
  state.counters["qp_iterations_per_solve"] =
      static_cast<double>(iterations) / static_cast<double>(state.iterations());
}

// Per-solve latency distribution over the stance samples: each solve is timed on its own with
// steady_clock (includes ~20-30 ns of clock overhead per reading pair on this VM). Reports the
// median, 99th percentile and maximum in ns as counters; the benchmark time itself is per pass.
template <class Solver>
void run_latency(benchmark::State& state) {
  const int points = static_cast<int>(state.range(0));
  const double reach = state.range(1) == 0 ? 0.09 : 0.20;
  std::vector<Sample> samples = gait_trajectory(reach, 3);
  std::erase_if(samples, [](const Sample& s) { return s.fz <= 0.0; });
  Solver solver(foot(points));
  ContactQpSolution solution;
  std::vector<double> latencies;
  latencies.reserve(samples.size() * 64);
  for (auto _ : state) {
    for (const Sample& s : samples) {
      const auto start = std::chrono::steady_clock::now();
      solver.solve(s.fz, s.cop, solution);
      benchmark::DoNotOptimize(solution.forces.data());
      benchmark::ClobberMemory();
      const auto stop = std::chrono::steady_clock::now();
      latencies.push_back(std::chrono::duration<double, std::nano>(stop - start).count());
    }
  }
  std::sort(latencies.begin(), latencies.end());
  const auto at = [&](double q) { return latencies[static_cast<std::size_t>(q * static_cast<double>(latencies.size() - 1))]; };
  state.counters["p50_ns"] = at(0.5);
  state.counters["p99_ns"] = at(0.99);
  state.counters["max_ns"] = latencies.back();
  state.counters["solves"] = static_cast<double>(latencies.size());
}

void BM_ActiveSet_Latency(benchmark::State& state) { run_latency<ActiveSetContactQp>(state); }
void BM_Ceres_Latency(benchmark::State& state) { run_latency<CeresContactQp>(state); }
void BM_ActiveSet_Stance(benchmark::State& state) { run_stance_only<ActiveSetContactQp>(state); }
void BM_ActiveSet_GaitWarm(benchmark::State& state) { run<ActiveSetContactQp>(state, true); }
void BM_ActiveSet_GaitCold(benchmark::State& state) { run<ActiveSetContactQp>(state, false); }
void BM_Ceres_Stance(benchmark::State& state) { run_stance_only<CeresContactQp>(state); }
void BM_Ceres_GaitWarm(benchmark::State& state) { run<CeresContactQp>(state, true); }

// Args: {points, reach: 0 = CoP inside, 1 = CoP leaves the polygon}
BENCHMARK(BM_ActiveSet_Stance)->ArgsProduct({{4, 8}, {0, 1}});
BENCHMARK(BM_ActiveSet_GaitWarm)->ArgsProduct({{4, 8}, {0, 1}});
BENCHMARK(BM_ActiveSet_GaitCold)->ArgsProduct({{4, 8}, {0, 1}});
BENCHMARK(BM_Ceres_Stance)->ArgsProduct({{4, 8}, {0, 1}});
BENCHMARK(BM_Ceres_GaitWarm)->ArgsProduct({{4, 8}, {0, 1}});
BENCHMARK(BM_ActiveSet_Latency)->ArgsProduct({{4, 8}, {0, 1}})->Iterations(20);
BENCHMARK(BM_Ceres_Latency)->ArgsProduct({{4, 8}, {0, 1}})->Iterations(3);

} // namespace

BENCHMARK_MAIN();
