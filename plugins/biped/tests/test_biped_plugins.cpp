// Biped plugins: the contract suite and analytic oracles (LIPM convergence, force conservation,
// CoP = moment formula, KKT of the distribution).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <thread>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ftsense/biped/biped_plugins.hpp"
#include "ftsense/biped/cholesky_pivots.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace {
const ftsense::Json kSuralpFoot = ftsense::Json::parse(
    R"([[0.12, 0.075], [0.12, -0.075], [-0.12, 0.075], [-0.12, -0.075]])");
}

namespace ftsense::testing {

template <>
struct ContractSetup<biped::LipmComEstimator> {
  static Json params() { return {{"com_height_m", 0.8}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "imu_acc") v[2] = 9.806;
    if (port == "planned_zmp") v[0] = 0.05;
  }
  static double sample_period_s() { return 1e-3; }
  // Not ready until its CoM variance settles near the steady state (46 ticks at these noises).
  static int settle_ticks() { return 100; }
  // A ZMP farther than z_c from the CoM is physically impossible and dropped (then the CoM is not
  // ready), so the ZMP walks by 1 cm per tick, not by metres.
  static double random_step() { return 0.01; }
};

template <>
struct ContractSetup<biped::LegForceSplit> {
  static Json params() { return {{"mass_kg", 114.0}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "imu_acc") v[2] = 9.806;
    if (port == "com") v[2] = 0.8;
    if (port == "l_foot_pos") v[1] = 0.1;
    if (port == "r_foot_pos") v[1] = -0.1;
    if (port == "contact") v[0] = v[1] = 1.0;
  }
  static double sample_period_s() { return 1e-3; }
  // A CoM may not lean past 45 degrees from a stance foot, so walk the inputs by 1 cm per tick
  // (about 0.13 m over the test): the clamp on alpha is still crossed.
  static double random_step() { return 0.01; }
};

template <>
struct ContractSetup<biped::FootCop> {
  static Json params() { return {{"points", kSuralpFoot}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "com") v[0] = 0.02, v[2] = 0.8;
    if (port == "force") v[2] = 500.0;
  }
  static double sample_period_s() { return 1e-3; }
};

template <>
struct ContractSetup<biped::ContactForceDistribution> {
  static Json params() { return {{"points", kSuralpFoot}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    if (port == "cop") v[0] = 0.03, v[1] = -0.01;
    if (port == "normal_force") v[0] = 600.0;
  }
  static double sample_period_s() { return 1e-3; }
};

template <>
struct ContractSetup<biped::ZmpFromContactForces> {
  static Json params() { return {{"points", kSuralpFoot}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "l_forces" || port == "r_forces") std::fill(v.begin(), v.end(), 140.0);
    if (port == "l_foot_pos") v[1] = 0.1;
    if (port == "r_foot_pos") v[1] = -0.1;
  }
  static double sample_period_s() { return 1e-3; }
};

template <>
struct ContractSetup<biped::ContactForceFdi> {
  static Json params() { return {{"points_per_foot", 4}, {"weight_N", 1118.0}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);  // every pad on the ground
    if (port == "measured") {
      for (std::size_t i = 0; i < v.size(); ++i) v[i] = 120.0 + 3.0 * static_cast<double>(i);
    }
    if (port == "total_force") v[2] = 1044.0;  // the sum of the nominal pads
  }
  static double sample_period_s() { return 1e-3; }
};

template <>
struct ContractSetup<biped::SupportForceDistribution> {
  static Json params() { return Json::object(); }
  static std::size_t input_dim(std::string_view port) {
    if (port == "foot_pos") return 12;  // four feet
    return 0;
  }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "total_force") v[2] = 130.0;  // a 13 kg quadruped
    if (port == "cop") v[0] = 0.02, v[1] = -0.01;
    if (port == "foot_pos") {
      const double corners[4][2] = {{0.2, 0.1}, {0.2, -0.1}, {-0.2, 0.1}, {-0.2, -0.1}};
      for (int i = 0; i < 4; ++i) v[3 * i] = corners[i][0], v[3 * i + 1] = corners[i][1];
    }
    if (port == "contact") std::fill(v.begin(), v.end(), 1.0);
  }
  static double sample_period_s() { return 1e-3; }
  // Positions and forces walk by 1 mm and 1 mN per tick: the ZMP stays inside the support.
  static double random_step() { return 0.001; }
};

template <>
struct ContractSetup<biped::TotalGroundForce> {
  static Json params() { return {{"mass_kg", 13.0}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "imu_acc") v[2] = 9.806;
  }
  static double sample_period_s() { return 1e-3; }
};

template <>
struct ContractSetup<biped::LipmZmp> {
  static Json params() { return {{"com_offset_x_m", 0.002}, {"com_offset_y_m", -0.01}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "total_force") v[2] = 324.0;
    if (port == "com") v[1] = 0.08, v[2] = 0.53;
    if (port == "foot_pos") v[1] = 0.16;  // left foot at y = 0.16, right at the origin
  }
  static double sample_period_s() { return 1e-2; }
};

template <>
struct ContractSetup<biped::LimbInertiaCorrection> {
  static Json params() { return {{"mass_kg", 114.0}, {"leg_effective_mass_kg", 16.0}}; }
  static std::size_t input_dim(std::string_view) { return 0; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "total_force") v[2] = 1118.0;
    if (port == "foot_pos") v[1] = 0.1, v[4] = -0.1;  // two feet
  }
  static double sample_period_s() { return 1e-3; }
  // Positions walk by 1 mm per tick: accelerations of metres per second squared, as a leg's.
  static double random_step() { return 0.001; }
};

using BipedPluginTypes = ::testing::Types<biped::LipmComEstimator, biped::LegForceSplit, biped::FootCop,
                                          biped::ContactForceDistribution, biped::ZmpFromContactForces,
                                          biped::ContactForceFdi, biped::SupportForceDistribution,
                                          biped::TotalGroundForce, biped::LipmZmp, biped::LimbInertiaCorrection>;
INSTANTIATE_TYPED_TEST_SUITE_P(Biped, PluginContract, BipedPluginTypes);

}  // namespace ftsense::testing

