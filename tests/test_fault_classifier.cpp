// fault_classifier: on noiseless traces with one-tick blocks it names each synthetic fault shape
// (offset, drift, gain, sign flip, frozen, dead output) with its exact size and onset, gives the
// estimate that recovers the true signal, stays unclassified when the models cannot be told
// apart, and judges each re-admitted episode afresh. A noisy trace (fixed seed) checks the
// likelihood-ratio margin against the noise density.

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/fault_classifier.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::FaultClassifier> {
  static Json params() {
    return Json{{"residual_noise_density", {1.0}}, {"history_s", 1.0}, {"exact_residual", true}};
  }
  static std::size_t input_dim(std::string_view) { return 3; }
  static double sample_period_s() { return 0.01; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t i = 0; i < v.size(); ++i) {
      // The exact reference holds on the first channel only (say, an unloaded one).
      if (port == "exact_residual") v[i] = i == 0 ? 0.5 : nan;
      else v[i] = port == "fault" ? 0.0 : 10.0 * static_cast<double>(i);
    }
  }
};
INSTANTIATE_TYPED_TEST_SUITE_P(FaultClassification, PluginContract, ::testing::Types<generic::FaultClassifier>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::FaultClassifier;

constexpr double kPeriod = 0.01;

// A reference that moves like a gait: v(t) = 100 + 50 sin(2 pi t) [N].
double reference(double t) { return 100.0 + 50.0 * std::sin(2.0 * M_PI * t); }

// One channel, one-tick blocks (block means are the samples: the fits are exact).
struct Trace {
  FaultClassifier classifier;
  double x = 0.0, v = 0.0, flag = 0.0;
  double type = 0.0, estimate = 0.0;
  long tick = 0;

  explicit Trace(double density = 1.0, double block_s = kPeriod)
      : classifier(params(density, block_s), StageContext(kPeriod, "classify", {{"measured", 1}})) {
    classifier.reset();
  }
  static FaultClassifier::Params params(double density, double block_s) {
    FaultClassifier::Params p;
    p.residual_noise_density = {density};
    p.block_s = block_s;
    p.history_s = 10.0;
    return p;
  }
  [[nodiscard]] double time() const { return static_cast<double>(tick) * kPeriod; }
  // Runs until `until_s`; `reading(t, v)` is the sensor's output, `flagged(t)` the isolator's flag.
  void run(double until_s, const std::function<double(double, double)>& reading,
           const std::function<bool(double)>& flagged) {
    while (time() < until_s - 1e-9) {
      const double t = time();
      v = reference(t);
      x = reading(t, v);
      flag = flagged(t) ? 1.0 : 0.0;
      const double f[] = {flag}, m[] = {x}, r[] = {v};
      double out_type[1], out_estimate[1];
      const std::span<const double> ins[] = {f, m, r};
      const std::span<double> outs[] = {out_type, out_estimate};
      classifier.step(StepIO{t, ins, outs});
      type = out_type[0];
      estimate = out_estimate[0];
      ++tick;
    }
  }
  [[nodiscard]] FaultType named() const { return fault_type_from_code(type).value_or(FaultType::invalid); }
};

// Fault from 5 s, flagged from 5.5 s (a detector's delay), judged at 7 s.
constexpr double kOnset = 5.0, kFlag = 5.5, kEnd = 7.0;
bool flagged_after_delay(double t) { return t >= kFlag - 1e-9; }
bool after_onset(double t) { return t >= kOnset - 1e-9; }

TEST(FaultClassifier, NamesAnOffsetWithItsSizeAndOnset) {
  Trace trace;
  trace.run(kEnd, [](double t, double v) { return v + (after_onset(t) ? 20.0 : 0.0); }, flagged_after_delay);
  EXPECT_EQ(trace.named(), FaultType::offset);
  EXPECT_NEAR(trace.classifier.fit(0).size, 20.0, 1e-9);
  EXPECT_NEAR(trace.classifier.fit(0).onset_s, kOnset, 1e-9);
  EXPECT_NEAR(trace.estimate, 20.0, 1e-9);
}

TEST(FaultClassifier, NamesADriftWithItsSlopeAndOnset) {
  Trace trace;
  trace.run(kEnd, [](double t, double v) { return v + (after_onset(t) ? 30.0 * (t - kOnset) : 0.0); },
            flagged_after_delay);
  EXPECT_EQ(trace.named(), FaultType::drift);
  EXPECT_NEAR(trace.classifier.fit(0).size, 30.0, 1e-6);
  EXPECT_NEAR(trace.classifier.fit(0).onset_s, kOnset, 1e-9);
  // The estimate is the drift at the last tick: x - estimate recovers the reference.
  EXPECT_NEAR(trace.x - trace.estimate, trace.v, 1e-6);
}

TEST(FaultClassifier, NamesAGainAndASignFlipAndRecoversTheTrueSignal) {
  for (const double k : {2.0, 0.5, -1.0}) {
    Trace trace;
    trace.run(kEnd, [k](double t, double v) { return after_onset(t) ? k * v : v; }, flagged_after_delay);
    EXPECT_EQ(trace.named(), FaultType::gain) << "k = " << k;
    EXPECT_NEAR(trace.classifier.fit(0).size, k, 1e-9) << "k = " << k;
    EXPECT_NEAR(trace.classifier.fit(0).onset_s, kOnset, 1e-9) << "k = " << k;
    EXPECT_NEAR(trace.x - trace.estimate, trace.v, 1e-9) << "k = " << k;
  }
}

TEST(FaultClassifier, NamesFrozenAtAPlausibleValueAndADeadOutput) {
  for (const double held : {130.0, 0.0}) {
    Trace trace;
    trace.run(kEnd, [held](double t, double v) { return after_onset(t) ? held : v; }, flagged_after_delay);
    EXPECT_EQ(trace.named(), FaultType::frozen) << "held at " << held;
    EXPECT_NEAR(trace.classifier.fit(0).onset_s, kOnset, 1e-9) << "held at " << held;
    // Frozen: the fault is everything the reading is not, so the recovered value is the reference.
    EXPECT_NEAR(trace.x - trace.estimate, trace.v, 1e-9) << "held at " << held;
  }
}

TEST(FaultClassifier, StaysUnclassifiedWhileTheModelsCannotBeToldApart) {
  // A reference that does not move (a robot standing still): x = v + 20 is as well an offset of
  // 20 as a gain of 1.2 or a reading frozen at 120, so nothing is named and the estimate hands
  // the reference downstream.
  Trace trace;
  FaultClassifier& c = trace.classifier;
  double x = 0.0, type = 0.0, estimate = 0.0;
  for (long k = 0; k < 700; ++k) {
    const double t = static_cast<double>(k) * kPeriod;
    x = 100.0 + (t >= kOnset - 1e-9 ? 20.0 : 0.0);
    const double f[] = {flagged_after_delay(t) ? 1.0 : 0.0}, m[] = {x}, r[] = {100.0};
    double out_type[1], out_estimate[1];
    const std::span<const double> ins[] = {f, m, r};
    const std::span<double> outs[] = {out_type, out_estimate};
    c.step(StepIO{t, ins, outs});
    type = out_type[0];
    estimate = out_estimate[0];
  }
  EXPECT_EQ(type, fault_code(FaultType::unclassified));
  EXPECT_NEAR(x - estimate, 100.0, 1e-12);
}

TEST(FaultClassifier, IsQuietWhileNotFlaggedAndJudgesEachEpisodeAfresh) {
  Trace trace;
  // An offset, flagged from 5.5 s to 6 s, then healthy, then a gain x2 from 8 s flagged at 8.5 s.
  const auto reading = [](double t, double v) {
    if (t >= 5.0 - 1e-9 && t < 6.0 - 1e-9) return v + 20.0;
    if (t >= 8.0 - 1e-9) return 2.0 * v;
    return v;
  };
  const auto flagged = [](double t) {
    return (t >= 5.5 - 1e-9 && t < 6.0 - 1e-9) || t >= 8.5 - 1e-9;
  };
  trace.run(5.0, reading, flagged);
  EXPECT_EQ(trace.named(), FaultType::none);
  EXPECT_EQ(trace.estimate, 0.0);
  trace.run(6.0, reading, flagged);
  EXPECT_EQ(trace.named(), FaultType::offset);
  trace.run(8.0, reading, flagged);
  EXPECT_EQ(trace.named(), FaultType::none);
  EXPECT_EQ(trace.estimate, 0.0);
  trace.run(9.5, reading, flagged);
  EXPECT_EQ(trace.named(), FaultType::gain);
  EXPECT_NEAR(trace.classifier.fit(0).size, 2.0, 1e-9);
  // The second episode's onset is searched after the first one's re-admission only.
  EXPECT_NEAR(trace.classifier.fit(0).onset_s, 8.0, 1e-9);
}

TEST(FaultClassifier, ANewEpisodeIsFittedOnlyAfterTheReadmission) {
  // An offset of +20 from 5 s that never ends, flagged 5.5-6 s, then again from 8.5 s (after
  // more than same_episode_s): the second fit starts at the block after the re-admission, so its
  // onset is 6.01 s, not 5 s; its type is unclassified until that first fit.
  Trace trace;
  const auto reading = [](double t, double v) { return v + (after_onset(t) ? 20.0 : 0.0); };
  const auto flagged = [](double t) { return (t >= 5.5 - 1e-9 && t < 6.0 - 1e-9) || t >= 8.5 - 1e-9; };
  trace.run(6.0, reading, flagged);
  ASSERT_EQ(trace.named(), FaultType::offset);
  EXPECT_NEAR(trace.classifier.fit(0).onset_s, kOnset, 1e-9);
  trace.run(9.5, reading, flagged);
  EXPECT_EQ(trace.named(), FaultType::offset);
  EXPECT_NEAR(trace.classifier.fit(0).onset_s, 6.01, 1e-9);
}

TEST(FaultClassifier, NoiseAloneIsNotNamed) {
  // A channel flagged with no fault, its reading the reference plus white noise of the density
  // the classifier is told (sigma 5 N at 1 kHz in 0.1 s blocks, seed 7): no model explains the
  // noise better than the others by the margin, so it stays unclassified.
  constexpr unsigned kSeed = 7;
  std::printf("fault_classifier noise only: seed %u\n", kSeed);
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 5.0);
  Trace trace(5.0 * std::sqrt(kPeriod), 0.1);
  trace.run(20.0, [&](double, double v) { return v + noise(rng); }, [](double t) { return t >= 2.0; });
  EXPECT_EQ(trace.named(), FaultType::unclassified);
}

