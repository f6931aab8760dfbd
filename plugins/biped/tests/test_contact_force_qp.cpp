// Why this file is longer than the ~500 lines a file usually holds: every section (KKT property
// tests, brute-force agreement, analytic cases, allocation and iteration limits, the checker
// itself) runs on the same random-problem generators, brute-force oracle and solver adapters of
// its first 250 lines; one file keeps one oracle for the two solvers of the contact-force QP.
#include "ftsense/biped/contact_force_qp.hpp"
#include "ftsense/biped/contact_force_qp_ceres.hpp"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <sstream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

// ---------------------------------------------------------------------------------------------
// Heap allocation counting. operator new is replaced for every build; without AddressSanitizer
// malloc/calloc/realloc are interposed as well (forwarding to glibc), because Eigen allocates
// with malloc, not operator new.
namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
void note_allocation() noexcept {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
}
} // namespace

#if defined(__SANITIZE_ADDRESS__)
#define FTSENSE_TEST_INTERPOSE_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FTSENSE_TEST_INTERPOSE_MALLOC 0
#endif
#endif
#ifndef FTSENSE_TEST_INTERPOSE_MALLOC
#if defined(__GLIBC__)
#define FTSENSE_TEST_INTERPOSE_MALLOC 1
#else
#define FTSENSE_TEST_INTERPOSE_MALLOC 0
#endif
#endif

#if FTSENSE_TEST_INTERPOSE_MALLOC
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void __libc_free(void* pointer);
void* malloc(std::size_t size) {
  note_allocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  note_allocation();
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) {
  note_allocation();
  return __libc_realloc(pointer, size);
}
void free(void* pointer) { __libc_free(pointer); }
}
#endif

namespace {
void* counted_new(std::size_t size) {
  note_allocation();
  if (void* pointer = std::malloc(size == 0 ? 1 : size)) return pointer;
  throw std::bad_alloc();
}
void* counted_aligned_new(std::size_t size, std::align_val_t alignment) {
  note_allocation();
  const auto align = static_cast<std::size_t>(alignment);
  const std::size_t rounded = (std::max<std::size_t>(size, 1) + align - 1) / align * align;
  if (void* pointer = std::aligned_alloc(align, rounded)) return pointer;
  throw std::bad_alloc();
}
} // namespace