namespace ftsense::biped {
namespace {

using testing::PluginHarness;

// A sinusoidal ZMP p = A sin(w t) has the LIPM solution c = A omega0^2 / (omega0^2 + w^2) sin(w t)
// (from c'' = omega0^2 (c - p)). The estimator starts at the ZMP, not at c, and gets the exact
// CoM acceleration (plus noise of the given RMS) as its IMU. Returns the RMS CoM error after 2 s.
double lipm_tracking_rms(double acc_noise_rms, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> acc_noise(0.0, 1.0);
  PluginHarness<LipmComEstimator> h;
  h.plugin().reset();
  const double zc = 0.8, g = 9.806, omega2 = g / zc;
  const double amplitude_x = 0.04, amplitude_y = 0.08, w = 2.0 * std::numbers::pi * 0.6;
  const double ratio = omega2 / (omega2 + w * w);
  double sum_squares = 0.0;
  int count = 0;
  for (int k = 0; k < 6000; ++k) {
    const double t = k * 1e-3;
    const double px = amplitude_x * std::sin(w * t), py = amplitude_y * std::cos(w * t);
    const double cx = ratio * px, cy = ratio * py;
    auto& in = h.inputs();
    in[0] = {-w * w * cx + acc_noise_rms * acc_noise(rng), -w * w * cy + acc_noise_rms * acc_noise(rng), g};
    in[1] = {0.0, 0.0, 0.0};  // level IMU: R = I
    in[2] = {px, py};
    h.step(t);
    const auto& com = h.outputs()[0];
    EXPECT_EQ(com[2], zc);
    if (t > 2.0) {
      sum_squares += std::pow(com[0] - cx, 2) + std::pow(com[1] - cy, 2);
      ++count;
    }
  }
  return std::sqrt(sum_squares / count);
}

TEST(LipmComEstimator, ConvergesOnASyntheticLipmTrajectoryWithKnownZmp) {
  // Noise-free: the model is exact, so the error after convergence is at the 0.1 mm level.
  const double exact = lipm_tracking_rms(0.0, 11);
  std::cout << "noise-free CoM RMS error after 2 s: " << exact * 1000 << " mm\n";
  EXPECT_LT(exact, 1e-4);
  // With 0.2 m/s^2 RMS IMU noise the error is noise-limited (about 2 mm).
  constexpr std::uint64_t kSeed = 11;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const double noisy = lipm_tracking_rms(0.2, kSeed);
  std::cout << "CoM RMS error after 2 s with 0.2 m/s^2 IMU noise: " << noisy * 1000 << " mm\n";
  EXPECT_LT(noisy, 0.004);
}

TEST(LipmComEstimator, TheCovarianceIsExactlySymmetricAfterEveryTick) {
  // Each update ends by P = (P + P^T) / 2. Written in place as one Eigen expression, P^T read
  // entries already written: a P left asymmetric in its last bits by the prediction F P F^T
  // stayed so. A swaying CoM whose ZMP is missing a third of the time (IMU updates alone then),
  // IMU noise from a fixed seed.
  constexpr std::uint64_t kSeed = 9;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  PluginHarness<LipmComEstimator> h;
  h.plugin().reset();
  for (int k = 0; k < 6000; ++k) {
    const double t = k * 1e-3;
    auto& in = h.inputs();
    in[0] = {std::sin(3.0 * t) + 0.1 * noise(rng), std::cos(2.0 * t), 9.806};
    in[1] = {0.0, 0.0, 0.0};
    const bool zmp_missing = (k / 300) % 3 == 0;
    in[2] = {zmp_missing ? std::nan("") : 0.05 * std::sin(3.0 * t),
             zmp_missing ? std::nan("") : ((k / 500) % 2 != 0 ? 0.08 : -0.08)};
    h.step(t);
    for (std::size_t axis = 0; axis < 2; ++axis) {
      const Eigen::Matrix3d& p = h.plugin().covariance(axis);
      ASSERT_TRUE(p == p.transpose()) << "tick " << k << ", axis " << axis << "\n" << p;
    }
  }
}

TEST(LipmComEstimator, ReplayingTheCovarianceRecursionGivesTheRecursionsOwnNumbers) {
  // Two filters on the same inputs: one replays its recorded recursion whenever P is back at the
  // same value, the other is made to run it in full every tick. A swaying CoM whose ZMP is
  // missing for 1 s (P grows, then settles again), absurd ZMP readings on three ticks once P has
  // settled (gated: an update that applied on the recorded tick and not on this one) and IMU
  // noise from a fixed seed. Every output and P must agree to the bit, every tick; and P must have sat at its fixed
  // point (unchanged from the tick before) on many ticks, so the replay was exercised (P settles
  // to the bit some 5 s after a start or a gap).
  constexpr std::uint64_t kSeed = 17;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  PluginHarness<LipmComEstimator> replaying, full;
  replaying.plugin().reset();
  full.plugin().reset();
  int unchanged = 0;
  Eigen::Matrix3d previous = Eigen::Matrix3d::Zero();
  constexpr int kTicks = 30000;
  for (int k = 0; k < kTicks; ++k) {
    const double t = k * 1e-3;
    const double acc = std::sin(3.0 * t) + 0.1 * noise(rng);
    const bool zmp_missing = k >= 15000 && k < 16000;
    const bool absurd = k == 10000 || k == 10001 || k == 25000;
    const double zmp_x = zmp_missing ? std::nan("") : absurd ? 1e6 : 0.05 * std::sin(3.0 * t);
    for (auto* h : {&replaying, &full}) {
      h->inputs()[0] = {acc, std::cos(2.0 * t), 9.806};
      h->inputs()[1] = {0.0, 0.0, 0.0};
      h->inputs()[2] = {zmp_x, zmp_missing ? std::nan("") : 0.08};
    }
    full.plugin().forget_covariance_recursion();
    replaying.step(t);
    full.step(t);
    for (std::size_t port = 0; port < replaying.outputs().size(); ++port) {
      for (std::size_t i = 0; i < replaying.outputs()[port].size(); ++i) {
        const double a = replaying.outputs()[port][i], b = full.outputs()[port][i];
        ASSERT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << "tick " << k << ", port " << port << "[" << i << "]: " << a << " vs " << b;
      }
    }
    for (std::size_t axis = 0; axis < 2; ++axis) {
      ASSERT_TRUE(replaying.plugin().covariance(axis) == full.plugin().covariance(axis)) << "tick " << k << ", axis " << axis;
    }
    unchanged += replaying.plugin().covariance(0) == previous ? 1 : 0;
    previous = replaying.plugin().covariance(0);
  }
  std::printf("P unchanged from the tick before on %d of %d ticks\n", unchanged, kTicks);
  EXPECT_GT(unchanged, 1000);  // 8485 of the 30000
}

TEST(LipmComEstimator, BrokenReadingsAreGatedAndALostFilterRestartsAndSaysSo) {
  PluginHarness<LipmComEstimator> h;
  h.plugin().reset();
  const auto resets = LipmComEstimator::kCovarianceResets;
  const auto com = LipmComEstimator::kCom;
  auto step = [&](double t, double zmp_x, double acc_x = 0.0) {
    h.inputs()[0] = {acc_x, 0.0, 9.806};
    h.inputs()[1] = {0.0, 0.0, 0.0};
    h.inputs()[2] = {zmp_x, -0.02};
    h.step(t);
  };
  for (int k = 0; k < 1000; ++k) step(k * 1e-3, 0.01);
  EXPECT_EQ(h.outputs()[resets], (std::vector<double>{0.0, 0.0}));
  // Absurd readings (a ZMP of +-1e308 m, an acceleration of 1e308 m/s^2) for 50 ticks: dropped by
  // the 100-sigma gate; the CoM stays put, every output finite, nothing restarts.
  for (int k = 0; k < 50; ++k) {
    step(1.0 + k * 1e-3, k % 2 ? 1e308 : -1e308, 1e308);
    for (const auto& out : h.outputs()) {
      for (double v : out) ASSERT_TRUE(std::isfinite(v)) << "tick " << k;
    }
  }
  EXPECT_NEAR(h.outputs()[com][0], 0.01, 1e-3);
  EXPECT_EQ(h.outputs()[resets], (std::vector<double>{0.0, 0.0}));
  // A ZMP that jumps 50 m and stays there: gated at first, then after 200 ticks the filter is
  // judged lost and the x axis restarts on the ZMP (counted once), the y axis untouched.
  for (int k = 0; k < 1000; ++k) step(2.0 + k * 1e-3, 50.0);
  EXPECT_EQ(h.outputs()[resets], (std::vector<double>{1.0, 0.0}));
  EXPECT_NEAR(h.outputs()[com][0], 50.0, 1e-3);
  h.plugin().reset();
  step(10.0, 0.01);
  EXPECT_EQ(h.outputs()[resets], (std::vector<double>{0.0, 0.0}));
}

TEST(LipmComEstimator, SteadyStateVarianceIsTheRiccatiFixedPoint) {
  // Oracle: with every measurement each tick, P(0,0) of the running filter settles on P_inf.
  PluginHarness<LipmComEstimator> h;
  h.plugin().reset();
  for (int k = 0; k < 20000; ++k) {
    h.inputs()[0] = {0.0, 0.0, 9.806};
    h.inputs()[1] = {0.0, 0.0, 0.0};
    h.inputs()[2] = {0.01, -0.02};
    h.step(k * 1e-3);
  }
  const double p_inf = h.plugin().steady_state_com_variance();
  EXPECT_GT(p_inf, 0.0);
  EXPECT_NEAR(h.outputs()[LipmComEstimator::kComVariance][0], p_inf, 1e-6 * p_inf);
  EXPECT_NEAR(h.outputs()[LipmComEstimator::kComVariance][1], p_inf, 1e-6 * p_inf);
}

TEST(CholeskyPivots, AnswerAsEigensLltOnEveryKindOfMatrix) {
  // Oracle: Eigen::LLT itself. Covariances as the filter holds them (positive definite, badly
  // scaled, nearly singular), indefinite and singular ones, and hostile entries (NaN, inf,
  // overflowing and underflowing squares); the upper triangle differs from the lower (only the
  // lower is read).
  constexpr std::uint64_t kSeed = 20261128;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> kind(0, 7);
  std::uniform_int_distribution<int> entry(0, 8);
  const double specials[] = {0.0, -0.0, 1e-300, 1e200, -1e200, std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
  int positive = 0, not_positive = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    Eigen::Matrix3d b;
    for (int i = 0; i < 9; ++i) b(i / 3, i % 3) = unit(rng);
    Eigen::Matrix3d a = b * b.transpose();  // positive semi-definite
    switch (kind(rng)) {
      case 0: break;
      case 1: a += 1e-12 * Eigen::Matrix3d::Identity(); break;
      case 2: a = Eigen::Vector3d(1e-6, 1.0, 1e6).asDiagonal() * a * Eigen::Vector3d(1e-6, 1.0, 1e6).asDiagonal(); break;
      case 3: a(2, 2) -= std::abs(unit(rng)); break;  // often indefinite
      case 4: a.col(2) = a.col(0) + a.col(1); a.row(2) = a.row(0) + a.row(1); break;  // singular
      case 5: a(entry(rng) / 3, entry(rng) % 3) = specials[static_cast<std::size_t>(entry(rng)) % 8]; break;
      case 6: a *= 1e160; break;  // squares overflow
      case 7: a = -a; break;
    }
    a(0, 2) = unit(rng);  // the upper triangle is not read
    const bool eigen = Eigen::LLT<Eigen::Matrix3d>(a).info() == Eigen::Success;
    ASSERT_EQ(cholesky_pivots_positive(a), eigen) << "trial " << trial << "\n" << a;
    (eigen ? positive : not_positive) += 1;
  }
  // Both answers were exercised.
  EXPECT_GT(positive, 50000);
  EXPECT_GT(not_positive, 50000);
}

TEST(LipmComEstimator, WithoutTheZmpTheCoMIsNotReadyAndReacquiresWhenItReturns) {
  // A CoM swaying on the LIPM (as in lipm_tracking_rms); the ZMP goes missing for 3 s.
  PluginHarness<LipmComEstimator> h;
  h.plugin().reset();
  const double zc = 0.8, g = 9.806, omega2 = g / zc, w = 2.0 * std::numbers::pi * 0.6;
  const double ratio = omega2 / (omega2 + w * w);
  const auto ready = [&] { return h.outputs()[LipmComEstimator::kReady][0]; };
  double first_not_ready = -1.0, ready_again = -1.0, worst_error_once_ready = 0.0;
  for (int k = 0; k < 9000; ++k) {
    const double t = k * 1e-3;
    const double px = 0.04 * std::sin(w * t), py = 0.08 * std::cos(w * t);
    const bool zmp_missing = t >= 3.0 && t < 6.0;
    h.inputs()[0] = {-w * w * ratio * px, -w * w * ratio * py, g};
    h.inputs()[1] = {0.0, 0.0, 0.0};
    h.inputs()[2] = {zmp_missing ? std::nan("") : px, zmp_missing ? std::nan("") : py};
    h.step(t);
    const auto& com = h.outputs()[LipmComEstimator::kCom];
    // Not ready and NaN go together, always.
    ASSERT_EQ(ready() == 1.0, std::isfinite(com[0]) && std::isfinite(com[1])) << "t = " << t;
    if (t >= 3.0 && first_not_ready < 0.0 && ready() == 0.0) first_not_ready = t;
    if (t >= 6.0 && ready_again < 0.0 && ready() == 1.0) ready_again = t;
    if (t >= 6.0 && ready() == 1.0) {
      worst_error_once_ready = std::max(worst_error_once_ready, std::hypot(com[0] - ratio * px, com[1] - ratio * py));
    }
  }
  std::cout << "ZMP missing at 3 s: not ready at " << first_not_ready << " s; back at 6 s: ready at " << ready_again
            << " s; worst CoM error once ready: " << worst_error_once_ready * 1000 << " mm\n";
  EXPECT_GT(first_not_ready, 3.0);  // not at once: the IMU carries it for a while
  EXPECT_LT(first_not_ready, 6.0);
  EXPECT_GT(ready_again, 6.0);
  EXPECT_LT(ready_again, 6.2);
  // Re-acquired, not drifted: within a centimetre of the true CoM from the first ready tick.
  EXPECT_LT(worst_error_once_ready, 0.01);
}

TEST(LipmComEstimator, NeverReadyBeforeAFirstZmp) {
  // Even with a ratio so loose that the starting variance is within it, no ZMP means no CoM.
  LipmComEstimator::Params p;
  p.com_height_m = 0.8;
  p.max_com_std_ratio = 100.0;
  LipmComEstimator estimator(p, StageContext(1e-3, "com"));
  std::vector<std::vector<double>> in{{0.0, 0.0, 9.806}, {0.0, 0.0, 0.0}, {std::nan(""), std::nan("")}};
  std::vector<std::vector<double>> out{std::vector<double>(3), std::vector<double>(2), std::vector<double>(2),
                                       std::vector<double>(2), std::vector<double>(2), std::vector<double>(1)};
  std::vector<std::span<const double>> ins(in.begin(), in.end());
  std::vector<std::span<double>> outs(out.begin(), out.end());
  StepIO io;
  io.inputs = ins;
  io.outputs = outs;
  for (int k = 0; k < 100; ++k) {
    io.time_s = k * 1e-3;
    estimator.step(io);
    ASSERT_EQ(out[LipmComEstimator::kReady][0], 0.0) << "tick " << k;
    ASSERT_TRUE(std::isnan(out[LipmComEstimator::kCom][0]));
  }
}

TEST(LipmComEstimator, AZmpFartherThanTheCoMHeightIsDropped) {
  // |c - p| <= z_c (friction mu <= 1): a ZMP 2 m off (z_c = 0.8 m) is dropped, the CoM stays.
  PluginHarness<LipmComEstimator> h;
  h.plugin().reset();
  auto step = [&](double t, double zmp_y) {
    h.inputs()[0] = {0.0, 0.0, 9.806};
    h.inputs()[1] = {0.0, 0.0, 0.0};
    h.inputs()[2] = {0.01, zmp_y};
    h.step(t);
  };
  for (int k = 0; k < 1000; ++k) step(k * 1e-3, 0.0);
  for (int k = 0; k < 150; ++k) step(1.0 + k * 1e-3, 2.0);
  EXPECT_NEAR(h.outputs()[LipmComEstimator::kCom][1], 0.0, 1e-3);
  // 0.7 m off is possible (a hard push), so it is taken.
  for (int k = 0; k < 150; ++k) step(1.15 + k * 1e-3, 0.7);
  EXPECT_GT(h.outputs()[LipmComEstimator::kCom][1], 0.3);
}

TEST(LipmComEstimator, MeasuredZmpSourceRenamesTheInput) {
  LipmComEstimator::Params p;
  p.com_height_m = 0.8;
  p.zmp_source = LipmComEstimator::ZmpSource::measured;
  p.use_kinematic_com = true;
  const LipmComEstimator estimator(p, StageContext(1e-3, "com"));
  EXPECT_TRUE(estimator.ports().find_input("measured_zmp"));
  EXPECT_FALSE(estimator.ports().find_input("planned_zmp"));
  EXPECT_TRUE(estimator.ports().find_input("kinematic_com"));
}

struct SplitCase {
  double c_lat;
  double contact_l, contact_r;
  double expected_alpha;
};

TEST(LegForceSplit, ForcesSumToTheTotalAndFollowAlpha) {
  PluginHarness<LegForceSplit> h;
  h.plugin().reset();
  h.fill_nominal();
  auto& in = h.inputs();
  in[0] = {0.3, -0.2, 10.1};  // a little horizontal acceleration
  in[1] = {0.02, -0.03, 0.4};
  in[3] = {0.0, 0.09, 0.0};
  in[4] = {0.0, -0.09, 0.0};
  const SplitCase cases[] = {{0.0, 1, 1, 0.0}, {0.045, 1, 1, 0.5}, {-0.3, 1, 1, -1.0},
                             {0.0, 1, 0, 1.0}, {0.0, 0, 1, -1.0}};
  // c_lat_max defaults to half the feet's distance (0.09 m) until a single support is seen.
  for (const auto& c : cases) {
    in[2] = {0.01, c.c_lat, 0.8};
    in[5] = {c.contact_l, c.contact_r};
    h.step(0.0);
    const auto& out = h.outputs();
    EXPECT_NEAR(out[3][0], c.expected_alpha, 1e-12) << "c_lat " << c.c_lat;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(out[0][i] + out[1][i], out[2][i], 1e-9);
    // F = m R f: its norm is m |f| (a rotation keeps lengths).
    EXPECT_NEAR(std::hypot(out[2][0], out[2][1], out[2][2]), 114.0 * std::hypot(0.3, -0.2, 10.1), 1e-9);
  }
  // Flight with the IMU in free fall: no ground force to split.
  in[0] = {0.3, -0.2, 0.4};
  in[5] = {0.0, 0.0};
  h.step(0.0);
  EXPECT_EQ(h.outputs()[0][2], 0.0);
  EXPECT_EQ(h.outputs()[1][2], 0.0);
  EXPECT_EQ(h.outputs()[2][2], 0.0);
}

TEST(LegForceSplit, AScheduleOrCoMThePhysicsForbidsMakesItNotReady) {
  PluginHarness<LegForceSplit> h;
  h.plugin().reset();
  h.fill_nominal();
  auto& in = h.inputs();
  const auto all_nan = [&](std::size_t port) {
    return std::all_of(h.outputs()[port].begin(), h.outputs()[port].end(), [](double v) { return std::isnan(v); });
  };
  // The schedule says flight but the IMU reads g (the robot is held): every output NaN. Just
  // below g / 2 it is a fall, just above it the robot is held.
  in[5] = {0.0, 0.0};
  in[0] = {0.0, 0.0, 9.806};
  h.step(0.0);
  EXPECT_TRUE(all_nan(0) && all_nan(1) && all_nan(2));
  in[0] = {0.0, 0.0, 0.49 * 9.806};
  h.step(0.001);
  EXPECT_EQ(h.outputs()[2][2], 0.0);
  in[0] = {0.0, 0.0, 0.51 * 9.806};
  h.step(0.002);
  EXPECT_TRUE(all_nan(2));
  // A stance foot whose line to the CoM (0.8 m up) leans past 45 degrees: the split is unknown,
  // the total is not. The left foot is at y = +0.1, so the CoM at y = 0.9 leans exactly 45 degrees
  // (still possible) and at y = 0.91 beyond.
  in[0] = {0.0, 0.0, 9.806};
  in[5] = {1.0, 0.0};
  in[2] = {0.0, 0.9, 0.8};
  h.step(0.003);
  EXPECT_NEAR(h.outputs()[0][2], 114.0 * 9.806, 1e-9);
  in[2] = {0.0, 0.91, 0.8};
  h.step(0.004);
  EXPECT_TRUE(all_nan(0) && all_nan(1) && all_nan(3));
  EXPECT_NEAR(h.outputs()[2][2], 114.0 * 9.806, 1e-9);
  // In double support a CoM that is not ready (NaN) leaves the split unknown too; in single
  // support the split is +-1 whatever the CoM.
  in[5] = {1.0, 1.0};
  in[2] = {std::nan(""), std::nan(""), 0.8};
  h.step(0.005);
  EXPECT_TRUE(all_nan(0) && all_nan(1));
  EXPECT_NEAR(h.outputs()[2][2], 114.0 * 9.806, 1e-9);
  in[5] = {0.0, 1.0};
  h.step(0.006);
  EXPECT_EQ(h.outputs()[3][0], -1.0);
  EXPECT_NEAR(h.outputs()[1][2], 114.0 * 9.806, 1e-9);
  // An unknown schedule: everything unknown, alpha too.
  in[5] = {std::nan(""), std::nan("")};
  h.step(0.007);
  EXPECT_TRUE(all_nan(0) && all_nan(1) && all_nan(2) && all_nan(3));
}

TEST(LegForceSplit, RecordsTheLateralReachAtSingleSupportOnset) {
  PluginHarness<LegForceSplit> h;
  h.plugin().reset();
  h.fill_nominal();
  auto& in = h.inputs();
  in[2] = {0.0, 0.04, 0.8};
  in[5] = {1.0, 0.0};  // right foot lifts: c_lat = 0.04 is recorded
  h.step(0.0);
  in[5] = {1.0, 1.0};
  in[2] = {0.0, 0.02, 0.8};
  h.step(0.001);
  EXPECT_NEAR(h.outputs()[3][0], 0.5, 1e-12);
}

// The remembered rotation is rotation_from_rpy's, bit for bit, whatever was asked before: angles
// that differ in one angle only (roll, pitch or yaw), in the sign of a zero (sin(-0) = -0) or in
// their last bit are other angles, and a thread of its own starts with a memo of its own.
namespace {
void expect_remembered_rotation_is_the_rotation(const std::array<double, 3>& rpy) {
  const Eigen::Matrix3d built = rotation_from_rpy(rpy);
  const Eigen::Matrix3d remembered = rotation_from_rpy_remembered(rpy);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(std::memcmp(&built(i), &remembered(i), sizeof(double)), 0)
        << "entry " << i << " at roll " << rpy[0] << ", pitch " << rpy[1] << ", yaw " << rpy[2];
  }
}
}  // namespace

TEST(Frames, TheRememberedRotationIsTheRotationBitForBit) {
  const double after_03 = std::nextafter(0.3, 1.0), after_02 = std::nextafter(0.2, 1.0);
  const std::array<std::array<double, 3>, 12> angles{{{0.1, -0.2, 2.5},
                                                      {0.1, -0.2, 2.5},    // the same: remembered
                                                      {0.1, 0.3, 2.5},     // pitch alone differs
                                                      {0.1, 0.3, -1.0},    // yaw alone differs
                                                      {0.0, 0.0, 0.0},
                                                      {-0.0, 0.0, -0.0},   // signs of zeros
                                                      {0.3, 0.0, 0.0},
                                                      {after_03, 0.0, 0.0},  // roll's last bit
                                                      {0.3, 0.2, 0.0},
                                                      {0.3, after_02, 0.0},  // pitch's last bit
                                                      {0.3, 0.0, 0.0},
                                                      {0.3, 0.0, -0.0}}};  // yaw's zero's sign
  for (const auto& rpy : angles) expect_remembered_rotation_is_the_rotation(rpy);
  // -0 and +0 give rotations that differ in a sign bit: the memo must not hand one for the other.
  (void)rotation_from_rpy_remembered(std::array<double, 3>{0.3, 0.0, 0.0});
  EXPECT_TRUE(std::signbit(rotation_from_rpy_remembered(std::array<double, 3>{0.3, 0.0, -0.0})(1, 0)));
  (void)rotation_from_rpy_remembered(std::array<double, 3>{0.0, 0.0, 0.0});
  EXPECT_TRUE(std::signbit(rotation_from_rpy_remembered(std::array<double, 3>{-0.0, 0.0, 0.0})(2, 1)));
  // A new thread's memo starts empty, not at some rotation of zeros; the last angles asked on this
  // thread ({-0, 0, 0}) are no use to it.
  std::thread other([] {
    expect_remembered_rotation_is_the_rotation({0.0, 0.0, 0.0});
    expect_remembered_rotation_is_the_rotation({0.2, -0.1, 1.0});
  });
  other.join();
  expect_remembered_rotation_is_the_rotation({-0.0, 0.0, 0.0});
}

TEST(FootCop, EqualsTheMomentFormulaInsideThePolygon) {
  constexpr std::uint64_t kSeed = 5;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PluginHarness<FootCop> h;
  int inside = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Vector3d c(0.05 * u(rng), 0.05 * u(rng), 0.75 + 0.05 * u(rng));
    const Eigen::Vector3d o(0.02 * u(rng), 0.02 * u(rng), 0.01 * u(rng));
    const Eigen::Vector3d rpy(0.05 * u(rng), 0.05 * u(rng), 0.5 * u(rng));
    const Eigen::Vector3d force(40.0 * u(rng), 40.0 * u(rng), 600.0 + 300.0 * u(rng));
    auto& in = h.inputs();
    in[0] = {c.x(), c.y(), c.z()};
    in[1] = {force.x(), force.y(), force.z()};
    in[2] = {o.x(), o.y(), o.z()};
    in[3] = {rpy.x(), rpy.y(), rpy.z()};
    h.step(0.0);
    const Eigen::Matrix3d rotation = rotation_from_rpy(rpy.x(), rpy.y(), rpy.z());
    const Eigen::Vector3d d = rotation.transpose() * (c - o);
    const Eigen::Vector3d f = rotation.transpose() * force;
    const Eigen::Vector3d moment = d.cross(f);
    const Eigen::Vector2d expected(-moment.y() / f.z(), moment.x() / f.z());
    if (std::abs(expected.x()) < 0.12 && std::abs(expected.y()) < 0.075) {
      ++inside;
      EXPECT_NEAR(h.outputs()[0][0], expected.x(), 1e-12);
      EXPECT_NEAR(h.outputs()[0][1], expected.y(), 1e-12);
      EXPECT_NEAR(h.outputs()[1][0], f.z(), 1e-9);
    } else {
      // Clamped onto the sole's boundary.
      const double x = h.outputs()[0][0], y = h.outputs()[0][1];
      EXPECT_TRUE(std::abs(std::abs(x) - 0.12) < 1e-12 || std::abs(std::abs(y) - 0.075) < 1e-12) << x << ", " << y;
    }
  }
  EXPECT_GT(inside, 500);
}