TEST(FaultClassifier, AFlagThatChattersContinuesTheEpisode) {
  // A drift from 5 s, flagged from 5.5 s; the flag drops for 0.3 s (< same_episode_s = 1 s) at
  // 6 s: the type is back at once when it returns, and the fit still sees the onset at 5 s.
  Trace trace;
  const auto reading = [](double t, double v) { return v + (after_onset(t) ? 30.0 * (t - kOnset) : 0.0); };
  const auto flagged = [](double t) { return flagged_after_delay(t) && !(t >= 6.0 - 1e-9 && t < 6.3 - 1e-9); };
  trace.run(6.0, reading, flagged);
  ASSERT_EQ(trace.named(), FaultType::drift);
  trace.run(6.3, reading, flagged);
  EXPECT_EQ(trace.named(), FaultType::none);
  trace.run(6.31, reading, flagged);
  EXPECT_EQ(trace.named(), FaultType::drift);
  trace.run(kEnd, reading, flagged);
  EXPECT_EQ(trace.named(), FaultType::drift);
  EXPECT_NEAR(trace.classifier.fit(0).size, 30.0, 1e-6);
  EXPECT_NEAR(trace.classifier.fit(0).onset_s, kOnset, 1e-9);
}

TEST(FaultClassifier, ToleratesMissingSamples) {
  Trace trace;
  // Every 7th reading is NaN (a dropout pattern); the offset is still named with its exact size
  // and the outputs stay finite.
  trace.run(kEnd,
            [&trace](double t, double v) {
              return trace.tick % 7 == 3 ? NAN : v + (after_onset(t) ? 20.0 : 0.0);
            },
            flagged_after_delay);
  EXPECT_EQ(trace.named(), FaultType::offset);
  EXPECT_NEAR(trace.classifier.fit(0).size, 20.0, 1e-9);
  EXPECT_TRUE(std::isfinite(trace.estimate));
}

