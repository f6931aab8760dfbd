// The insole virtual sensor passes ftsense's plugin contract, predicts what its model says, and
// its fit recovers a known model and refuses an ill-conditioned one.

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/pipeline.hpp"
#include "insole/insole_fit.hpp"
#include "insole/insole_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace {
constexpr std::size_t kSensors = 8;
constexpr double kBodyWeightN = 814.23;

// Row j = [a_j, c_jk for k != j]: a_j = 0.01 (j + 1), c_jk = 0.05 k.
std::vector<double> known_coefficients() {
  std::vector<double> c;
  for (std::size_t j = 0; j < kSensors; ++j) {
    c.push_back(0.01 * static_cast<double>(j + 1));
    for (std::size_t k = 0; k < kSensors; ++k) {
      if (k != j) c.push_back(0.05 * static_cast<double>(k));
    }
  }
  return c;
}
}  // namespace

// [snippet:contract_test]
template <>
struct ftsense::testing::ContractSetup<insole::InsoleVirtualSensor> {
  static Json params() {
    return {{"body_weight_N", 814.23}, {"coefficients", std::vector<double>(64, 0.1)}};
  }
  static std::size_t input_dim(std::string_view /*port*/) { return 8; }
  static void nominal_input(std::string_view /*port*/, std::span<double> forces_N) {
    for (std::size_t i = 0; i < forces_N.size(); ++i) forces_N[i] = 50.0 + 10.0 * static_cast<double>(i);
  }
  static double sample_period_s() { return 0.01; }
};

namespace ftsense::testing {
using InsolePlugins = ::testing::Types<insole::InsoleVirtualSensor>;
INSTANTIATE_TYPED_TEST_SUITE_P(Insole, PluginContract, InsolePlugins);
}  // namespace ftsense::testing
// [end-snippet]

namespace {

ftsense::Json pipeline_config(const std::vector<double>& coefficients) {
  std::vector<std::string> columns;
  for (std::size_t k = 0; k < kSensors; ++k) columns.push_back("s" + std::to_string(k + 1));
  return {{"sample_period_s", 0.01},
          {"inputs", {{"foot", {{"columns", columns}, {"unit", "N"}}}}},
          {"stages",
           {{{"name", "model"},
             {"plugin", "insole_virtual_sensor"},
             {"params", {{"body_weight_N", kBodyWeightN}, {"coefficients", coefficients}}},
             {"inputs", {{"measured", "input.foot"}}}},
            {{"name", "smooth"},
             {"plugin", "low_pass"},
             {"inputs", {{"signal", "model.residual"}}}}}}};
}

TEST(InsoleVirtualSensor, PredictsTheModelInStanceAndZeroInSwing) {
  const auto coefficients = known_coefficients();
  auto pipeline = ftsense::Pipeline::build(pipeline_config(coefficients), insole::plugins::registry());
  const auto estimate = pipeline.signal("model.virtual");
  const auto stance = pipeline.signal("model.stance");
  auto foot = pipeline.input_values(0);
  for (std::size_t k = 0; k < kSensors; ++k) foot[k] = 20.0 + 3.0 * static_cast<double>(k);
  pipeline.step(0.0);
  for (std::size_t j = 0; j < kSensors; ++j) {
    double expected = 0.01 * static_cast<double>(j + 1) * kBodyWeightN;
    for (std::size_t k = 0; k < kSensors; ++k) {
      if (k != j) expected += 0.05 * static_cast<double>(k) * foot[k];
    }
    EXPECT_NEAR(pipeline.values(estimate)[j], expected, 1e-9 * std::abs(expected)) << "sensor " << j;
    EXPECT_EQ(pipeline.values(stance)[j], 1.0);
    EXPECT_EQ(pipeline.values(pipeline.signal("model.residual"))[j], foot[j] - pipeline.values(estimate)[j]);
  }
  // Swing: only sensor 0 loaded (one loaded sensor < min_loaded_sensors = 2 for every other one).
  std::fill(foot.begin(), foot.end(), 0.0);
  foot[0] = 300.0;
  pipeline.step(0.01);
  for (std::size_t j = 0; j < kSensors; ++j) {
    EXPECT_EQ(pipeline.values(estimate)[j], 0.0) << "sensor " << j;
    EXPECT_EQ(pipeline.values(stance)[j], 0.0) << "sensor " << j;
  }
}

TEST(InsoleVirtualSensor, NaNInputMakesOnlyTheEstimatesThatNeedItUnavailable) {
  auto pipeline = ftsense::Pipeline::build(pipeline_config(known_coefficients()), insole::plugins::registry());
  auto foot = pipeline.input_values(0);
  std::fill(foot.begin(), foot.end(), 100.0);
  foot[3] = std::nan("");
  pipeline.step(0.0);
  const auto estimate = pipeline.values(pipeline.signal("model.virtual"));
  const auto available = pipeline.values(pipeline.signal("model.available"));
  for (std::size_t j = 0; j < kSensors; ++j) {
    if (j == 3) {  // sensor 3's own estimate does not read sensor 3
      EXPECT_TRUE(std::isfinite(estimate[j]));
      EXPECT_EQ(available[j], 1.0);
    } else {
      EXPECT_TRUE(std::isnan(estimate[j])) << "sensor " << j;
      EXPECT_EQ(available[j], 0.0) << "sensor " << j;
    }
  }
}

TEST(InsoleVirtualSensor, WrongCoefficientCountIsAConfigErrorWithItsPath) {
  try {
    (void)ftsense::Pipeline::build(pipeline_config(std::vector<double>(63, 0.0)), insole::plugins::registry());
    FAIL() << "63 coefficients for 8 sensors were accepted";
  } catch (const ftsense::ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems()[0].path, "/stages/0/params/coefficients");
    EXPECT_NE(e.problems()[0].message.find("expected n x n = 64"), std::string::npos) << e.what();
  }
}

