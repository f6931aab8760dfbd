// rejoin_detector: a flagged channel whose reading jumps onto its recovered value is called
// rejoined on that exact tick, and on no other: not while the fault goes on (noisy, seeded), not
// for a jump that lands elsewhere, not while unflagged or guarded.

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/generic/rejoin_detector.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::RejoinDetector> {
  static Json params() { return {{"guard", true}, {"residual", true}}; }
  static std::size_t input_dim(std::string_view) { return 3; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = port == "fault" || port == "guard" ? 0.0 : 100.0 + 10.0 * i;
  }
  static double sample_period_s() { return 1e-3; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(Rejoin, PluginContract, ::testing::Types<generic::RejoinDetector>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::RejoinDetector;

constexpr double kRejoinPeriod = 1e-3;

// One channel: the true load moves as a gait's (200 + 100 sin), the reading carries `fault(k)`
// and the noise `noise(k)`, flagged while `flagged(k)`; the recovered value is the reading less
// the estimate `estimate(k)`, fed one tick late as previous_tick does. Returns the ticks rejoined.
struct RejoinChannel {
  RejoinDetector detector;
  // The true load: a gait's by default.
  std::function<double(long)> load_of = [](long k) {
    return 200.0 + 100.0 * std::sin(2.0 * M_PI * static_cast<double>(k) * kRejoinPeriod);
  };
  explicit RejoinChannel(const RejoinDetector::Params& p) : detector(p, StageContext(kRejoinPeriod, "rejoin", {{"signal", 1}})) {
    detector.reset();
  }
  std::vector<long> run(long ticks, const std::function<double(long)>& fault, const std::function<double(long)>& estimate,
                        const std::function<bool(long)>& flagged, const std::function<double(long)>& noise,
                        const std::function<bool(long)>& guarded = [](long) { return false; }) {
    std::vector<long> rejoined;
    double y_before = std::numeric_limits<double>::quiet_NaN(), flag_before = 0.0;
    for (long k = 0; k < ticks; ++k) {
      const double load = load_of(k);
      const double x = load + fault(k) + noise(k);
      const double xs[] = {x}, ys[] = {y_before}, fs[] = {flag_before}, gs[] = {guarded(k) ? 1.0 : 0.0};
      double out[1];
      const std::span<const double> ins[] = {xs, ys, fs, gs};
      const std::span<double> outs[] = {out};
      detector.step(StepIO{static_cast<double>(k) * kRejoinPeriod, ins, outs});
      if (out[0] != 0.0) rejoined.push_back(k);
      y_before = flagged(k) ? x - estimate(k) : x;
      flag_before = flagged(k) ? 1.0 : 0.0;
    }
    return rejoined;
  }
};

RejoinDetector::Params rejoin_params(bool guard = false) {
  RejoinDetector::Params p;
  p.noise_std = {2.0};
  p.guard = guard;
  return p;
}

double no_noise(long) { return 0.0; }

// An offset of 60 from tick 100 to tick 500, flagged from 150 on with its estimate.
double offset_60(long k) { return k >= 100 && k < 500 ? 60.0 : 0.0; }
double offset_60_estimate(long) { return 60.0; }
bool rejoin_flagged_from_150(long k) { return k >= 150; }

TEST(RejoinDetector, TheTickAnOffsetEndsIsTheTickTheReadingRejoins) {
  RejoinChannel channel(rejoin_params());
  EXPECT_EQ(channel.run(1000, offset_60, offset_60_estimate, rejoin_flagged_from_150, no_noise), std::vector<long>{500});
}

// A load that ramps by 60 N a tick, more than the bound: the lines through the last two samples
// must be the right ones (a sample a tick off would miss the line by 60).
TEST(RejoinDetector, ALoadThatRampsFasterThanTheBoundRejoinsOnTheExactTick) {
  RejoinChannel channel(rejoin_params());
  ASSERT_LT(channel.detector.jump_bound(0), 60.0);
  channel.load_of = [](long k) { return 60.0 * static_cast<double>(k); };
  EXPECT_EQ(channel.run(1000, offset_60, offset_60_estimate, rejoin_flagged_from_150, no_noise), std::vector<long>{500});
}

// Flagged from tick 499 only: on tick 500 the channel was not flagged two ticks back, and the
// ticks after hold the jump in their second differences, so nothing is judged to rejoin.
TEST(RejoinDetector, AChannelFlaggedForOneTickOnlyIsNotJudged) {
  RejoinChannel channel(rejoin_params());
  EXPECT_TRUE(channel.run(1000, offset_60, offset_60_estimate, [](long k) { return k >= 499; }, no_noise).empty());
}

TEST(RejoinDetector, AFrozenOutputThatMovesAgainRejoinsItsVirtualValue) {
  // Frozen at 150 from tick 100 to 500; the recovered value is the true load (a virtual sensor).
  RejoinChannel channel(rejoin_params());
  const auto frozen = [](long k) {
    const double load = 200.0 + 100.0 * std::sin(2.0 * M_PI * static_cast<double>(k) * kRejoinPeriod);
    return k >= 100 && k < 500 ? 150.0 - load : 0.0;
  };
  EXPECT_EQ(channel.run(1000, frozen, frozen, rejoin_flagged_from_150, no_noise), std::vector<long>{500});
}

TEST(RejoinDetector, NothingRejoinsUnflaggedGuardedOrElsewhere) {
  {
    RejoinChannel channel(rejoin_params());
    EXPECT_TRUE(channel.run(1000, offset_60, offset_60_estimate, [](long) { return false; }, no_noise).empty());
  }
  {
    RejoinChannel channel(rejoin_params(true));
    EXPECT_TRUE(channel.run(1000, offset_60, offset_60_estimate, rejoin_flagged_from_150, no_noise, [](long k) {
                  return k >= 495 && k < 510;
                }).empty());
  }
  {
    // The reading jumps up by 60 more at 500 instead of back: it lands on no recovered line.
    RejoinChannel channel(rejoin_params());
    const auto doubled = [](long k) { return k >= 100 ? (k < 500 ? 60.0 : 120.0) : 0.0; };
    EXPECT_TRUE(channel.run(1000, doubled, offset_60_estimate, rejoin_flagged_from_150, no_noise).empty());
  }
  {
    // The estimate is half the offset_60: the jump lands 30 off the recovered line, beyond the bound.
    RejoinChannel channel(rejoin_params());
    const double bound = channel.detector.jump_bound(0);
    ASSERT_LT(bound, 30.0);
    EXPECT_TRUE(channel.run(1000, offset_60, [](long) { return 30.0; }, rejoin_flagged_from_150, no_noise).empty());
  }
}

TEST(RejoinDetector, ANoisyFaultThatGoesOnNeverRejoinsAndItsEndDoes) {
  // 100 s of a 60 N offset_60 under white noise of 2 N (seed printed), flagged throughout, ended at
  // 100 s: the bound is z sqrt(6) 2 with z for one false pulse a day, so none before the end.
  const unsigned seed = 20261207;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 2.0);
  std::vector<double> noise(100100);
  for (double& n : noise) n = gauss(rng);
  RejoinChannel channel(rejoin_params());
  const auto rejoined = channel.run(
      100100, [](long k) { return k < 100000 ? 60.0 : 0.0; }, offset_60_estimate, [](long) { return true; },
      [&](long k) { return noise[static_cast<std::size_t>(k)]; });
  EXPECT_EQ(rejoined, std::vector<long>{100000});
}

// With `residual`: the channel's constraint row r (its reading's share of a sum residual) must
// step with the jump. A 60 offset from tick 100 to `end_at`, flagged from 150, estimate 60, the
// load at 200 (its row: the offset alone): its end moves the row by -60 too, and the pulse comes
// W - 1 = 9 ticks after the jump (W = 10 at 1 kHz). The load dropping by 60 at `load_drop_at`
// while the offset goes on (a foot rolling off the pad) lands the reading on the same recovered
// line, but the row stays: no end (without the row, an end on that tick).
struct RowCase {
  bool residual = true;
  long end_at = 500;         // the offset's end (1000: none)
  long load_drop_at = 1000;  // the load's drop by 60 (1000: none)
  long guard_from = 0, guard_to = 0;  // guarded ticks (with a guard wired)
};

std::vector<long> run_with_row(const RowCase& c) {
  RejoinDetector::Params p = rejoin_params(c.guard_to > c.guard_from);
  p.residual = c.residual;
  p.residual_step_std = {1.0};
  RejoinDetector detector(p, StageContext(kRejoinPeriod, "rejoin", {{"signal", 1}}));
  detector.reset();
  std::vector<long> rejoined;
  double y_before = std::numeric_limits<double>::quiet_NaN(), flag_before = 0.0;
  for (long k = 0; k < 1000; ++k) {
    const double load = k >= c.load_drop_at ? 140.0 : 200.0;
    const double fault = k >= 100 && k < c.end_at ? 60.0 : 0.0;
    const double x = load + fault;
    const double xs[] = {x}, ys[] = {y_before}, fs[] = {flag_before}, rs[] = {fault},
                 gs[] = {k >= c.guard_from && k < c.guard_to ? 1.0 : 0.0};
    double out[1];
    std::vector<std::span<const double>> ins{xs, ys, fs};
    if (p.guard) ins.emplace_back(gs);
    if (p.residual) ins.emplace_back(rs);
    const std::span<double> outs[] = {out};
    detector.step(StepIO{static_cast<double>(k) * kRejoinPeriod, ins, outs});
    if (out[0] != 0.0) rejoined.push_back(k);
    const bool flagged = k >= 150;
    y_before = flagged ? x - 60.0 : x;
    flag_before = flagged ? 1.0 : 0.0;
  }
  return rejoined;
}

TEST(RejoinDetector, WithItsRowAJumpIsAnEndOnlyIfTheRowSteppedWithIt) {
  EXPECT_EQ(run_with_row({}), std::vector<long>{509});
  EXPECT_TRUE(run_with_row({.end_at = 1000, .load_drop_at = 500}).empty());
  EXPECT_EQ(run_with_row({.residual = false, .end_at = 1000, .load_drop_at = 500}), std::vector<long>{500});
  EXPECT_EQ(run_with_row({.residual = false}), std::vector<long>{500});
}

TEST(RejoinDetector, WithItsRowEachJumpIsJudgedOnItsOwnWindows) {
  // The load drops on tick 491 (a candidate: the row stays, rejected on tick 500) and the offset
  // ends on tick 500, within the first's window: judged on its own windows, confirmed on 509.
  EXPECT_EQ(run_with_row({.end_at = 500, .load_drop_at = 491}), std::vector<long>{509});
}

TEST(RejoinDetector, WithItsRowAWindowNeedsHalfItsSamplesUnguarded) {
  // A guard over tick 490, the first of the window before the end: nine samples left, confirmed.
  EXPECT_EQ(run_with_row({.guard_from = 490, .guard_to = 491}), std::vector<long>{509});
  // A guard over ticks 490-495: four left of ten, not judged; nor with the whole window guarded.
  EXPECT_TRUE(run_with_row({.guard_from = 490, .guard_to = 496}).empty());
  EXPECT_TRUE(run_with_row({.guard_from = 490, .guard_to = 500}).empty());
}

TEST(RejoinDetector, RejectsAFalseAlarmIntervalOfTwoTicks) {
  RejoinDetector::Params p = rejoin_params();
  p.false_alarm_interval_s = 2.0 * kRejoinPeriod;
  EXPECT_THROW(RejoinDetector(p, StageContext(kRejoinPeriod, "rejoin", {{"signal", 1}})), ConfigError);
}

}  // namespace
}  // namespace ftsense