TEST(FaultClassifier, NamesAtTheLikelihoodRatioMarginOnNoisyBlocks) {
  // White noise of standard deviation sigma per tick has density q = sigma sqrt(T). With 0.1 s
  // blocks, an offset of 3 sigma from 5 s is named offset within 1 s of its flag; the margin is
  // chi^2_1(0.999) = z^2 with P(|Z| > z) = 0.001.
  constexpr unsigned kSeed = 20261124;
  std::printf("fault_classifier noisy offset: seed %u\n", kSeed);
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  constexpr double sigma = 5.0;
  Trace trace(sigma * std::sqrt(kPeriod), 0.1);
  EXPECT_NEAR(std::erfc(std::sqrt(trace.classifier.margin() / 2.0)), 0.001, 1e-9);
  trace.run(kEnd, [&](double t, double v) { return v + sigma * noise(rng) + (after_onset(t) ? 3.0 * sigma : 0.0); },
            flagged_after_delay);
  EXPECT_EQ(trace.named(), FaultType::offset);
  EXPECT_NEAR(trace.classifier.fit(0).size, 3.0 * sigma, 0.2 * sigma);
  EXPECT_NEAR(trace.classifier.fit(0).onset_s, kOnset, 0.2);
}

TEST(FaultClassifier, SpreadsTheFitsOverTheBlocksTicks) {
  // Three channels with the same offset, blocks of 3 ticks: one fit a tick, so the three are
  // named on three consecutive ticks, channel 0 first.
  FaultClassifier::Params p;
  p.residual_noise_density = {1.0};
  p.block_s = 3 * kPeriod;
  p.history_s = 10.0;
  FaultClassifier c(p, StageContext(kPeriod, "classify", {{"measured", 3}}));
  c.reset();
  std::vector<long> named_at(3, -1);
  for (long k = 0; k < 700; ++k) {
    const double t = static_cast<double>(k) * kPeriod;
    const double v = reference(t), x = v + (after_onset(t) ? 20.0 : 0.0);
    const double f = flagged_after_delay(t) ? 1.0 : 0.0;
    const double flags[] = {f, f, f}, xs[] = {x, x, x}, vs[] = {v, v, v};
    double types[3], estimates[3];
    const std::span<const double> ins[] = {flags, xs, vs};
    const std::span<double> outs[] = {types, estimates};
    c.step(StepIO{t, ins, outs});
    for (std::size_t j = 0; j < 3; ++j) {
      if (named_at[j] < 0 && types[j] == fault_code(FaultType::offset)) named_at[j] = k;
    }
  }
  ASSERT_GE(named_at[0], 0);
  EXPECT_EQ(named_at[1], named_at[0] + 1);
  EXPECT_EQ(named_at[2], named_at[0] + 2);
}