TEST(FootCop, UnloadedFootHasNoDivision) {
  PluginHarness<FootCop> h;
  h.fill_nominal();
  h.inputs()[1] = {10.0, 0.0, 1e-9};
  h.step(0.0);
  EXPECT_EQ(h.outputs()[0][0], 0.0);  // the centroid
  EXPECT_EQ(h.outputs()[0][1], 0.0);
  EXPECT_EQ(h.outputs()[2][0], 0.0);  // not loaded
}

TEST(ContactForceDistribution, ConservesTheNormalForceAndSatisfiesKkt) {
  constexpr std::uint64_t kSeed = 99;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PluginHarness<ContactForceDistribution> h;
  h.plugin().reset();
  const ContactQpProblem base{ContactGeometry::rectangle(0.24, 0.15, 1e-6), 0.0, Eigen::Vector2d::Zero()};
  for (int trial = 0; trial < 1000; ++trial) {
    const double fz = 1000.0 * (u(rng) + 1.0);
    const Eigen::Vector2d cop(0.15 * u(rng), 0.1 * u(rng));  // inside and outside the sole
    h.inputs()[0] = {cop.x(), cop.y()};
    h.inputs()[1] = {fz};
    h.step(0.0);
    const auto& forces = h.outputs()[0];
    double sum = 0.0;
    for (double f : forces) {
      EXPECT_GE(f, 0.0);
      sum += f;
    }
    EXPECT_NEAR(sum, fz, 1e-9 * std::max(1.0, fz));
    // The plugin's point order (SURALP p1..p4) differs from rectangle(): compare via the KKT check
    // on the plugin's own geometry.
    ContactQpProblem problem = base;
    problem.geometry.points << 0.12, 0.12, -0.12, -0.12, 0.075, -0.075, 0.075, -0.075;
    problem.fz = fz;
    problem.cop = cop;
    const Eigen::VectorXd n = Eigen::Map<const Eigen::VectorXd>(forces.data(), 4);
    const ContactQpKkt kkt = check_kkt(problem, n, 1e-6);
    EXPECT_TRUE(kkt.satisfied()) << kkt.describe();
  }
}

