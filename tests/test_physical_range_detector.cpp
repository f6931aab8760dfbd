// physical_range_detector: a reading beyond floor - b or ceiling + b is flagged on its own tick,
// b = z m sigma + q / 2 exactly; a healthy reading that sits at the floor for 100 s (seeded) is
// never flagged, nor one whose noise is noise_margin times the calibrated one.

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/physical_range_detector.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::PhysicalRangeDetector> {
  static Json params() { return {{"floor", {0.0}}, {"ceiling", {1000.0}}}; }
  static std::size_t input_dim(std::string_view) { return 3; }
  static void nominal_input(std::string_view, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = 100.0 + 10.0 * static_cast<double>(i);
  }
  static double sample_period_s() { return 1e-3; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(PhysicalRange, PluginContract, ::testing::Types<generic::PhysicalRangeDetector>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::PhysicalRangeDetector;

// One tick of a one-channel detector on reading x: its fault and fault_type.
std::pair<double, double> range_flag(PhysicalRangeDetector& detector, double x) {
  std::vector<double> in{x}, fault(1), type(1);
  const std::span<const double> ins[] = {in};
  const std::span<double> outs[] = {fault, type};
  detector.step(StepIO{0.0, ins, outs});
  return {fault[0], type[0]};
}

TEST(PhysicalRangeDetector, FlagsAReadingBeyondTheBoundOnItsTickAndNotAtIt) {
  PhysicalRangeDetector::Params p;
  p.floor = {0.0};
  p.ceiling = {500.0};
  p.noise_std = {2.0};
  p.resolution = {5.0};
  p.noise_margin = 1.5;
  p.false_alarm_interval_s = 86400.0;
  PhysicalRangeDetector detector(p, StageContext(1e-3, "range", {{"signal", 1}}));
  // b = z m sigma + q / 2, z = -Phi^-1(alpha / 2), alpha = 1e-3 / 86400.
  const double z = -generic::normal_quantile(0.5 * 1e-3 / 86400.0);
  const double b = z * 1.5 * 2.0 + 2.5;
  std::printf("z %.6f, b %.6f N\n", z, b);
  EXPECT_NEAR(z, 5.7058841, 1e-6);  // the one-day quantile at 1 kHz (Python statistics.NormalDist)
  EXPECT_DOUBLE_EQ(detector.lowest(0), -b);
  EXPECT_DOUBLE_EQ(detector.highest(0), 500.0 + b);
  EXPECT_EQ(range_flag(detector, -b).first, 0.0);
  EXPECT_EQ(range_flag(detector, std::nextafter(-b, -1e9)).first, 1.0);
  EXPECT_EQ(range_flag(detector, std::nextafter(-b, -1e9)).second, fault_code(FaultType::unclassified));
  EXPECT_EQ(range_flag(detector, 500.0 + b).first, 0.0);
  EXPECT_EQ(range_flag(detector, std::nextafter(500.0 + b, 1e9)).first, 1.0);
  EXPECT_EQ(range_flag(detector, 250.0).second, fault_code(FaultType::none));
  // A sign flip of a loaded pad reads -L: flagged once L > b.
  EXPECT_EQ(range_flag(detector, -300.0).first, 1.0);
  // Not a number is not this part's to flag (signal_validator's invalid test).
  EXPECT_EQ(range_flag(detector, std::numeric_limits<double>::quiet_NaN()).first, 0.0);
  EXPECT_EQ(range_flag(detector, -std::numeric_limits<double>::infinity()).first, 1.0);
}

TEST(PhysicalRangeDetector, AChannelWithoutABoundIsNeverFlaggedOnThatSide) {
  PhysicalRangeDetector::Params p;
  p.floor = {0.0};
  PhysicalRangeDetector detector(p, StageContext(1e-3, "range", {{"signal", 1}}));
  EXPECT_EQ(detector.highest(0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(range_flag(detector, 1e300).first, 0.0);
  EXPECT_EQ(range_flag(detector, -1e300).first, 1.0);
}

TEST(PhysicalRangeDetector, AHealthyReadingAtTheFloorIsNeverFlagged) {
  // 100 s at 1 kHz of an unloaded pad (load 0) whose noise is sigma, then noise_margin sigma
  // (the calibration a factor off), quantised to 2 N: not one tick flagged. At the bound's
  // quantile the chance of one is 1e5 x 5.8e-9 per run (the floor's side: alpha / 2 a tick).
  constexpr unsigned kSeed = 20261207;
  std::printf("seed %u\n", kSeed);
  for (const double noise_factor : {1.0, 1.5}) {
    PhysicalRangeDetector::Params p;
    p.floor = {0.0};
    p.noise_std = {2.0};
    p.resolution = {2.0};
    PhysicalRangeDetector detector(p, StageContext(1e-3, "range", {{"signal", 1}}));
    std::mt19937_64 rng(kSeed);
    std::normal_distribution<double> noise(0.0, 2.0 * noise_factor);
    int flagged = 0;
    double lowest = 0.0;
    for (int k = 0; k < 100000; ++k) {
      const double x = 2.0 * std::round(noise(rng) / 2.0);
      lowest = std::min(lowest, x);
      flagged += range_flag(detector, x).first == 1.0 ? 1 : 0;
    }
    std::printf("noise x%.1f: lowest reading %.1f N against the bound %.2f N\n", noise_factor, lowest,
                detector.lowest(0));
    EXPECT_EQ(flagged, 0) << "noise x" << noise_factor;
  }
}

TEST(PhysicalRangeDetector, NoBoundOrACeilingNotAboveTheFloorIsAConfigError) {
  Diagnostics d;
  (void)load_params<PhysicalRangeDetector::Params>(Json::parse(R"({"noise_std": [2.0]})"), "/stages/4/params",
                                                   "physical_range_detector", d);
  ASSERT_EQ(d.errors().size(), 1u);
  EXPECT_EQ(d.errors()[0].path, "/stages/4/params/floor");
  EXPECT_NE(d.errors()[0].message.find("neither floor nor ceiling"), std::string::npos);
  PhysicalRangeDetector::Params p;
  p.floor = {0.0, 10.0};
  p.ceiling = {100.0, 10.0};
  EXPECT_THROW(PhysicalRangeDetector(p, StageContext(1e-3, "range", {{"signal", 2}})), ConfigError);
  p.noise_margin = 0.5;
  p.ceiling = {100.0};
  EXPECT_THROW(PhysicalRangeDetector(p, StageContext(1e-3, "range", {{"signal", 2}})), ConfigError);
}

}  // namespace
}  // namespace ftsense