// A pad that lifts every other 0.5 s (0-0.5 s air, 0.5-1 s ground, ...), an offset of 20 from
// 5 s, flagged from 5.5 s, its ground reference 5 off after 5 s: 7 s of one channel, with `shake`
// added to the faulty air samples; the exact residual (the reading in the air) is wired when
// `exact_wired`.
void run_lifting_pad(FaultClassifier& c, bool exact_wired, const std::function<double(long)>& shake) {
  c.reset();
  for (long k = 0; k < 700; ++k) {
    const double t = static_cast<double>(k) * kPeriod;
    const bool in_air = (k / 50) % 2 == 0;
    const double load = in_air ? 0.0 : reference(t);
    const double x = load + (after_onset(t) ? 20.0 + (in_air ? shake(k) : 0.0) : 0.0);
    const double v = in_air ? 0.0 : load + (after_onset(t) ? 5.0 : 0.0);
    const double exact = in_air ? x : std::numeric_limits<double>::quiet_NaN();
    const double f = flagged_after_delay(t) ? 1.0 : 0.0;
    const double flags[] = {f}, xs[] = {x}, vs[] = {v}, es[] = {exact};
    double types[1], estimates[1];
    const std::span<const double> ins[] = {flags, xs, vs, es};
    const std::span<double> outs[] = {types, estimates};
    c.step(StepIO{t, exact_wired ? std::span<const std::span<const double>>(ins)
                                 : std::span<const std::span<const double>>(ins, 3),
                  outs});
  }
}