TEST(ContactForceDistribution, DefaultWeightsMeetTheMomentsInsideTheSole) {
  // With W = 1e-6 m^2 the realised CoP sum_l N_l (x_l, y_l) / F_z is within sqrt(w) = 1 mm of
  // the requested one anywhere inside the sole (the paper's 0.01 m^2 would miss by 15-30 %).
  PluginHarness<ContactForceDistribution> h;
  h.plugin().reset();
  const double xs[] = {0.12, 0.12, -0.12, -0.12}, ys[] = {0.075, -0.075, 0.075, -0.075};
  for (double rx : {-0.11, -0.05, 0.0, 0.07, 0.11}) {
    for (double ry : {-0.07, 0.0, 0.03, 0.07}) {
      h.inputs()[0] = {rx, ry};
      h.inputs()[1] = {800.0};
      h.step(0.0);
      double mx = 0.0, my = 0.0;
      for (int l = 0; l < 4; ++l) {
        mx += h.outputs()[0][l] * xs[l];
        my += h.outputs()[0][l] * ys[l];
      }
      EXPECT_NEAR(mx / 800.0, rx, 1e-3) << rx << ", " << ry;
      EXPECT_NEAR(my / 800.0, ry, 1e-3) << rx << ", " << ry;
    }
  }
}

