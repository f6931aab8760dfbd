// Generic plugins: the contract suite and analytic oracles.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "ftsense/generic/generic_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
using GenericPluginTypes =
    ::testing::Types<generic::DifferenceResidual, generic::LowPass, generic::ThresholdDetector>;
INSTANTIATE_TYPED_TEST_SUITE_P(Generic, PluginContract, GenericPluginTypes);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using testing::PluginHarness;

TEST(LowPass, StepResponseIsTheExactDiscreteExponential) {
  // From y_0 = 0 and a unit step, y_k = 1 - (1 - a)^k with a = 1 - exp(-2 pi f_c T): after
  // t = k T the response equals the continuous 1 - exp(-t / tau) exactly at the samples.
  generic::LowPass::Params params;
  params.cutoff_hz = 2.0;
  params.start = generic::LowPass::Start::zero;
  constexpr double kT = 1e-3;
  generic::LowPass filter(params, StageContext(kT, "lp", {{"signal", 1}}));
  filter.reset();
  std::vector<double> x{1.0};
  std::vector<double> y{0.0};
  const std::span<const double> ins[] = {x};
  const std::span<double> outs[] = {y};
  StepIO io{0.0, ins, outs};
  const double tau = 1.0 / (2.0 * std::numbers::pi * params.cutoff_hz);
  for (int k = 1; k <= 1000; ++k) {
    filter.step(io);
    EXPECT_NEAR(y[0], 1.0 - std::exp(-k * kT / tau), 1e-12) << "k = " << k;
  }
}

TEST(LowPass, NonFiniteInputHoldsTheState) {
  generic::LowPass::Params params;
  generic::LowPass filter(params, StageContext(1e-3, "lp", {{"signal", 1}}));
  filter.reset();
  std::vector<double> x{5.0};
  std::vector<double> y{0.0};
  const std::span<const double> ins[] = {x};
  const std::span<double> outs[] = {y};
  StepIO io{0.0, ins, outs};
  filter.step(io);
  EXPECT_EQ(y[0], 5.0);  // first sample initialises
  x[0] = std::nan("");
  filter.step(io);
  EXPECT_EQ(y[0], 5.0);
  x[0] = 6.0;
  filter.step(io);
  EXPECT_NEAR(y[0], 5.0 + filter.smoothing_factor(), 1e-15);
}

TEST(ThresholdDetector, OnAndOffDelaysCountTicks) {
  generic::ThresholdDetector::Params params;
  params.thresholds = {1.0};
  params.on_delay_s = 0.003;   // 3 ticks
  params.off_delay_s = 0.002;  // 2 ticks
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 1}}));
  detector.reset();
  std::vector<double> s{0.0};
  std::vector<double> fault{0.0};
  std::vector<double> type{0.0};
  const std::span<const double> ins[] = {s};
  const std::span<double> outs[] = {fault, type};
  StepIO io{0.0, ins, outs};
  const double signal[] = {0, 2, 2, -2, 2, 0, 0, 0, 2, 0};
  const double expected[] = {0, 0, 0, 1, 1, 1, 0, 0, 0, 0};
  for (std::size_t k = 0; k < std::size(signal); ++k) {
    s[0] = signal[k];
    detector.step(io);
    EXPECT_EQ(fault[0], expected[k]) << "tick " << k;
    EXPECT_EQ(type[0], expected[k]) << "tick " << k;  // 1 = unclassified
  }
}

TEST(ThresholdDetector, NonFiniteSignalIsFlaggedInvalidAtOnce) {
  generic::ThresholdDetector::Params params;
  params.thresholds = {1.0, 1.0};
  params.on_delay_s = 1.0;
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 2}}));
  detector.reset();
  std::vector<double> s{std::nan(""), 0.0};
  std::vector<double> fault{0.0, 0.0};
  std::vector<double> type{0.0, 0.0};
  const std::span<const double> ins[] = {s};
  const std::span<double> outs[] = {fault, type};
  detector.step(StepIO{0.0, ins, outs});
  EXPECT_EQ(fault[0], 1.0);
  EXPECT_EQ(type[0], 8.0);
  EXPECT_EQ(fault[1], 0.0);
}

TEST(ThresholdDetector, PerChannelThresholds) {
  generic::ThresholdDetector::Params params;
  params.thresholds = {1.0, 10.0};
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 2}}));
  detector.reset();
  std::vector<double> s{5.0, 5.0};
  std::vector<double> fault{0.0, 0.0};
  std::vector<double> type{0.0, 0.0};
  const std::span<const double> ins[] = {s};
  const std::span<double> outs[] = {fault, type};
  detector.step(StepIO{0.0, ins, outs});
  EXPECT_EQ(fault[0], 1.0);
  EXPECT_EQ(fault[1], 0.0);
}

}  // namespace
}  // namespace ftsense
