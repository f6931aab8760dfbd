// still_reading_isolator: a reading stuck at 200 while its load falls at 500 N/s and its
// neighbours take the load over is named frozen on the tick the block that ends its span's
// judgement completes; two still readings, a flag within the span, or the alarm down name nobody.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/still_reading_isolator.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::StillReadingIsolator> {
  static Json params() { return Json::object(); }
  static std::size_t input_dim(std::string_view port) { return port == "sum_residual" ? 1 : 3; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      v[i] = port == "signal" ? 100.0 + 10.0 * static_cast<double>(i) : port == "loadable" ? 1.0 : 0.0;
    }
  }
  static double sample_period_s() { return 1e-3; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(StillReadingIsolator, PluginContract,
                               ::testing::Types<generic::StillReadingIsolator>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::StillReadingIsolator;

// Three loaded channels at 1 kHz. From tick 1000 (t = 1 s) channel 1's load falls at 500 N/s
// while its reading stays at 200 N; channel 0 takes 300 N/s of it and channel 2 200 N/s (0 N/s
// with `third_still`). The reference is the loads' sum, so e = 500 (t - 1) from tick 1000.
struct StillTrace {
  bool third_still = false;
  int flagged_tick = -1;      // channel 0 flagged on this tick
  int alarm_to = 1000000;     // the alarm is up on [1000, alarm_to)
  int ticks = 1300;
};

std::vector<int> run_still_trace(const StillTrace& t) {
  StillReadingIsolator::Params p;  // q = 1, sigma = 1: blocks of 50 ticks, a span of 4 blocks
  StillReadingIsolator iso(p, StageContext(1e-3, "still", {{"signal", 3}, {"sum_residual", 1}}));
  iso.reset();
  std::vector<double> x(3), e(1), alarm(3), loadable(3, 1.0), flagged(3, 0.0), fault(3), type(3);
  const std::span<const double> ins[] = {x, e, alarm, loadable, flagged};
  const std::span<double> outs[] = {fault, type};
  std::vector<int> named;
  for (int k = 0; k < t.ticks; ++k) {
    const double s = k >= 1000 ? (k - 1000) * 1e-3 : 0.0;
    const double l0 = 100.0 + 300.0 * s, l1 = 200.0 - 500.0 * s, l2 = 150.0 + (t.third_still ? 0.0 : 200.0) * s;
    x = {l0, 200.0, l2};
    e[0] = x[0] + x[1] + x[2] - (l0 + l1 + l2);
    for (double& a : alarm) a = k >= 1000 && k < t.alarm_to ? 1.0 : 0.0;
    flagged[0] = k == t.flagged_tick ? 1.0 : 0.0;
    iso.step(StepIO{k * 1e-3, ins, outs});
    int who = -1;
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(type[j], fault_code(fault[j] == 1.0 ? FaultType::frozen : FaultType::none)) << "tick " << k;
      if (fault[j] == 1.0) who = who == -1 ? j : -2;
    }
    named.push_back(who);
  }
  return named;
}

int first_still_named(const std::vector<int>& named) {
  for (std::size_t k = 0; k < named.size(); ++k) {
    if (named[k] != -1) return static_cast<int>(k);
  }
  return -1;
}

TEST(StillReadingIsolator, TheStuckReadingIsNamedWhenItsSpanIsJudgedABlockLater) {
  // The move bound: z sqrt(2 / 0.05) q with z at alpha = 0.05 / 86400 (4.99): 31.6 N. Block 20
  // (ticks 1000-1049) has e's mean 500 x 0.0245 = 12.25, block 21 37.25: the span of blocks
  // 17-21 moved 37.25 N, channel 1 by 0, channel 0 by 22.35 and channel 2 by 14.9 (above a
  // quarter of 37.25). It is judged once block 22 ends, on tick 1149.
  StillReadingIsolator iso(StillReadingIsolator::Params{},
                           StageContext(1e-3, "still", {{"signal", 3}, {"sum_residual", 1}}));
  EXPECT_NEAR(iso.move_bound(0), 31.6, 0.05);
  const std::vector<int> named = run_still_trace(StillTrace{});
  EXPECT_EQ(first_still_named(named), 1149);
  for (int k = 1149; k < 1300; ++k) ASSERT_EQ(named[k], 1) << "tick " << k;
}

TEST(StillReadingIsolator, TwoStillReadingsNameNobody) {
  StillTrace t;
  t.third_still = true;  // channel 2 keeps 150 N: still and loaded beside the stuck one
  EXPECT_EQ(first_still_named(run_still_trace(t)), -1);
}

TEST(StillReadingIsolator, AFlagWithinTheSpanOrTheBlockAfterItHoldsTheJudgement) {
  // Channel 0 flagged on tick 1100 (block 22): every span whose blocks or next block hold 22 is
  // not judged, up to blocks 23-27 with block 28 after them, which ends on tick 1449.
  StillTrace t;
  t.flagged_tick = 1100;
  t.ticks = 1500;
  EXPECT_EQ(first_still_named(run_still_trace(t)), 1449);
}

TEST(StillReadingIsolator, TheNameDropsWithTheAlarm) {
  StillTrace t;
  t.alarm_to = 1200;
  const std::vector<int> named = run_still_trace(t);
  EXPECT_EQ(named[1199], 1);
  for (int k = 1200; k < 1300; ++k) ASSERT_EQ(named[k], -1) << "tick " << k;
}

TEST(StillReadingIsolator, BlocksAndSpanAreTakenToWholeTicksAtAnyRate) {
  // At 333 Hz (T = 3 ms) 0.05 s is 16.7 ticks: blocks of 17 ticks, 0.051 s, and the move bound
  // z sqrt(2 / 0.051) q with z at alpha = 0.051 / 86400, as the other block parts round theirs.
  const StillReadingIsolator iso(StillReadingIsolator::Params{},
                                 StageContext(0.003, "still", {{"signal", 3}, {"sum_residual", 1}}));
  const double z = -generic::normal_quantile(0.5 * 0.051 / 86400.0);
  EXPECT_NEAR(iso.move_bound(0), z * std::sqrt(2.0 / 0.051), 1e-9);
}

}  // namespace
}  // namespace ftsense