// A foot's pad: 0.5 s in the air (its reference 0, exact up to the sensor's noise), 0.5 s on the
// ground (its reference, a leave-one-out force, 5 N off after 5 s); an offset of 20 from 5 s.
// Without the exact input every block weighs alike and the offset is the mean of 20 and 15; with
// it an air block weighs (q / q_e)^2 = 100 stance blocks. The onset's block (5.00 s, air) is
// fitted by no model, so 99 air blocks and 100 ground blocks give b.
TEST(FaultClassifier, WeighsBlocksWhoseReferenceIsExactByTheirOwnNoise) {
  for (const bool exact_wired : {false, true}) {
    FaultClassifier::Params p;
    p.residual_noise_density = {1.0};
    p.exact_noise_density = {0.1};
    p.exact_residual = exact_wired;
    p.block_s = kPeriod;
    p.history_s = 10.0;
    FaultClassifier c(p, StageContext(kPeriod, "classify", {{"measured", 1}}));
    run_lifting_pad(c, exact_wired, [](long) { return 0.0; });
    EXPECT_EQ(c.fit(0).type, FaultType::offset) << "exact wired: " << exact_wired;
    EXPECT_NEAR(c.fit(0).onset_s, kOnset, 1e-9) << "exact wired: " << exact_wired;
    const double air_weight = exact_wired ? 100.0 : 1.0;
    const double expected = (100.0 * 15.0 + 99.0 * air_weight * 20.0) / (100.0 + 99.0 * air_weight);
    EXPECT_NEAR(c.fit(0).size, expected, 1e-9) << "exact wired: " << exact_wired;
  }
}

// An offset of 20 from 5 s (25 over 5.1-5.2 s), its reference not a number over 5.3-5.4 s (empty
// blocks): an onset there must still pay for the faulty blocks before it. It would otherwise
// fit everything after it exactly and beat the true onset, which pays for the bump.
TEST(FaultClassifier, AnEmptyBlockGivesNoOnsetAFreeHistory) {
  Trace trace;
  const auto reading = [](double t, double v) {
    const bool bump = t >= 5.1 - 1e-9 && t < 5.2 - 1e-9;
    return v + (after_onset(t) ? (bump ? 25.0 : 20.0) : 0.0);
  };
  trace.run(5.3, reading, flagged_after_delay);
  FaultClassifier& c = trace.classifier;
  for (long k = 0; k < 10; ++k, ++trace.tick) {  // 5.3-5.4 s: the reference is missing
    const double t = trace.time();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double f[] = {0.0}, m[] = {reference(t) + 20.0}, r[] = {nan};
    double out_type[1], out_estimate[1];
    const std::span<const double> ins[] = {f, m, r};
    const std::span<double> outs[] = {out_type, out_estimate};
    c.step(StepIO{t, ins, outs});
  }
  trace.run(kEnd, reading, flagged_after_delay);
  EXPECT_EQ(trace.named(), FaultType::offset);
  EXPECT_NEAR(c.fit(0).onset_s, kOnset, 1e-9);
  // 10 blocks of 25 among the 189 after the onset's, every other at 20.
  EXPECT_NEAR(c.fit(0).size, 20.0 + 5.0 * 10.0 / 189.0, 1e-9);
}

// A step of 20 that begins halfway through a block of 0.1 s: that block's mean is 10, a ramp's
// first point, and no model is asked to explain it, so the offset is exactly 20 and its onset the
// block's mean tick time.
TEST(FaultClassifier, TheBlockAFaultBeginsInIsFittedByNoModel) {
  Trace trace(1.0, 0.1);
  trace.run(kEnd, [](double t, double v) { return v + (t >= 5.05 - 1e-9 ? 20.0 : 0.0); }, flagged_after_delay);
  EXPECT_EQ(trace.named(), FaultType::offset);
  EXPECT_NEAR(trace.classifier.fit(0).size, 20.0, 1e-9);
  EXPECT_NEAR(trace.classifier.fit(0).onset_s, 5.045, 1e-9);
}

