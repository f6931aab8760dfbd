// step_isolator: on three channels that sum to a reference while their loads move, a step on one
// is named on the tick its window completes, with its exact size, and no neighbour is; its end
// re-admits it on the tick that window completes. A reference step, a spike of three ticks, a step towards zero, a step on a row raised
// with no named cause and a step inside a guard name nobody, unless the guard's own move s_g
// is given: then a step inside a guard is named once the guard is over, when the rows moved by its
// jump across it and no other reading jumped with it; a corrected channel's step is not blamed; a step no
// detector confirms is dropped after confirm_s, and a blamed channel is re-admitted on the tick
// its detector falls. window_step_noise: exact steps of small sequences, and sigma sqrt(2 / W)
// for white noise (seed printed). guard_step_noise: exact steps across the guards of a small
// sequence, and the guards it does not count.

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/guard_step_noise.hpp"
#include "ftsense/generic/step_isolator.hpp"
#include "ftsense/generic/window_step_noise.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::StepIsolator> {
  static Json params() { return Json{{"guard", true}}; }
  static std::size_t input_dim(std::string_view) { return 3; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      v[i] = port == "alarm" ? 1.0 : port == "guard" ? 0.0 : 1.0 + 0.25 * static_cast<double>(i);
    }
  }
  static double sample_period_s() { return 1e-3; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(StepIsolation, PluginContract, ::testing::Types<generic::StepIsolator>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::StepIsolator;

constexpr double kStepPeriod = 1e-3;  // W = 10 ticks
constexpr double kSharedLoad = 300.0;

// Three loaded channels that share kSharedLoad, the load swaying between them at 1 Hz (300 N/s at
// most: a window step of up to 3 N in each virtual sensor).
double swaying_load(std::size_t j, int k, double period = kStepPeriod) {
  const double phase = 2.0 * M_PI * 1.0 * k * period + 2.0 * M_PI * static_cast<double>(j) / 3.0;
  return kSharedLoad / 3.0 + 50.0 * std::sin(phase);
}

struct StepTrace {
  std::vector<double> fault_on_channel;  // added to channel j's reading from onset to end
  std::size_t channel = 1;
  int onset = 500;
  int end = 800;
  double size = 30.0;
  double reference_step = 0.0;  // added to the reference from reference_onset
  int reference_onset = 500;
  int guard_from = -1, guard_to = -1;
  int alarm_from = 505, alarm_to = 100000;  // the detector on every row raised on [from, to)
  double shift = 0.0;      // load moved from channel 2 to channel 0 from the onset (the sum keeps it)
  int corrected_from = 100000;  // input correction nonzero on the faulty channel from this tick
  double period = kStepPeriod;  // T: W = round(10 ms / T)
};

struct StepVerdicts {
  std::vector<std::vector<double>> fault, estimate;  // [tick][channel]
};

StepVerdicts run_isolator(const StepTrace& trace, StepIsolator::Params p = {}) {
  p.noise_std = {0.1};
  p.residual_step_std = {0.1};
  p.virtual_step_std = {2.0};
  p.guard = true;
  StepIsolator iso(p, StageContext(trace.period, "step", {{"signal", 3}}));
  iso.reset();
  std::vector<double> x(3), r(3), alarm(3), guard(3), correction(3), fault(3), type(3), estimate(3);
  const std::span<const double> ins[] = {x, r, alarm, guard, correction};
  const std::span<double> outs[] = {fault, type, estimate};
  StepVerdicts out;
  for (int k = 0; k < 1200; ++k) {
    double sum = 0.0;
    for (std::size_t j = 0; j < 3; ++j) {
      x[j] = swaying_load(j, k, trace.period) + (j == trace.channel && k >= trace.onset && k < trace.end ? trace.size : 0.0);
      if (k >= trace.onset) x[j] += j == 0 ? trace.shift : j == 2 ? -trace.shift : 0.0;
      sum += x[j];
      correction[j] = j == trace.channel && k >= trace.corrected_from ? 1.0 : 0.0;
    }
    const double reference = kSharedLoad + (k >= trace.reference_onset ? trace.reference_step : 0.0);
    for (std::size_t j = 0; j < 3; ++j) {
      r[j] = sum - reference;  // every channel loaded: each row is the sum residual
      alarm[j] = k >= trace.alarm_from && k < trace.alarm_to ? 1.0 : 0.0;
      guard[j] = k >= trace.guard_from && k < trace.guard_to ? 1.0 : 0.0;
    }
    iso.step(StepIO{k * trace.period, ins, outs});
    out.fault.push_back(fault);
    out.estimate.push_back(estimate);
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_EQ(type[j], fault_code(fault[j] != 0.0 ? FaultType::unclassified : FaultType::none)) << k;
    }
  }
  return out;
}

int flagged_ticks(const StepVerdicts& r, std::size_t j) {
  int n = 0;
  for (const auto& f : r.fault) n += f[j] != 0.0 ? 1 : 0;
  return n;
}

void expect_nobody_blamed(const StepVerdicts& r) {
  for (std::size_t j = 0; j < 3; ++j) EXPECT_EQ(flagged_ticks(r, j), 0) << "channel " << j;
}

TEST(StepIsolator, WindowIsTenMillisecondsInTicks) {
  EXPECT_EQ(generic::step_window_ticks(0.001), 10u);
  EXPECT_EQ(generic::step_window_ticks(0.002), 5u);
  EXPECT_EQ(generic::step_window_ticks(0.005), 2u);
  EXPECT_EQ(generic::step_window_ticks(0.02), 1u);  // round(0.5) = 1
  EXPECT_EQ(generic::step_window_ticks(0.1), 1u);
  EXPECT_EQ(generic::step_window_ticks(0.0), 1u);
}

TEST(StepIsolator, ALoadedChannelsStepIsNamedWhenItsWindowCompletesAndNoNeighbourIs) {
  // Onset at tick 500: the window after it completes on tick 509, where the sum residual's window
  // step is exactly 30 (0 before, 30 after). The end's step back completes on tick 809.
  const StepVerdicts r = run_isolator(StepTrace{});
  for (int k = 0; k < 1200; ++k) {
    const bool blamed = k >= 509 && k < 809;
    EXPECT_EQ(r.fault[k][1], blamed ? 1.0 : 0.0) << "tick " << k;
    EXPECT_EQ(r.fault[k][0], 0.0) << "tick " << k;
    EXPECT_EQ(r.fault[k][2], 0.0) << "tick " << k;
    if (blamed) {
      EXPECT_NEAR(r.estimate[k][1], 30.0, 1e-9) << "tick " << k;
    }
  }
}

TEST(StepIsolator, ANegativeStepOnAnotherChannelIsNamedAlike) {
  StepTrace t;
  t.channel = 2;
  t.size = -25.0;
  const StepVerdicts r = run_isolator(t);
  EXPECT_EQ(flagged_ticks(r, 2), 300);
  EXPECT_EQ(r.fault[508][2], 0.0);
  EXPECT_EQ(r.fault[509][2], 1.0);
  EXPECT_NEAR(r.estimate[509][2], -25.0, 1e-9);
  EXPECT_EQ(flagged_ticks(r, 0) + flagged_ticks(r, 1), 0);
}

TEST(StepIsolator, ASpikeOfAFewTicksIsNoStep) {
  // Channel 1 reads 100 N high on ticks 500-502 only: the window after it moves by 30 N, as a
  // 30 N step's would, but the reading jumped by 100 N, not by what its row stepped.
  StepTrace t;
  t.size = 100.0;
  t.end = 503;
  expect_nobody_blamed(run_isolator(t));
}

TEST(StepIsolator, AReferenceThatStepsBlamesNoChannel) {
  // Every row's residual and virtual sensor step by the reference's 30 N; no reading does.
  StepTrace t;
  t.size = 0.0;
  t.reference_step = -30.0;
  expect_nobody_blamed(run_isolator(t));
}

TEST(StepIsolator, AStepTowardsZeroBeginsNoFault) {
  // The reference is 30 N low from the start (a fault nobody named holds the rows at +30); channel
  // 1 then steps by -30 N: the rows return to zero, which begins no fault.
  StepTrace t;
  t.size = -30.0;
  t.reference_step = -30.0;
  t.reference_onset = 0;
  t.end = 100000;
  expect_nobody_blamed(run_isolator(t));
}

TEST(StepIsolator, AStepOnARowRaisedWithNoNamedCauseNamesNobody) {
  // The detector is up from the start (a fault nobody named holds the rows): channel 1's step at
  // tick 500 may begin a second fault or end that one, and names nobody.
  StepTrace t;
  t.alarm_from = 0;
  expect_nobody_blamed(run_isolator(t));
}

TEST(StepIsolator, WithJudgeRaisedRowsAStepAwayFromZeroOnARaisedRowIsNamed) {
  // Rows of readings corrected for the faults already found: the alarm up from the start says
  // nothing of the row's level, which is zero, so channel 1's step is named on the tick its window
  // completes, as on a quiet row, and the detector, still up, keeps it until the step back.
  StepTrace t;
  t.alarm_from = 0;
  StepIsolator::Params p;
  p.judge_raised_rows = true;
  const StepVerdicts r = run_isolator(t, p);
  for (int k = 0; k < 1200; ++k) {
    EXPECT_EQ(r.fault[k][1], k >= 509 && k < 809 ? 1.0 : 0.0) << "tick " << k;
    EXPECT_EQ(r.fault[k][0], 0.0) << "tick " << k;
    EXPECT_EQ(r.fault[k][2], 0.0) << "tick " << k;
  }
}

TEST(StepIsolator, AStepInsideAGuardIsNotJudged) {
  // Guarded over ticks 495-514: no judgement rests on them (the isolator needs 20 unguarded ticks),
  // so the onset is not named; the end at 800 is a step towards zero and begins nothing.
  StepTrace t;
  t.guard_from = 495;
  t.guard_to = 515;
  expect_nobody_blamed(run_isolator(t));
}

// Guard step s_g = 1: the bar z s_g is 5.7 (z = 5.70 at one false alarm a day at 1 kHz).
StepIsolator::Params judged_in_guard(double guard_step_std = 1.0) {
  StepIsolator::Params p;
  p.guard_step_std = {guard_step_std};
  return p;
}

TEST(StepIsolator, WithGuardStepStdAStepInsideAGuardIsNamedOnceTheGuardIsOver) {
  // Guarded over ticks 495-514: the step at 500 is the one candidate on tick 509 (its windows
  // complete), and is judged on tick 524, the tenth unguarded tick: the rows moved from 0 (ticks
  // 485-494) to 30 (515-524), its jump. Its end at 800 is named as usual (blamed 524-808).
  StepTrace t;
  t.guard_from = 495;
  t.guard_to = 515;
  const StepVerdicts r = run_isolator(t, judged_in_guard());
  for (int k = 0; k < 1200; ++k) {
    EXPECT_EQ(r.fault[k][1], k >= 524 && k < 809 ? 1.0 : 0.0) << "tick " << k;
    EXPECT_EQ(r.fault[k][0] + r.fault[k][2], 0.0) << "tick " << k;
  }
  EXPECT_NEAR(r.estimate[524][1], 30.0, 1e-9);
}

TEST(StepIsolator, AStepJustBeforeAGuardIsMeasuredFromTheRowBeforeTheStep) {
  // The step at 500, three ticks before the guard (503-519): its windows complete inside the guard
  // (tick 509), and the guard's baseline (493-502) already holds three ticks of it; the move is
  // taken from the row before the step (490-499), so it is named on tick 529 at its full 30 N.
  StepTrace t;
  t.guard_from = 503;
  t.guard_to = 520;
  const StepVerdicts r = run_isolator(t, judged_in_guard());
  EXPECT_EQ(r.fault[528][1], 0.0);
  EXPECT_EQ(r.fault[529][1], 1.0);
  EXPECT_NEAR(r.estimate[529][1], 30.0, 1e-9);
}

TEST(StepIsolator, AStepInsideAGuardIsJudgedAlikeAt200HzAnd50Hz) {
  // At T = 5 ms (W = 2) the step at tick 500 inside the guard (495-514) is named on tick 516, the
  // second unguarded tick, and its end at 800 on tick 801; at T = 20 ms (W = 1) on tick 515 and
  // 800. At 50 Hz the lone-jump rule looks at the step's own tick: 40 N moving from channel 2 to 0
  // on it leaves nobody named.
  for (const double period : {0.005, 0.02}) {
    StepTrace t;
    t.period = period;
    t.guard_from = 495;
    t.guard_to = 515;
    const int first = period == 0.005 ? 516 : 515, last = period == 0.005 ? 801 : 800;
    const StepVerdicts r = run_isolator(t, judged_in_guard());
    for (int k = 0; k < 1200; ++k) {
      EXPECT_EQ(r.fault[k][1], k >= first && k < last ? 1.0 : 0.0) << "T " << period << ", tick " << k;
      EXPECT_EQ(r.fault[k][0] + r.fault[k][2], 0.0) << "T " << period << ", tick " << k;
    }
    t.shift = 40.0;
    expect_nobody_blamed(run_isolator(t, judged_in_guard()));
  }
}

TEST(StepIsolator, AStepInsideAGuardThatEndsThereIsNotNamed) {
  // The step at 500 is back on 510, inside the guard (495-529): the rows did not move across it.
  StepTrace t;
  t.guard_from = 495;
  t.guard_to = 530;
  t.end = 510;
  expect_nobody_blamed(run_isolator(t, judged_in_guard()));
}

TEST(StepIsolator, AMoveAcrossTheGuardOtherThanTheJumpNamesNobody) {
  // s_g = 10: bar 57, and the move may differ from the jump by z sqrt(6 sigma^2 + s_g^2) = 57 but
  // by no more than half the jump. A 70 N step moves the rows by 70: named on tick 544 (guard
  // 495-534). A 30 N step with the reference 30 N lower from tick 515 (inside the guard, after
  // the step's windows) moves them by 60, twice the jump: nobody.
  StepTrace named;
  named.size = 70.0;
  named.guard_from = 495;
  named.guard_to = 535;
  const StepVerdicts r = run_isolator(named, judged_in_guard(10.0));
  EXPECT_EQ(r.fault[543][1], 0.0);
  EXPECT_EQ(r.fault[544][1], 1.0);
  EXPECT_NEAR(r.estimate[544][1], 70.0, 1e-9);
  StepTrace doubled = named;
  doubled.size = 30.0;
  doubled.reference_step = -30.0;
  doubled.reference_onset = 515;
  doubled.end = 100000;
  expect_nobody_blamed(run_isolator(doubled, judged_in_guard(10.0)));
}

TEST(StepIsolator, AStepInsideAGuardBesideAnotherJumpNamesNobody) {
  // 40 N moves from channel 2 to channel 0 on the tick channel 1 steps (a foot's pads trading
  // load): the sum keeps the shift, the rows move by channel 1's 30 N, but three readings jumped.
  StepTrace t;
  t.guard_from = 495;
  t.guard_to = 515;
  t.shift = 40.0;
  expect_nobody_blamed(run_isolator(t, judged_in_guard()));
}

TEST(StepIsolator, ACorrectedChannelsStepIsNotBlamed) {
  // Input correction on channel 1 from tick 0 (a fault already found there): its step at 500,
  // outside a guard or inside one, is that fault changing, and names nobody.
  StepTrace t;
  t.corrected_from = 0;
  StepIsolator::Params p = judged_in_guard();
  p.correction = true;
  expect_nobody_blamed(run_isolator(t, p));
  t.guard_from = 495;
  t.guard_to = 515;
  expect_nobody_blamed(run_isolator(t, p));
  // Without the input, the same trace names it (the test above).
  t.corrected_from = 100000;
  EXPECT_EQ(flagged_ticks(run_isolator(t, p), 1), 809 - 524);
}

TEST(StepIsolator, AStepNoDetectorConfirmsIsDroppedAfterConfirmS) {
  // No alarm ever: blamed on tick 509 for confirm_s = 50 ms, 50 ticks (509-558).
  StepTrace t;
  t.alarm_from = 100000;
  StepIsolator::Params p;
  p.confirm_s = 0.05;
  const StepVerdicts r = run_isolator(t, p);
  for (int k = 0; k < 1200; ++k) {
    EXPECT_EQ(r.fault[k][1], k >= 509 && k < 559 ? 1.0 : 0.0) << "tick " << k;
  }
}

TEST(StepIsolator, ABlamedChannelIsReadmittedOnTheTickItsDetectorFalls) {
  // The detector rises on tick 520 and falls on tick 700: blamed 509-699.
  StepTrace t;
  t.alarm_from = 520;
  t.alarm_to = 700;
  const StepVerdicts r = run_isolator(t);
  for (int k = 0; k < 1200; ++k) {
    EXPECT_EQ(r.fault[k][1], k >= 509 && k < 700 ? 1.0 : 0.0) << "tick " << k;
  }
}

TEST(StepIsolator, AChannelOffTheGroundIsNamedOnItsOwnRow) {
  // Channel 2 in the air (reads 0, its row its own reading): a 20 N step on it is named on tick
  // 509; the loaded rows (channels 0 and 1 share the 300 N) do not move.
  StepIsolator::Params p;
  p.noise_std = {0.1};
  p.residual_step_std = {0.1};
  p.virtual_step_std = {2.0};
  StepIsolator iso(p, StageContext(kStepPeriod, "step", {{"signal", 3}}));
  iso.reset();
  std::vector<double> x(3), r(3), alarm(3, 0.0), fault(3), type(3), estimate(3);
  const std::span<const double> ins[] = {x, r, alarm};
  const std::span<double> outs[] = {fault, type, estimate};
  for (int k = 0; k < 700; ++k) {
    alarm[2] = k >= 505 ? 1.0 : 0.0;  // the detector on channel 2's own row rises after its step
    const double sway = 50.0 * std::sin(2.0 * M_PI * k * kStepPeriod);
    x[0] = 150.0 + sway;
    x[1] = 150.0 - sway;
    x[2] = k >= 500 ? 20.0 : 0.0;
    r[0] = r[1] = x[0] + x[1] - kSharedLoad;
    r[2] = x[2];
    iso.step(StepIO{k * kStepPeriod, ins, outs});
    EXPECT_EQ(fault[2], k >= 509 ? 1.0 : 0.0) << "tick " << k;
    EXPECT_EQ(fault[0] + fault[1], 0.0) << "tick " << k;
  }
  EXPECT_NEAR(estimate[2], 20.0, 1e-12);
}

TEST(WindowStepNoise, StepsOfASmallSequenceAreExact) {
  // T = 5 ms: W = 2, so each step compares the mean of the last two samples with the two before.
  generic::WindowStepNoise w(0.005);
  EXPECT_EQ(w.window_ticks(), 2u);
  for (const double s : {0.0, 0.0, 1.0, 1.0}) w.add(s);
  EXPECT_EQ(w.count(), 1u);  // (1 + 1) / 2 - (0 + 0) / 2 = 1
  EXPECT_DOUBLE_EQ(w.standard_deviation(), 1.0 / 0.6744897501960817);
  w.add(3.0);  // (1 + 3) / 2 - (0 + 1) / 2 = 1.5
  EXPECT_EQ(w.count(), 2u);  // steps 1 and 1.5: an even count's median is their mean
  EXPECT_DOUBLE_EQ(w.standard_deviation(), 1.25 / 0.6744897501960817);
  w.add(std::nan(""));  // breaks the sequence: no window spans it
  for (const double s : {5.0, 5.0, 5.0}) w.add(s);
  EXPECT_EQ(w.count(), 2u);
  w.add(5.0);  // (5 + 5) / 2 - (5 + 5) / 2 = 0
  EXPECT_EQ(w.count(), 3u);
  // Steps 1, 1.5, 0: median 1.
  EXPECT_DOUBLE_EQ(w.standard_deviation(), 1.0 / 0.6744897501960817);
  generic::WindowStepNoise empty(0.001);
  EXPECT_TRUE(std::isnan(empty.standard_deviation()));
}

TEST(GuardStepNoise, StepsAcrossGuardsOfASmallSequenceAreExact) {
  // T = 5 ms: W = 2. Each entry is (sample, guarded).
  generic::GuardStepNoise g(0.005);
  EXPECT_EQ(g.window_ticks(), 2u);
  const auto feed = [&](std::initializer_list<std::pair<double, bool>> samples) {
    for (const auto& [r, guarded] : samples) g.add(r, guarded);
  };
  feed({{0.0, false}, {0.0, false}, {5.0, true}, {7.0, true}, {3.0, false}});
  EXPECT_EQ(g.count(), 0u);  // one tick after the guard so far
  feed({{3.0, false}});      // (3 + 3) / 2 - (0 + 0) / 2 = 3
  EXPECT_EQ(g.count(), 1u);
  EXPECT_DOUBLE_EQ(g.standard_deviation(), 3.0 / 0.6744897501960817);
  // A non-finite sample after a guard breaks it: not counted.
  feed({{1.0, false}, {9.0, true}, {2.0, false}, {std::nan(""), false}});
  EXPECT_EQ(g.count(), 1u);
  // A guard again one tick after the last: neither counts.
  feed({{4.0, false}, {4.0, false}, {0.0, true}, {6.0, false}, {0.0, true}, {8.0, false}, {8.0, false}});
  EXPECT_EQ(g.count(), 1u);
  // The two ticks after that guard are the next one's before: (13 + 13) / 2 - (8 + 8) / 2 = 5.
  feed({{1.0, true}, {13.0, false}, {13.0, false}});
  EXPECT_EQ(g.count(), 2u);
  EXPECT_DOUBLE_EQ(g.standard_deviation(), 4.0 / 0.6744897501960817);  // median of 3 and 5
  // A gap inside a guard is skipped: (19 + 19) / 2 - (13 + 13) / 2 = 6, median of 3, 5, 6.
  feed({{2.0, true}, {std::nan(""), true}, {19.0, false}, {19.0, false}});
  EXPECT_EQ(g.count(), 3u);
  EXPECT_DOUBLE_EQ(g.standard_deviation(), 5.0 / 0.6744897501960817);
  generic::GuardStepNoise empty(0.001);
  EXPECT_TRUE(std::isnan(empty.standard_deviation()));
}

TEST(WindowStepNoise, WhiteNoiseStepsBySigmaTimesRootTwoOverW) {
  const unsigned seed = 20261206;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 2.0);
  for (const double period : {0.001, 0.005}) {
    generic::WindowStepNoise w(period);
    for (int k = 0; k < 200000; ++k) w.add(noise(rng));
    const double expected = 2.0 * std::sqrt(2.0 / static_cast<double>(w.window_ticks()));
    std::printf("T = %g s: W = %zu, sigma %.4f against %.4f\n", period, w.window_ticks(), w.standard_deviation(),
                expected);
    EXPECT_NEAR(w.standard_deviation() / expected, 1.0, 0.02);
  }
}

}  // namespace
}  // namespace ftsense