TEST(ContactForceDistribution, WeightsMustMatchThePoints) {
  Diagnostics d;
  (void)load_params<ContactForceDistribution::Params>(
      Json{{"points", kSuralpFoot}, {"weights", {0.01, 0.02}}}, "/stages/5/params", "contact_force_distribution", d);
  ASSERT_EQ(d.errors().size(), 1u);
  EXPECT_EQ(d.errors()[0].path, "/stages/5/params/weights");
}

TEST(ContactForceFdi, WindowsTooLongForTheTickAreConfigErrors) {
  // Found by fuzzing: huge windows overflowed int or asked for gigabytes per channel.
  Diagnostics d;
  (void)load_params<ContactForceFdi::Params>(Json{{"points_per_foot", 4}, {"weight_N", 1118.0}, {"jump_window_s", 1.5e6}},
                                             "/stages/2/params", "contact_force_fdi", d);
  ASSERT_EQ(d.errors().size(), 1u);
  EXPECT_EQ(d.errors()[0].path, "/stages/2/params/jump_window_s");
  ContactForceFdi::Params p;
  p.points_per_foot = 4;
  p.weight_N = 1118.0;
  try {
    const ContactForceFdi fdi(p, StageContext(1e-10, "fdi"));
    FAIL() << "a 1e-10 s tick makes the 0.05 s noise window 5e8 ticks long";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems()[0].path, "/params/noise_window_s");
    EXPECT_NE(e.problems()[0].message.find("at most 100000 ticks"), std::string::npos) << e.what();
  }
  // The airborne mean's fixed 0.02 s is no parameter: the tick is what is too short.
  p.noise_window_s = p.jump_window_s = 1e-4;
  try {
    const ContactForceFdi fdi(p, StageContext(1e-8, "fdi"));
    FAIL() << "a 1e-8 s tick makes the 0.02 s airborne mean 2e6 ticks long";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems()[0].path, "");
    EXPECT_NE(e.problems()[0].message.find("sample period 1e-08 s is too short"), std::string::npos) << e.what();
  }
}