// Stance samples of a foot whose sensor s8 obeys s8 = 0.03 W + sum_k (0.1 + 0.05 k) s_k exactly
// (plus 1e-6 N noise); the fit's row for s8 must recover those numbers.
Eigen::MatrixXd samples_of_known_model(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> load(10.0, 200.0);
  std::normal_distribution<double> noise(0.0, 1e-6);
  Eigen::MatrixXd s(2000, static_cast<Eigen::Index>(kSensors));
  for (Eigen::Index t = 0; t < s.rows(); ++t) {
    double s7 = 0.03 * kBodyWeightN;
    for (Eigen::Index k = 0; k < 7; ++k) {
      s(t, k) = load(rng);
      s7 += (0.1 + 0.05 * static_cast<double>(k)) * s(t, k);
    }
    s(t, 7) = s7 + noise(rng);
  }
  return s;
}

TEST(InsoleFit, RecoversAKnownModel) {
  constexpr std::uint64_t kSeed = 42;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const auto samples = samples_of_known_model(kSeed);
  insole::FitOptions options;
  options.body_weight_N = kBodyWeightN;
  const auto fit = insole::fit_foot(samples, {"s1", "s2", "s3", "s4", "s5", "s6", "s7", "s8"}, options);
  const double* row7 = fit.coefficients.data() + 7 * kSensors;
  EXPECT_NEAR(row7[0], 0.03, 1e-8);
  for (std::size_t k = 0; k < 7; ++k) EXPECT_NEAR(row7[k + 1], 0.1 + 0.05 * static_cast<double>(k), 1e-8);
  EXPECT_LT(fit.rms_error_N[7], 1e-5);
}

TEST(InsoleFit, RefusesCollinearSensorsNamingTheSensor) {
  auto samples = samples_of_known_model(7);
  samples.col(2) = samples.col(1);  // two sensors that always read alike
  insole::FitOptions options;
  options.body_weight_N = kBodyWeightN;
  try {
    (void)insole::fit_foot(samples, {"s1", "s2", "s3", "s4", "s5", "s6", "s7", "s8"}, options);
    FAIL() << "an ill-conditioned fit was accepted";
  } catch (const insole::FitError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor s1 is ill-conditioned"), std::string::npos) << e.what();
  }
}

TEST(InsoleFit, RefusesASensorThatNeverLoads) {
  auto samples = samples_of_known_model(9);
  samples.col(4).setZero();
  insole::FitOptions options;
  options.body_weight_N = kBodyWeightN;
  try {
    (void)insole::fit_foot(samples, {"s1", "s2", "s3", "s4", "s5", "s6", "s7", "s8"}, options);
    FAIL() << "a fit with a dead sensor was accepted";
  } catch (const insole::FitError& e) {
    EXPECT_NE(std::string(e.what()).find("never loads"), std::string::npos) << e.what();
  }
}

}  // namespace