// The same pad as above, its air samples now shaken by a burst of +-5 around the offset of 20
// (two-tick blocks: their sample variance is 2 x 5^2 = 50, against q_e^2 / T = 1). An air block
// then weighs n^2 / (n 50) = 0.04, a ground block n T / q^2 = 0.02, instead of 2 for a quiet air
// block: 49 air blocks and 50 ground blocks after the onset's.
TEST(FaultClassifier, AnExactBlockThatSpreadsMoreThanItsNoiseWeighsAsItsSpread) {
  FaultClassifier::Params p;
  p.residual_noise_density = {1.0};
  p.exact_noise_density = {0.1};
  p.exact_residual = true;
  p.block_s = 2.0 * kPeriod;
  p.history_s = 10.0;
  FaultClassifier c(p, StageContext(kPeriod, "classify", {{"measured", 1}}));
  run_lifting_pad(c, true, [](long k) { return k % 2 == 0 ? 5.0 : -5.0; });
  EXPECT_EQ(c.fit(0).type, FaultType::offset);
  EXPECT_NEAR(c.fit(0).onset_s, kOnset + 0.5 * kPeriod, 1e-9);
  EXPECT_NEAR(c.fit(0).size, (50.0 * 0.02 * 15.0 + 49.0 * 0.04 * 20.0) / (50.0 * 0.02 + 49.0 * 0.04), 1e-9);
}

// A gain named on a stance is refuted by the air after it, where an offset and a frozen output fit
// alike: the type goes back to unclassified (the recovery takes the reference), not a type the data
// have since refuted (without the rule: a drift, which the air's first blocks favoured, then kept).
// 0-6 s the reference swings about zero, v = 100 sin(2 pi t) (whole periods: an offset's and a
// frozen reading's misfits there are equal); from 5 s the reading is v / 2, flagged at once, so
// gain is named (k = 0.5; offset and frozen leave 0.25 sum w v^2 = 1250 each). From 6 s to 7 s the
// pad is in the air: its reference 0 exactly (input exact_residual), its reading stuck at -60 (a
// second long: a drift's ramp from 5 s cannot pass for that constant).
TEST(FaultClassifier, ANamedTypeThatAnotherModelRefutesIsUnclassifiedUntilOneStandsApart) {
  FaultClassifier::Params p;
  p.residual_noise_density = {1.0};
  p.exact_noise_density = {0.1};
  p.exact_residual = true;
  p.block_s = kPeriod;
  p.history_s = 10.0;
  FaultClassifier c(p, StageContext(kPeriod, "classify", {{"measured", 1}}));
  c.reset();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double type = 0.0, estimate = 0.0, x = 0.0, v = 0.0;
  for (long k = 0; k < 700; ++k) {
    const double t = static_cast<double>(k) * kPeriod;
    const bool in_air = k >= 600;
    v = in_air ? 0.0 : 100.0 * std::sin(2.0 * M_PI * t);
    x = in_air ? -60.0 : (k >= 500 ? 0.5 * v : v);
    const double flags[] = {k >= 500 ? 1.0 : 0.0}, xs[] = {x}, vs[] = {v}, es[] = {in_air ? x : nan};
    double types[1], estimates[1];
    const std::span<const double> ins[] = {flags, xs, vs, es};
    const std::span<double> outs[] = {types, estimates};
    c.step(StepIO{t, ins, outs});
    type = types[0];
    estimate = estimates[0];
    if (k == 599) {
      EXPECT_EQ(type, fault_code(FaultType::gain));
      EXPECT_NEAR(c.fit(0).size, 0.5, 1e-9);
    }
  }
  EXPECT_EQ(type, fault_code(FaultType::unclassified));
  EXPECT_NEAR(x - estimate, v, 1e-12);  // recovered: the reference, 0 in the air
}

TEST(FaultClassifier, RejectsAHistoryShorterThanFourBlocks) {
  FaultClassifier::Params p;
  p.block_s = 0.1;
  p.history_s = 0.3;
  EXPECT_THROW(FaultClassifier(p, StageContext(kPeriod, "classify", {{"measured", 1}})), ConfigError);
}

}  // namespace
}  // namespace ftsense