void* operator new(std::size_t size) { return counted_new(size); }
void* operator new[](std::size_t size) { return counted_new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return counted_new(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return counted_new(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t size, std::align_val_t alignment) { return counted_aligned_new(size, alignment); }
void* operator new[](std::size_t size, std::align_val_t alignment) { return counted_aligned_new(size, alignment); }
void operator delete(void* pointer) noexcept { std::free(pointer); }
void operator delete[](void* pointer) noexcept { std::free(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { std::free(pointer); }
void operator delete[](void* pointer, std::size_t) noexcept { std::free(pointer); }
void operator delete(void* pointer, std::align_val_t) noexcept { std::free(pointer); }
void operator delete[](void* pointer, std::align_val_t) noexcept { std::free(pointer); }
void operator delete(void* pointer, std::size_t, std::align_val_t) noexcept { std::free(pointer); }
void operator delete[](void* pointer, std::size_t, std::align_val_t) noexcept { std::free(pointer); }

namespace ftsense::biped {
namespace {

constexpr double kKktTolerance = 1e-6;

// ---------------------------------------------------------------------------------------------
// Problem generators (all seeded; the seed is in the test name or SCOPED_TRACE).

ContactGeometry random_convex(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> angles(static_cast<std::size_t>(n));
  for (double& angle : angles) angle = 2.0 * std::numbers::pi * unit(rng);
  std::sort(angles.begin(), angles.end());
  const double ax = 0.10 + 0.05 * unit(rng);
  const double ay = 0.04 + 0.04 * unit(rng);
  const Eigen::Vector2d offset(0.1 * unit(rng) - 0.05, 0.04 * unit(rng) - 0.02); // ankle is not the centre
  ContactGeometry geometry;
  geometry.points.resize(2, n);
  for (int l = 0; l < n; ++l) {
    const double angle = angles[static_cast<std::size_t>(l)];
    geometry.points.col(l) = offset + Eigen::Vector2d(ax * std::cos(angle), ay * std::sin(angle));
  }
  geometry.weights = ContactVector::Constant(n, 0.01);
  return geometry;
}

struct Layout {
  std::string name;
  int n;
  ContactGeometry (*make)(std::mt19937_64&);
};

const std::vector<Layout>& layouts() {
  static const std::vector<Layout> all{
      {"foot_rectangle_4", 4, [](std::mt19937_64&) { return ContactGeometry::rectangle(0.240, 0.150); }},
      {"triangle_3", 3, [](std::mt19937_64& rng) { return random_convex(rng, 3); }},
      {"convex_4", 4, [](std::mt19937_64& rng) { return random_convex(rng, 4); }},
      {"convex_6", 6, [](std::mt19937_64& rng) { return random_convex(rng, 6); }},
      {"convex_8", 8, [](std::mt19937_64& rng) { return random_convex(rng, 8); }},
      {"rectangle_8_edges",
       8,
       [](std::mt19937_64&) {
         ContactGeometry geometry;
         geometry.points.resize(2, 8);
         geometry.points << 0.12, 0.0, -0.12, -0.12, -0.12, 0.0, 0.12, 0.12, //
             0.075, 0.075, 0.075, 0.0, -0.075, -0.075, -0.075, 0.0;
         geometry.weights = ContactVector::Constant(8, 0.01);
         return geometry;
       }},
      {"random_weights_6",
       6,
       [](std::mt19937_64& rng) {
         ContactGeometry geometry = random_convex(rng, 6);
         std::uniform_real_distribution<double> log_weight(-4.0, 0.0);
         for (int l = 0; l < 6; ++l) geometry.weights(l) = std::pow(10.0, log_weight(rng));
         return geometry;
       }},
      {"collinear_4",
       4,
       [](std::mt19937_64&) {
         ContactGeometry geometry;
         geometry.points.resize(2, 4);
         geometry.points << -0.1, 0.0, 0.05, 0.12, 0.0, 0.0, 0.0, 0.0;
         geometry.weights = ContactVector::Constant(4, 0.01);
         return geometry;
       }},
      {"repeated_point_4",
       4,
       [](std::mt19937_64&) {
         ContactGeometry geometry = ContactGeometry::rectangle(0.24, 0.15);
         geometry.points.col(3) = geometry.points.col(0);
         return geometry;
       }},
      {"tiny_weight_4", 4, [](std::mt19937_64&) { return ContactGeometry::rectangle(0.240, 0.150, 1e-7); }},
  };
  return all;
}

struct Load {
  double fz;
  Eigen::Vector2d cop;
};

Load random_load(std::mt19937_64& rng, const ContactGeometry& geometry) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Load load{};
  const double kind = unit(rng);
  load.fz = kind < 0.02 ? 0.0 : 2000.0 * unit(rng);
  if (unit(rng) < 0.5) { // inside: random convex combination of the points
    Eigen::VectorXd weights(geometry.size());
    for (int l = 0; l < geometry.size(); ++l) weights(l) = -std::log(1.0 - unit(rng));
    load.cop = geometry.points * (weights / weights.sum());
  } else { // mostly outside: up to ~4 foot lengths away
    load.cop = Eigen::Vector2d(unit(rng) - 0.5, unit(rng) - 0.5) * (unit(rng) < 0.7 ? 0.6 : 2.0);
  }
  return load;
}

std::string describe(const ContactQpProblem& problem, const ContactQpSolution& solution) {
  std::ostringstream os;
  os.precision(17);
  os << "points=\n"
     << problem.geometry.points << "\nweights=" << problem.geometry.weights.transpose() << "\nfz=" << problem.fz
     << " cop=" << problem.cop.transpose() << "\nstatus=" << to_string(solution.status)
     << " iterations=" << solution.iterations << " forces=" << solution.forces.transpose();
  return os.str();
}

// ---------------------------------------------------------------------------------------------
// KKT property tests, one harness for both solvers.

enum class SolverKind { active_set, ceres };

struct PropertyCase {
  SolverKind solver;
  std::size_t layout;
  std::uint64_t seed;
  int problems;
};

std::string case_name(const testing::TestParamInfo<PropertyCase>& info) {
  return std::string(info.param.solver == SolverKind::active_set ? "active_set_" : "ceres_") +
         layouts()[info.param.layout].name + "_seed" + std::to_string(info.param.seed);
}

std::unique_ptr<ContactForceQpSolver> make_solver(SolverKind kind, const ContactGeometry& geometry) {
  if (kind == SolverKind::active_set) return std::make_unique<ActiveSetContactQp>(geometry);
  return std::make_unique<CeresContactQp>(geometry);
}

std::vector<PropertyCase> property_cases() {
  std::vector<PropertyCase> cases;
  for (std::size_t layout = 0; layout < layouts().size(); ++layout) {
    for (std::uint64_t seed : {11U, 12U}) {
      cases.push_back({SolverKind::active_set, layout, seed + 100 * layout, 1000});
      cases.push_back({SolverKind::ceres, layout, seed + 100 * layout, 500});
    }
  }
  return cases;
}

class ContactQpKktProperty : public testing::TestWithParam<PropertyCase> {};

TEST_P(ContactQpKktProperty, RandomProblemsSatisfyKkt) {
  const PropertyCase& param = GetParam();
  std::mt19937_64 rng(param.seed);
  const Layout& layout = layouts()[param.layout];
  // A new geometry every 50 problems; the solver sees a load sequence that jumps (worst case for
  // warm starting).
  std::unique_ptr<ContactForceQpSolver> solver;
  int optimal = 0;
  for (int i = 0; i < param.problems; ++i) {
    if (i % 50 == 0) solver = make_solver(param.solver, layout.make(rng));
    const Load load = random_load(rng, solver->geometry());
    ContactQpSolution solution;
    solver->solve(load.fz, load.cop, solution);
    const ContactQpProblem problem = solver->problem(load.fz, load.cop);
    SCOPED_TRACE("seed " + std::to_string(param.seed) + " problem " + std::to_string(i) + "\n" +
                 describe(problem, solution));
    ASSERT_TRUE(solution.ok());
    ASSERT_EQ(solution.forces.size(), layout.n);
    if (load.fz == 0.0) {
      EXPECT_EQ(solution.status, ContactQpStatus::zero_load);
      EXPECT_TRUE(solution.forces.isZero(0.0));
      continue;
    }
    ++optimal;
    EXPECT_EQ(solution.status, ContactQpStatus::optimal);
    const ContactQpKkt independent = check_kkt(problem, solution.forces, kKktTolerance);
    EXPECT_TRUE(independent.satisfied()) << independent.describe();
    const ContactQpKkt reported = check_kkt(problem, solution.forces, solution.sum_multiplier,
                                            solution.bound_multipliers, kKktTolerance);
    EXPECT_TRUE(reported.satisfied()) << reported.describe();
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(optimal, param.problems * 9 / 10);
}

INSTANTIATE_TEST_SUITE_P(Layouts, ContactQpKktProperty, testing::ValuesIn(property_cases()), case_name);

// ---------------------------------------------------------------------------------------------
// Brute-force oracle: enumerate every free set F, solve the equality-constrained QP on F through
// an n x n Cholesky of H_FF (independent of the solvers' 3 x 3 reduction), keep the feasible
// candidate with the lowest objective.

ContactVector brute_force(const ContactQpProblem& problem) {
  const int n = problem.geometry.size();
  const ContactMatrix h = problem.hessian();
  const ContactVector g = problem.linear_term();
  ContactVector best = ContactVector::Zero(n);
  double best_objective = std::numeric_limits<double>::infinity();
  for (std::uint32_t free_mask = 1; free_mask < (1U << n); ++free_mask) {
    std::vector<int> free;
    for (int l = 0; l < n; ++l) {
      if ((free_mask >> l) & 1U) free.push_back(l);
    }
    const int m = static_cast<int>(free.size());
    Eigen::MatrixXd h_ff(m, m);
    Eigen::VectorXd g_f(m);
    for (int i = 0; i < m; ++i) {
      g_f(i) = g(free[static_cast<std::size_t>(i)]);
      for (int j = 0; j < m; ++j) h_ff(i, j) = h(free[static_cast<std::size_t>(i)], free[static_cast<std::size_t>(j)]);
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(h_ff);
    const Eigen::VectorXd u = llt.solve(Eigen::VectorXd::Ones(m)); // x = lambda u - v
    const Eigen::VectorXd v = llt.solve(g_f);
    const double lambda = (problem.fz + v.sum()) / u.sum();
    const Eigen::VectorXd x_f = lambda * u - v;
    if (x_f.minCoeff() < -1e-12 * problem.fz) continue;
    ContactVector x = ContactVector::Zero(n);
    for (int i = 0; i < m; ++i) x(free[static_cast<std::size_t>(i)]) = std::max(x_f(i), 0.0);
    const double objective = problem.objective(x);
    if (objective < best_objective) {
      best_objective = objective;
      best = x;
    }
  }
  return best;
}

TEST(ContactQpSolvers, MatchBruteForceEnumeration) {
  for (std::size_t layout_index = 0; layout_index < layouts().size(); ++layout_index) {
    const std::uint64_t seed = 500 + layout_index;
    std::mt19937_64 rng(seed);
    const Layout& layout = layouts()[layout_index];
    const ContactGeometry geometry = layout.make(rng);
    ActiveSetContactQp active_set(geometry);
    CeresContactQp ceres(geometry);
    for (int i = 0; i < 60; ++i) {
      Load load = random_load(rng, geometry);
      if (load.fz == 0.0) load.fz = 1.0;
      const ContactQpProblem problem = active_set.problem(load.fz, load.cop);
      const ContactVector expected = brute_force(problem);
      ContactQpSolution a;
      ContactQpSolution b;
      active_set.solve(load.fz, load.cop, a);
      ceres.solve(load.fz, load.cop, b);
      SCOPED_TRACE(layout.name + " seed " + std::to_string(seed) + " problem " + std::to_string(i) + "\n" +
                   describe(problem, a) + "\nbrute force=" + std::to_string(expected.sum()));
      // The minimiser is unique (strictly convex), so the forces must agree, not just the objective.
      EXPECT_LE((a.forces - expected).lpNorm<Eigen::Infinity>(), 1e-6 * load.fz) << expected.transpose();
      EXPECT_LE((b.forces - expected).lpNorm<Eigen::Infinity>(), 1e-6 * load.fz) << expected.transpose();
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Cross-check and warm start.

TEST(ContactQpSolvers, AgreeOnRandomProblems) {
  for (std::size_t layout_index = 0; layout_index < layouts().size(); ++layout_index) {
    const std::uint64_t seed = 700 + layout_index;
    std::mt19937_64 rng(seed);
    const Layout& layout = layouts()[layout_index];
    const ContactGeometry geometry = layout.make(rng);
    ActiveSetContactQp active_set(geometry);
    CeresContactQp ceres(geometry);
    for (int i = 0; i < 100; ++i) {
      const Load load = random_load(rng, geometry);
      ContactQpSolution a;
      ContactQpSolution b;
      active_set.solve(load.fz, load.cop, a);
      ceres.solve(load.fz, load.cop, b);
      SCOPED_TRACE(layout.name + " seed " + std::to_string(seed) + " problem " + std::to_string(i) + "\n" +
                   describe(active_set.problem(load.fz, load.cop), a));
      ASSERT_EQ(a.status, b.status);
      EXPECT_LE((a.forces - b.forces).lpNorm<Eigen::Infinity>(), 1e-6 * std::max(1.0, load.fz))
          << "ceres: " << b.forces.transpose();
      EXPECT_NEAR(a.sum_multiplier, b.sum_multiplier, 1e-6 * std::max(1.0, std::abs(a.sum_multiplier)));
    }
  }
}

// Slowly varying 1 kHz load: stance-like Fz and a CoP that sweeps heel to toe and beyond.
std::vector<Load> walking_trajectory(int samples, double cop_amplitude) {
  std::vector<Load> loads;
  for (int k = 0; k < samples; ++k) {
    const double t = 1e-3 * k;
    const double phase = 2.0 * std::numbers::pi * t / 0.8;
    Load load{};
    load.fz = std::max(0.0, 700.0 * std::sin(phase) + 150.0);
    load.cop = Eigen::Vector2d(cop_amplitude * std::cos(phase), 0.4 * cop_amplitude * std::sin(2.0 * phase));
    loads.push_back(load);
  }
  return loads;
}

template <class Solver>
void expect_warm_equals_cold() {
  for (const double amplitude : {0.08, 0.2}) {
    for (const std::size_t layout_index : {std::size_t{0}, std::size_t{4}}) {
      std::mt19937_64 rng(900 + layout_index);
      const ContactGeometry geometry = layouts()[layout_index].make(rng);
      typename Solver::Options cold_options;
      cold_options.warm_start = false;
      Solver warm(geometry);
      Solver cold(geometry, cold_options);
      int warm_iterations = 0;
      int cold_iterations = 0;
      const std::vector<Load> loads = walking_trajectory(Solver::kTestSamples, amplitude);
      for (std::size_t k = 0; k < loads.size(); ++k) {
        ContactQpSolution a;
        ContactQpSolution b;
        warm.solve(loads[k].fz, loads[k].cop, a);
        cold.solve(loads[k].fz, loads[k].cop, b);
        SCOPED_TRACE("layout " + layouts()[layout_index].name + " amplitude " + std::to_string(amplitude) +
                     " sample " + std::to_string(k));
        ASSERT_EQ(a.status, b.status);
        ASSERT_LE((a.forces - b.forces).lpNorm<Eigen::Infinity>(), 1e-9 * std::max(1.0, loads[k].fz));
        warm_iterations += a.iterations;
        cold_iterations += b.iterations;
      }
      EXPECT_LE(warm_iterations, cold_iterations);
    }
  }
}

struct ActiveSetForTest {
  using Options = ActiveSetContactQp::Options;
  static constexpr int kTestSamples = 4000;
  explicit ActiveSetForTest(const ContactGeometry& geometry) : solver(geometry) {}
  ActiveSetForTest(const ContactGeometry& geometry, Options options) : solver(geometry, options) {}
  void solve(double fz, const Eigen::Vector2d& cop, ContactQpSolution& out) noexcept { solver.solve(fz, cop, out); }
  ActiveSetContactQp solver;
};
struct CeresForTest {
  using Options = CeresContactQp::Options;
  static constexpr int kTestSamples = 800;
  explicit CeresForTest(const ContactGeometry& geometry) : solver(geometry) {}
  CeresForTest(const ContactGeometry& geometry, Options options) : solver(geometry, options) {}
  void solve(double fz, const Eigen::Vector2d& cop, ContactQpSolution& out) noexcept { solver.solve(fz, cop, out); }
  CeresContactQp solver;
};

TEST(ActiveSetContactQp, WarmStartGivesSameAnswerAsColdStart) { expect_warm_equals_cold<ActiveSetForTest>(); }
TEST(CeresContactQp, WarmStartGivesSameAnswerAsColdStart) { expect_warm_equals_cold<CeresForTest>(); }

// ---------------------------------------------------------------------------------------------
// Analytic oracles (both solvers).

class ContactQpAnalytic : public testing::TestWithParam<SolverKind> {};

TEST_P(ContactQpAnalytic, SymmetricRectangleInsideMatchesClosedForm) {
  // For a centred symmetric rectangle, K_F is diagonal when all points carry load, giving
  //   N_l = F_z / 4 + F_z r_x x_l / (sum x^2 + w) + F_z r_y y_l / (sum y^2 + w),
  // so C N = d only up to the factor sum x^2 / (sum x^2 + w) (0.85 in x for w = 0.01 m^2).
  for (const double w : {0.01, 1e-9}) {
    const ContactGeometry geometry = ContactGeometry::rectangle(0.240, 0.150, w);
    const double sum_xx = geometry.points.row(0).squaredNorm();
    const double sum_yy = geometry.points.row(1).squaredNorm();
    auto solver = make_solver(GetParam(), geometry);
    for (const Eigen::Vector2d& cop : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.05, -0.02),
                                       Eigen::Vector2d(-0.04, 0.03), Eigen::Vector2d(0.06, 0.02)}) {
      const double fz = 812.5;
      ContactQpSolution solution;
      solver->solve(fz, cop, solution);
      SCOPED_TRACE("w=" + std::to_string(w) + " cop=" + std::to_string(cop.x()) + "," + std::to_string(cop.y()));
      ASSERT_EQ(solution.status, ContactQpStatus::optimal);
      ContactVector expected(4);
      for (int l = 0; l < 4; ++l) {
        expected(l) = fz / 4 + fz * cop.x() * geometry.points(0, l) / (sum_xx + w) +
                      fz * cop.y() * geometry.points(1, l) / (sum_yy + w);
      }
      ASSERT_GE(expected.minCoeff(), 0.0); // the closed form assumes no point is unloaded
      EXPECT_LE((solution.forces - expected).lpNorm<Eigen::Infinity>(), 1e-9 * fz);
      EXPECT_NEAR(solution.forces.sum(), fz, 1e-9 * fz);
      const Eigen::Vector2d moment = geometry.points * solution.forces;
      EXPECT_NEAR(moment.x(), fz * cop.x() * sum_xx / (sum_xx + w), 1e-9 * fz);
      EXPECT_NEAR(moment.y(), fz * cop.y() * sum_yy / (sum_yy + w), 1e-9 * fz);
      if (w < 1e-6) { // W -> 0: the moment equations are met (to O(w / sum x^2) = 1e-7 relative)
        EXPECT_LE((moment - fz * cop).norm(), 1e-6 * fz);
      }
    }
  }
}

TEST_P(ContactQpAnalytic, CopInsideMeetsMomentsAsWeightVanishes) {
  // r inside the polygon => some N* >= 0 with 1^T N* = F_z and C N* = d exists (|N*| <= F_z), so the
  // optimum satisfies ||C N - d||^2 <= ||C N - d||^2 + N^T W N <= w |N*|^2, i.e.
  // ||C N - d|| <= sqrt(w) F_z, even where the unconstrained split would pull on a corner.
  for (const double w : {1e-6, 1e-9, 1e-12}) {
    const ContactGeometry geometry = ContactGeometry::rectangle(0.240, 0.150, w);
    auto solver = make_solver(GetParam(), geometry);
    for (const Eigen::Vector2d& cop : {Eigen::Vector2d(-0.09, 0.05), Eigen::Vector2d(0.115, 0.07),
                                       Eigen::Vector2d(0.0, -0.07), Eigen::Vector2d(0.02, 0.01)}) {
      const double fz = 900.0;
      ContactQpSolution solution;
      solver->solve(fz, cop, solution);
      SCOPED_TRACE("w=" + std::to_string(w) + " cop=" + std::to_string(cop.x()) + "," + std::to_string(cop.y()));
      ASSERT_EQ(solution.status, ContactQpStatus::optimal);
      EXPECT_NEAR(solution.forces.sum(), fz, 1e-9 * fz);
      EXPECT_GE(solution.forces.minCoeff(), 0.0);
      EXPECT_LE((geometry.points * solution.forces - fz * cop).norm(), std::sqrt(w) * fz);
    }
  }
}

TEST_P(ContactQpAnalytic, CopFarBeyondCornerLoadsThatCornerOnly) {
  // With only corner c loaded (N = F_z e_c): mu_l = 2 F_z ((c_l - c)^T (c - r) - w) for l != c,
  // positive for r = k c once k > 1 + w / min_l (|c|^2 - c_l^T c) (= 1.89 here).
  const ContactGeometry geometry = ContactGeometry::rectangle(0.240, 0.150);
  auto solver = make_solver(GetParam(), geometry);
  for (int corner = 0; corner < 4; ++corner) {
    for (const double k : {3.0, 10.0, 1000.0}) {
      const Eigen::Vector2d corner_point = geometry.points.col(corner);
      const Eigen::Vector2d cop = k * corner_point;
      const double fz = 640.0;
      ContactQpSolution solution;
      solver->solve(fz, cop, solution);
      SCOPED_TRACE("corner " + std::to_string(corner) + " k " + std::to_string(k));
      ASSERT_EQ(solution.status, ContactQpStatus::optimal);
      ContactVector expected = ContactVector::Zero(4);
      expected(corner) = fz;
      EXPECT_LE((solution.forces - expected).lpNorm<Eigen::Infinity>(), 1e-9 * fz);
      for (int l = 0; l < 4; ++l) {
        if (l == corner) continue;
        const double mu = 2.0 * fz *
                          ((geometry.points.col(l) - corner_point).dot(corner_point - cop) - geometry.weights(l));
        EXPECT_GT(mu, 0.0);
        EXPECT_NEAR(solution.bound_multipliers(l), mu, 1e-9 * std::abs(mu));
      }
    }
  }
}

TEST_P(ContactQpAnalytic, CopFarAheadSplitsBetweenFrontCorners) {
  const ContactGeometry geometry = ContactGeometry::rectangle(0.240, 0.150);
  auto solver = make_solver(GetParam(), geometry);
  ContactQpSolution solution;
  solver->solve(1000.0, Eigen::Vector2d(1.0, 0.0), solution);
  ASSERT_EQ(solution.status, ContactQpStatus::optimal);
  ContactVector expected(4);
  expected << 500.0, 0.0, 0.0, 500.0; // front-left, rear-left, rear-right, front-right
  EXPECT_LE((solution.forces - expected).lpNorm<Eigen::Infinity>(), 1e-9 * 1000.0) << solution.forces.transpose();
}

TEST_P(ContactQpAnalytic, ZeroLoadGivesZeros) {
  auto solver = make_solver(GetParam(), ContactGeometry::rectangle(0.240, 0.150));
  for (const Eigen::Vector2d& cop : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(5.0, -3.0)}) {
    ContactQpSolution solution;
    solver->solve(0.0, cop, solution);
    EXPECT_EQ(solution.status, ContactQpStatus::zero_load);
    EXPECT_TRUE(solution.ok());
    ASSERT_EQ(solution.forces.size(), 4);
    EXPECT_TRUE(solution.forces.isZero(0.0));
    const ContactQpKkt kkt = check_kkt(solver->problem(0.0, cop), solution.forces, kKktTolerance);
    EXPECT_TRUE(kkt.satisfied()) << kkt.describe();
  }
}

TEST_P(ContactQpAnalytic, InvalidInputGivesZerosAndStatus) {
  auto solver = make_solver(GetParam(), ContactGeometry::rectangle(0.240, 0.150));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Load> bad{{nan, {0.0, 0.0}},  {500.0, {nan, 0.0}},     {500.0, {0.0, nan}},
                              {inf, {0.0, 0.0}},  {500.0, {inf, 0.0}},     {-1.0, {0.0, 0.0}},
                              {-1e-12, {0.0, 0.0}}, {1e300, {1e300, 0.0}}, {-inf, {0.0, 0.0}}};
  for (const Load& load : bad) {
    ContactQpSolution solution;
    solution.forces = ContactVector::Constant(4, nan); // must be overwritten
    solver->solve(load.fz, load.cop, solution);
    SCOPED_TRACE("fz=" + std::to_string(load.fz) + " cop=" + std::to_string(load.cop.x()) + "," +
                 std::to_string(load.cop.y()));
    EXPECT_EQ(solution.status, ContactQpStatus::invalid_input);
    EXPECT_FALSE(solution.ok());
    ASSERT_EQ(solution.forces.size(), 4);
    EXPECT_TRUE(solution.forces.isZero(0.0));
    EXPECT_TRUE(solution.bound_multipliers.allFinite());
    EXPECT_TRUE(std::isfinite(solution.sum_multiplier));
  }
  // A bad sample does not poison the next one.
  ContactQpSolution solution;
  solver->solve(400.0, Eigen::Vector2d(0.01, 0.0), solution);
  EXPECT_EQ(solution.status, ContactQpStatus::optimal);
}

TEST_P(ContactQpAnalytic, ExtremeButValidLoadsStayAccurate) {
  auto solver = make_solver(GetParam(), ContactGeometry::rectangle(0.240, 0.150));
  for (const double fz : {1e-300, 1e-9, 1.0, 1e6, 1e12}) {
    for (const Eigen::Vector2d& cop : {Eigen::Vector2d(0.03, 0.01), Eigen::Vector2d(-0.7, 0.4)}) {
      ContactQpSolution solution;
      solver->solve(fz, cop, solution);
      SCOPED_TRACE("fz=" + std::to_string(fz));
      ASSERT_EQ(solution.status, ContactQpStatus::optimal);
      // The problem is homogeneous in F_z: compare with the F_z = 1 solution scaled.
      ContactQpSolution unit;
      solver->solve(1.0, cop, unit);
      EXPECT_LE((solution.forces / fz - unit.forces).lpNorm<Eigen::Infinity>(), 1e-12);
    }
  }
}

TEST_P(ContactQpAnalytic, SinglePointAndTwoPoints) {
  ContactGeometry one;
  one.points.resize(2, 1);
  one.points << 0.05, 0.0;
  one.weights = ContactVector::Constant(1, 0.01);
  ContactQpSolution solution;
  make_solver(GetParam(), one)->solve(300.0, Eigen::Vector2d(-1.0, 2.0), solution);
  ASSERT_EQ(solution.status, ContactQpStatus::optimal);
  EXPECT_DOUBLE_EQ(solution.forces(0), 300.0);

  ContactGeometry two;
  two.points.resize(2, 2);
  two.points << 0.1, -0.1, 0.0, 0.0;
  two.weights = ContactVector::Constant(2, 0.01);
  // Unconstrained split along the segment: N_1 - N_2 = 2 F_z r_x * 0.1 / (2 * 0.01 + 0.01)...
  // checked by KKT instead, plus the clamp beyond the end.
  auto solver = make_solver(GetParam(), two);
  solver->solve(300.0, Eigen::Vector2d(0.02, 0.0), solution);
  EXPECT_TRUE(check_kkt(solver->problem(300.0, Eigen::Vector2d(0.02, 0.0)), solution.forces, 1e-9).satisfied());
  EXPECT_GT(solution.forces.minCoeff(), 0.0);
  solver->solve(300.0, Eigen::Vector2d(0.5, 0.0), solution);
  EXPECT_NEAR(solution.forces(0), 300.0, 1e-9);
  EXPECT_EQ(solution.forces(1), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Solvers, ContactQpAnalytic, testing::Values(SolverKind::active_set, SolverKind::ceres),
                         [](const testing::TestParamInfo<SolverKind>& info) {
                           return info.param == SolverKind::active_set ? std::string("active_set")
                                                                       : std::string("ceres");
                         });

// ---------------------------------------------------------------------------------------------
// Active-set specifics.

TEST(ActiveSetContactQp, DoesNotAllocateAcross10000Solves) {
  std::mt19937_64 rng(4242);
  ActiveSetContactQp four(ContactGeometry::rectangle(0.240, 0.150));
  ActiveSetContactQp eight(random_convex(rng, 8));
  std::vector<Load> loads = walking_trajectory(5000, 0.2);
  loads.push_back({std::numeric_limits<double>::quiet_NaN(), {0.0, 0.0}});
  loads.push_back({-5.0, {0.0, 0.0}});
  for (int i = 0; i < 100; ++i) loads.push_back(random_load(rng, eight.geometry()));
  ContactQpSolution solution;
  solution.forces.resize(8); // the output object itself is fixed-capacity as well
  double checksum = 0.0;
  int solves = 0;
  g_allocations = 0;
  g_counting = true;
  while (solves < 10000) {
    for (const Load& load : loads) {
      ActiveSetContactQp& solver = (solves % 2 == 0) ? four : eight;
      solver.solve(load.fz, load.cop, solution);
      checksum += solution.forces.sum();
      if (++solves == 10000) break;
    }
  }
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 0);
  EXPECT_TRUE(std::isfinite(checksum));
  // The counter works: operator new is seen, and (without ASan) so is Eigen's malloc.
  g_counting = true;
  std::vector<double> probe(100, 0.0);
  g_counting = false;
  EXPECT_GE(g_allocations.exchange(0), 1);
  EXPECT_EQ(probe.size(), 100U);
#if FTSENSE_TEST_INTERPOSE_MALLOC
  g_counting = true;
  Eigen::VectorXd eigen_probe(100);
  eigen_probe.setZero();
  g_counting = false;
  EXPECT_GE(g_allocations.load(), 1);
  EXPECT_EQ(eigen_probe.sum(), 0.0);
#endif
}

TEST(ActiveSetContactQp, IterationLimitReturnsFeasibleForces) {
  ActiveSetContactQp::Options options;
  options.max_iterations = 1;
  options.warm_start = false;
  ActiveSetContactQp solver(ContactGeometry::rectangle(0.240, 0.150), options);
  ContactQpSolution solution;
  solver.solve(1000.0, Eigen::Vector2d(3.0, 2.0), solution); // needs several iterations cold
  EXPECT_EQ(solution.status, ContactQpStatus::iteration_limit);
  EXPECT_FALSE(solution.ok());
  EXPECT_EQ(solution.iterations, 1);
  EXPECT_GE(solution.forces.minCoeff(), 0.0);
  EXPECT_NEAR(solution.forces.sum(), 1000.0, 1e-9);
}

TEST(ActiveSetContactQp, ColdStartIterationsStayBounded) {
  std::mt19937_64 rng(31337);
  ActiveSetContactQp::Options options;
  options.warm_start = false;
  int worst = 0;
  for (int i = 0; i < 2000; ++i) {
    ActiveSetContactQp solver(random_convex(rng, 8), options);
    const Load load = random_load(rng, solver.geometry());
    ContactQpSolution solution;
    solver.solve(load.fz, load.cop, solution);
    ASSERT_TRUE(solution.ok());
    worst = std::max(worst, solution.iterations);
  }
  EXPECT_LE(worst, 2 * kMaxContactPoints);
}

// ---------------------------------------------------------------------------------------------
// KKT checker, configuration and status names.

TEST(ContactQpKktChecker, DetectsEachKindOfViolation) {
  const ContactGeometry geometry = ContactGeometry::rectangle(0.240, 0.150);
  ActiveSetContactQp solver(geometry);
  const Eigen::Vector2d cop(0.3, 0.0); // rear corners unloaded
  ContactQpSolution solution;
  solver.solve(1000.0, cop, solution);
  const ContactQpProblem problem = solver.problem(1000.0, cop);
  ASSERT_TRUE(check_kkt(problem, solution.forces, 1e-9).satisfied());
  ASSERT_EQ(solution.forces(1), 0.0);

  ContactVector moved = solution.forces; // still feasible, not stationary
  moved(0) += 1.0;
  moved(3) -= 1.0;
  EXPECT_FALSE(check_kkt(problem, moved, kKktTolerance).satisfied());
  EXPECT_GT(check_kkt(problem, moved, kKktTolerance).stationarity, kKktTolerance);

  ContactVector infeasible_sum = solution.forces;
  infeasible_sum(0) += 0.01;
  EXPECT_GT(check_kkt(problem, infeasible_sum, kKktTolerance).primal_feasibility, kKktTolerance);

  ContactVector negative = solution.forces; // pull on a rear point, keep the sum
  negative(1) = -0.5;
  negative(0) += 0.5;
  EXPECT_GT(check_kkt(problem, negative, kKktTolerance).primal_feasibility, kKktTolerance);

  ContactVector wrong_mu = solution.bound_multipliers;
  wrong_mu(1) = -wrong_mu(1) - 1.0;
  EXPECT_GT(check_kkt(problem, solution.forces, solution.sum_multiplier, wrong_mu, kKktTolerance).dual_feasibility,
            kKktTolerance);

  ContactVector not_complementary = solution.bound_multipliers; // mu > 0 on a loaded point
  not_complementary(0) = 10.0;
  EXPECT_GT(check_kkt(problem, solution.forces, solution.sum_multiplier, not_complementary, kKktTolerance)
                .complementarity,
            kKktTolerance);

  // Independent multipliers agree with the solver's.
  const ContactQpKkt kkt = check_kkt(problem, solution.forces, kKktTolerance);
  EXPECT_NEAR(kkt.sum_multiplier, solution.sum_multiplier, 1e-9 * std::abs(solution.sum_multiplier));
  EXPECT_LE((kkt.bound_multipliers - solution.bound_multipliers).lpNorm<Eigen::Infinity>(),
            1e-9 * kkt.gradient_scale);

  ContactVector with_nan = solution.forces;
  with_nan(2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(check_kkt(problem, with_nan, kKktTolerance).satisfied());
  EXPECT_THROW(check_kkt(problem, ContactVector::Zero(3), kKktTolerance), std::invalid_argument);
}

TEST(ContactGeometry, ValidationNamesFieldValueAndConstraint) {
  struct BadCase {
    std::string name;
    ContactGeometry geometry;
    std::string message;
  };
  std::vector<BadCase> cases;
  {
    ContactGeometry g;
    g.points.resize(2, 0);
    g.weights.resize(0);
    cases.push_back({"empty", g, "ContactGeometry.points: number of points = 0. Violated constraint: 1 <= n <= 8"});
  }
  {
    ContactGeometry g = ContactGeometry::rectangle(0.24, 0.15);
    g.weights.resize(3);
    g.weights.setConstant(0.01);
    cases.push_back({"weights size", g, "ContactGeometry.weights: size = 3. Violated constraint: == number of points (4)"});
  }
  {
    ContactGeometry g = ContactGeometry::rectangle(0.24, 0.15);
    g.weights(2) = 0.0;
    cases.push_back({"zero weight", g, "ContactGeometry.weights(2) = 0. Violated constraint: 0 < w < inf"});
  }
  {
    ContactGeometry g = ContactGeometry::rectangle(0.24, 0.15);
    g.weights(1) = -0.5;
    cases.push_back({"negative weight", g, "ContactGeometry.weights(1) = -0.5. Violated constraint: 0 < w < inf"});
  }
  {
    ContactGeometry g = ContactGeometry::rectangle(0.24, 0.15);
    g.points(1, 3) = std::numeric_limits<double>::quiet_NaN();
    cases.push_back({"nan point", g, "ContactGeometry.points(1, 3) = nan. Violated constraint: finite"});
  }
  for (const BadCase& bad : cases) {
    SCOPED_TRACE(bad.name);
    for (const SolverKind kind : {SolverKind::active_set, SolverKind::ceres}) {
      try {
        make_solver(kind, bad.geometry);
        ADD_FAILURE() << "no exception";
      } catch (const std::invalid_argument& error) {
        EXPECT_EQ(std::string(error.what()), bad.message);
      }
    }
  }
  ActiveSetContactQp::Options options;
  options.max_iterations = 0;
  EXPECT_THROW(ActiveSetContactQp(ContactGeometry::rectangle(0.24, 0.15), options), std::invalid_argument);
  CeresContactQp::Options ceres_options;
  ceres_options.max_ceres_iterations = 1;
  EXPECT_THROW(CeresContactQp(ContactGeometry::rectangle(0.24, 0.15), ceres_options), std::invalid_argument);
}

TEST(ContactQpStatus, StringRoundTrip) {
  for (const ContactQpStatus status : {ContactQpStatus::optimal, ContactQpStatus::zero_load,
                                       ContactQpStatus::invalid_input, ContactQpStatus::iteration_limit,
                                       ContactQpStatus::solver_failure}) {
    EXPECT_EQ(contact_qp_status_from_string(to_string(status)), status);
  }
  EXPECT_EQ(contact_qp_status_from_string("optimum"), std::nullopt);
  EXPECT_EQ(contact_qp_status_choices(), "optimal, zero_load, invalid_input, iteration_limit, solver_failure");
}

} // namespace
} // namespace ftsense::biped