TEST(ZmpFromContactForces, IsTheCentreOfPressureOfAllPads) {
  PluginHarness<ZmpFromContactForces> h;
  h.plugin().reset();
  h.fill_nominal();
  h.step(0.0);
  EXPECT_NEAR(h.outputs()[0][0], 0.0, 1e-12);
  EXPECT_NEAR(h.outputs()[0][1], 0.0, 1e-12);  // symmetric feet at y = +-0.1
  EXPECT_NEAR(h.outputs()[1][0], 8 * 140.0, 1e-9);
  h.inputs()[1] = {0.0, 0.0, 0.0, 0.0};  // right foot unloaded: ZMP at the left foot's centre
  h.step(0.001);
  EXPECT_NEAR(h.outputs()[0][1], 0.1, 1e-12);
}

// lipm_zmp: p = c + (dx, dy) - (c_z - z_g) F_xy / F_z, the ground at the lowest foot.
TEST(LipmZmp, TheForceLineThroughTheComMeetsTheGroundAtTheZmp) {
  PluginHarness<LipmZmp> h;  // offset (0.002, -0.01) m (the contract setup)
  auto& in = h.inputs();
  // CoM 0.55 m above the lower foot (z = -0.02; the other at -0.01), accelerating at
  // a = (1, -2) m/s^2 with F_z = 300 N: p = c + offset - 0.55 (30, -60) / 300.
  in[LipmZmp::kTotalForce] = {30.0, -60.0, 300.0};
  in[LipmZmp::kCom] = {0.10, 0.05, 0.53};
  in[LipmZmp::kFootPos] = {0.0, 0.16, -0.01, 0.2, 0.0, -0.02};
  h.step(0.0);
  EXPECT_DOUBLE_EQ(h.outputs()[LipmZmp::kZmp][0], 0.10 + 0.002 - 0.55 * 0.1);   // 0.047 m
  EXPECT_DOUBLE_EQ(h.outputs()[LipmZmp::kZmp][1], 0.05 - 0.01 + 0.55 * 0.2);    // 0.15 m
  // Standing still (F vertical) the ZMP is the corrected CoM's projection.
  in[LipmZmp::kTotalForce] = {0.0, 0.0, 324.0};
  h.step(0.01);
  EXPECT_DOUBLE_EQ(h.outputs()[LipmZmp::kZmp][0], 0.102);
  EXPECT_DOUBLE_EQ(h.outputs()[LipmZmp::kZmp][1], 0.04);
}

TEST(LipmZmp, NoZmpWithoutAPushOnTheGroundOrAFiniteInput) {
  PluginHarness<LipmZmp> h;  // offset (0.002, -0.01) m
  auto& in = h.inputs();
  in[LipmZmp::kCom] = {0.0, 0.0, 0.5};
  in[LipmZmp::kFootPos] = {0.0, 0.1, 0.0, 0.0, -0.1, 0.0};
  in[LipmZmp::kTotalForce] = {0.0, 0.0, 0.0};  // flight: nothing pushes
  h.step(0.0);
  EXPECT_TRUE(std::isnan(h.outputs()[LipmZmp::kZmp][0]));
  EXPECT_TRUE(std::isnan(h.outputs()[LipmZmp::kZmp][1]));
  in[LipmZmp::kTotalForce] = {0.0, 0.0, 300.0};
  in[LipmZmp::kFootPos][5] = std::numeric_limits<double>::quiet_NaN();  // a foot not known
  h.step(0.01);
  EXPECT_TRUE(std::isnan(h.outputs()[LipmZmp::kZmp][0]));
  in[LipmZmp::kFootPos][5] = 0.0;
  h.step(0.02);
  EXPECT_DOUBLE_EQ(h.outputs()[LipmZmp::kZmp][0], 0.002);  // the corrected CoM's projection
  EXPECT_DOUBLE_EQ(h.outputs()[LipmZmp::kZmp][1], -0.01);
}

// support_force_distribution: N feet. Oracles: the lever rule (2 feet), barycentric coordinates
// (3 feet), symmetry and the KKT conditions of the QP (4 feet), conservation of force always.
struct SupportCase {
  std::vector<std::array<double, 2>> feet;  // (x, y) world, m
  std::vector<double> contact;
  std::array<double, 2> cop;
};

std::vector<double> distribute(const SupportCase& c, double fz) {
  PluginHarness<SupportForceDistribution> h;  // four feet (the contract setup)
  h.plugin().reset();
  h.fill_nominal();
  auto& in = h.inputs();
  for (std::size_t i = 0; i < 4; ++i) {
    in[SupportForceDistribution::kFootPos][3 * i] = i < c.feet.size() ? c.feet[i][0] : 5.0;
    in[SupportForceDistribution::kFootPos][3 * i + 1] = i < c.feet.size() ? c.feet[i][1] : 5.0;
    in[SupportForceDistribution::kContact][i] = i < c.contact.size() ? c.contact[i] : 0.0;
  }
  in[SupportForceDistribution::kTotalForce] = {3.0, -2.0, fz};
  in[SupportForceDistribution::kCop] = {c.cop[0], c.cop[1]};
  h.step(0.0);
  return h.outputs()[SupportForceDistribution::kForces];
}

TEST(SupportForceDistribution, TwoFeetFollowTheLeverRule) {
  // Feet at y = +-0.1, the ZMP at y = 0.04: the lever rule gives f_left = F (0.04 + 0.1) / 0.2 =
  // 0.7 F. Exactly, with f_left = F / 2 + d the QP minimises (0.2 d - 0.04 F)^2 + w (2 d^2 +
  // F^2 / 2), so d = 0.2 * 0.04 F / (0.04 + 2 w): 199.990 N for w = 1e-6 m^2, 0.01 N short of
  // the lever rule.
  const auto f = distribute({{{0.0, 0.1}, {0.0, -0.1}}, {1.0, 1.0}, {0.0, 0.04}}, 1000.0);
  const double d = 0.2 * 0.04 * 1000.0 / (0.04 + 2e-6);
  EXPECT_NEAR(f[0], 500.0 + d, 1e-9);
  EXPECT_NEAR(f[1], 500.0 - d, 1e-9);
  EXPECT_NEAR(f[0], 700.0, 0.011);
  EXPECT_NEAR(f[0] + f[1], 1000.0, 1e-9);
  EXPECT_EQ(f[2], 0.0);  // feet in swing carry nothing
  EXPECT_EQ(f[3], 0.0);
}

TEST(SupportForceDistribution, ThreeFeetTakeBarycentricShares) {
  // Triangle (0,0), (0.4,0), (0,0.3); p = (0.1, 0.075) has barycentric coordinates (0.5, 0.25, 0.25).
  const auto f = distribute({{{0.0, 0.0}, {0.4, 0.0}, {0.0, 0.3}, {9.0, 9.0}}, {1.0, 1.0, 1.0, 0.0}, {0.1, 0.075}}, 200.0);
  EXPECT_NEAR(f[0], 100.0, 0.01);
  EXPECT_NEAR(f[1], 50.0, 0.01);
  EXPECT_NEAR(f[2], 50.0, 0.01);
  EXPECT_EQ(f[3], 0.0);
  EXPECT_NEAR(f[0] + f[1] + f[2], 200.0, 1e-9);
}

TEST(SupportForceDistribution, FourFeetMeetTheMomentAndTheKktConditions) {
  const std::vector<std::array<double, 2>> feet{{10.2, 3.1}, {10.2, 2.9}, {9.8, 3.1}, {9.8, 2.9}};  // far from the origin
  // At the centre: a quarter each (symmetry).
  auto f = distribute({feet, {1, 1, 1, 1}, {10.0, 3.0}}, 130.0);
  for (double v : f) EXPECT_NEAR(v, 32.5, 1e-9);
  // Off-centre: sum, moments (to w / sum x^2 = 1e-6 / 0.2 relative) and the QP's KKT conditions.
  const std::array<double, 2> p{10.07, 2.96};
  f = distribute({feet, {1, 1, 1, 1}, p}, 130.0);
  double sum = 0.0, mx = 0.0, my = 0.0;
  ContactGeometry g;
  g.points.resize(2, 4);
  g.weights.setConstant(4, 1e-6);
  ContactVector forces(4);
  for (int i = 0; i < 4; ++i) {
    sum += f[i];
    mx += f[i] * (feet[i][0] - 10.0);
    my += f[i] * (feet[i][1] - 3.0);
    EXPECT_GE(f[i], 0.0);
    g.points(0, i) = feet[i][0] - 10.0;
    g.points(1, i) = feet[i][1] - 3.0;
    forces(i) = f[i];
  }
  EXPECT_NEAR(sum, 130.0, 1e-9);
  EXPECT_NEAR(mx, 130.0 * 0.07, 130.0 * 0.07 * 1e-4);
  EXPECT_NEAR(my, 130.0 * -0.04, 130.0 * 0.04 * 1e-4);
  const ContactQpKkt kkt = check_kkt(ContactQpProblem{g, 130.0, Eigen::Vector2d(0.07, -0.04)}, forces, 1e-8);
  EXPECT_TRUE(kkt.satisfied()) << kkt.describe();
}

TEST(SupportForceDistribution, OutsideTheSupportTheNearestFootCarriesMost) {
  const auto f = distribute({{{0.0, 0.1}, {0.0, -0.1}}, {1.0, 1.0}, {0.0, 0.5}}, 100.0);
  EXPECT_NEAR(f[0], 100.0, 1e-6);  // all on the left foot, none pulling
  EXPECT_NEAR(f[1], 0.0, 1e-6);
}

TEST(SupportForceDistribution, FlightIsZeroAndUnknownInputsAreNotReady) {
  auto f = distribute({{{0.0, 0.1}, {0.0, -0.1}}, {0.0, 0.0}, {0.0, 0.0}}, 0.0);
  for (double v : f) EXPECT_EQ(v, 0.0);
  f = distribute({{{0.0, 0.1}, {0.0, -0.1}}, {1.0, std::nan("")}, {0.0, 0.0}}, 100.0);
  for (double v : f) EXPECT_TRUE(std::isnan(v));
  f = distribute({{{0.0, 0.1}, {std::nan(""), -0.1}}, {1.0, 1.0}, {0.0, 0.0}}, 100.0);
  for (double v : f) EXPECT_TRUE(std::isnan(v));
  f = distribute({{{0.0, 0.1}, {0.0, -0.1}}, {1.0, 1.0}, {0.0, 0.0}}, -50.0);  // pulled, not pushed
  for (double v : f) EXPECT_TRUE(std::isnan(v));
  // A foot in swing may have no position at all.
  f = distribute({{{0.0, 0.1}, {std::nan(""), -0.1}}, {1.0, 0.0}, {0.0, 0.1}}, 100.0);
  EXPECT_NEAR(f[0], 100.0, 1e-9);
  EXPECT_EQ(f[1], 0.0);
}

TEST(SupportForceDistribution, FeetAreStackedInThreesAndAtMostEight) {
  SupportForceDistribution::Params p;
  EXPECT_THROW(SupportForceDistribution(p, StageContext(1e-3, "s", {{"foot_pos", 7}})), ConfigError);
  EXPECT_THROW(SupportForceDistribution(p, StageContext(1e-3, "s", {{"foot_pos", 27}})), ConfigError);
  const SupportForceDistribution six(p, StageContext(1e-3, "s", {{"foot_pos", 18}}));
  EXPECT_EQ(six.ports().outputs()[0].dim, 6u);
}

}  // namespace
}  // namespace ftsense::biped
