// signal_validator: each test fires on the tick it should (deterministic traces), and healthy
// quantised or noisy sensors raise nothing (seeded noise, seeds printed).

#include <cmath>
#include <limits>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/signal_validator.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::SignalValidator> {
  static Json params() { return {{"reference", true}, {"upper_limit", {1e4}}}; }
  static std::size_t input_dim(std::string_view) { return 3; }
  static void nominal_input(std::string_view, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = 100.0 + 10.0 * static_cast<double>(i);
  }
  static double sample_period_s() { return 1e-3; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(Validator, PluginContract, ::testing::Types<generic::SignalValidator>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::SignalValidator;

struct OneValidatedChannel {
  SignalValidator validator;
  bool with_reference;
  std::vector<double> x{0.0}, r{0.0}, fault{0.0}, type{0.0};
  double t = 0.0;
  double period;

  OneValidatedChannel(const SignalValidator::Params& p, double period_s)
      : validator(p, StageContext(period_s, "v", p.reference ? std::vector<std::pair<std::string, std::size_t>>{{"signal", 1}, {"reference", 1}}
                                                            : std::vector<std::pair<std::string, std::size_t>>{{"signal", 1}})),
        with_reference(p.reference),
        period(period_s) {
    validator.reset();
  }
  FaultType step(double reading, double reference = 0.0) {
    x[0] = reading;
    r[0] = reference;
    const std::span<double> outs[] = {fault, type};
    if (with_reference) {
      const std::span<const double> ins[] = {x, r};
      validator.step(StepIO{t, ins, outs});
    } else {
      const std::span<const double> ins[] = {x};
      validator.step(StepIO{t, ins, outs});
    }
    t += period;
    EXPECT_EQ(fault[0] != 0.0, type[0] != fault_code(FaultType::none));
    return static_cast<FaultType>(static_cast<int>(type[0]));
  }
};

TEST(ChiSquare, QuantilesMatchTables) {
  EXPECT_NEAR(generic::normal_quantile(0.975), 1.959964, 1e-6);
  EXPECT_NEAR(generic::normal_quantile(1e-9), -5.997807, 1e-5);
  // chi2 tables: nu = 30, p = 0.05: 18.493; p = 0.95: 43.773 (Wilson-Hilferty within 0.1 %).
  EXPECT_NEAR(generic::chi_square_quantile(30.0, 0.05) / 18.493, 1.0, 1e-3);
  EXPECT_NEAR(generic::chi_square_quantile(30.0, 0.95) / 43.773, 1.0, 1e-3);
  // Given z itself: p = 0.95 is z = 1.644854.
  EXPECT_NEAR(generic::chi_square_quantile_at_z(30.0, 1.644854) / 43.773, 1.0, 1e-3);
  EXPECT_NEAR(generic::chi_square_quantile_at_z(30.0, generic::normal_quantile(0.95)),
              generic::chi_square_quantile(30.0, 0.95), 1e-12);
}

TEST(SignalValidator, InvalidAndSaturationOnTheirTick) {
  SignalValidator::Params p;
  p.noise_std = {100.0};  // so that the jumps below are not spikes
  p.resolution = {1.0};
  p.upper_limit = {100.0};
  OneValidatedChannel c(p, 1e-3);
  EXPECT_EQ(c.step(10.0), FaultType::none);
  EXPECT_EQ(c.step(std::nan("")), FaultType::invalid);
  EXPECT_EQ(c.step(11.0), FaultType::none);
  EXPECT_EQ(c.step(std::numeric_limits<double>::infinity()), FaultType::invalid);
  EXPECT_EQ(c.step(99.4), FaultType::none);
  EXPECT_EQ(c.step(99.5), FaultType::saturation);  // within q / 2 of the limit
  EXPECT_EQ(c.step(130.0), FaultType::saturation);
  EXPECT_EQ(c.step(50.0), FaultType::none);
  // No lower limit given: 0 and below are readings like any other.
  EXPECT_EQ(c.step(0.0), FaultType::none);
  EXPECT_EQ(c.step(-3.0), FaultType::none);
}

TEST(SignalValidator, AFrozenReadingIsFlaggedOnTheTickItsLastMovesLeaveTheWindow) {
  // A reading alternating +-1 (d2 = +-4: below the noise count's 2 sqrt(6) sigma, d2^2 = 16) that
  // freezes at its last value from tick f: d2 is 16 up to tick f - 1, 4 on tick f, 0 after. The
  // stale bound 6 sigma^2 n chi2_nu(alpha) / nu lies between 16 + 4 and 16 + 16 + 4 (checked), so
  // the flag rises on the tick the window keeps only d2(f - 1) and d2(f): f + n - 2.
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.window_s = 0.05;
  p.noise_margin = 1.0;  // the bound as computed below; NoiseMargin* tests the margin
  p.repeat_min_s = 1.0;  // the run of repeats off (n_r beyond the window): the window's test alone
  OneValidatedChannel c(p, 1e-3);
  const std::size_t n = c.validator.window_ticks();
  ASSERT_EQ(n, 50u);
  const double nu = 36.0 * 50.0 / 70.0;
  const double bound = 6.0 * 50.0 * generic::chi_square_quantile(nu, 1e-3 / p.false_alarm_interval_s) / nu;
  std::printf("stale bound on sum(d2^2): %.2f\n", bound);
  ASSERT_GT(bound, 20.0);
  ASSERT_LT(bound, 36.0);
  constexpr int kFreeze = 200;
  double last = 0.0;
  for (int k = 0; k < kFreeze; ++k) {
    last = k % 2 ? 1.0 : -1.0;
    ASSERT_EQ(c.step(last), FaultType::none) << k;
  }
  const int flag_tick = kFreeze + static_cast<int>(n) - 2;
  for (int k = kFreeze; k < kFreeze + 200; ++k) {
    EXPECT_EQ(c.step(last), k >= flag_tick ? FaultType::frozen : FaultType::none) << "tick " << k;
  }
  // It moves by 3 (d2 = 3: 9 < bound, still frozen) and back (d2 = -6: 9 + 36 > bound, cleared).
  EXPECT_EQ(c.step(last + 3.0), FaultType::frozen);
  EXPECT_EQ(c.step(last), FaultType::none);
}

TEST(SignalValidator, ARunOfRepeatsIsFrozenAfterRepeatMinSOrTheRunItsNoiseMakesUnlikely) {
  // Window 0.1 s (100 ticks at 1 kHz), repeat_min_s 0.02 s, noise_margin 1.5. A reading that moves
  // every tick by +-a (a = 1 continuous, one level of q = 2: its d2 below the noise test's bar),
  // then repeats its last value on ticks 500-559:
  //   continuous (q = 0): no noise leaves a reading on its value, so the run is frozen once it is
  //     repeat_min_s long, 20 repeats: on tick 519;
  //   q = 2, sigma = 2: p = erf(2 x 1.5 / (2 sqrt(2) 2)) = 0.5468, and alpha = 1e-3 / 86400, so
  //     n_r = ceil(ln alpha / ln p) = 31 repeats: on tick 530.
  // The move on tick 560 ends it, before the window's variance test (which needs most of the
  // window silent) fires; a second run at the same value from tick 700 is saturation (a clip's
  // ceiling), as soon after its start.
  for (const double q : {0.0, 2.0}) {
    SignalValidator::Params p;
    p.noise_std = {2.0};
    p.resolution = {q};
    OneValidatedChannel c(p, 1e-3);
    const int run = q == 0.0 ? 19 : 30;  // the flag's tick less the run's first
    const double a = q == 0.0 ? 1.0 : q;
    const auto moving = [&](int k) { return 100.0 + (k % 2 ? a : -a); };
    for (int k = 0; k < 800; ++k) {
      const bool first = k >= 500 && k < 560, second = k >= 700;
      const double x = first ? moving(499) : second ? moving(699) : moving(k);
      const FaultType expected = first && k >= 500 + run    ? FaultType::frozen
                                 : second && k >= 700 + run ? FaultType::saturation
                                                            : FaultType::none;
      EXPECT_EQ(c.step(x), expected) << "q " << q << ", tick " << k;
    }
  }
}

TEST(SignalValidator, AQuantisedHealthySensorAtItsLeastNoiseRepeatsItselfWithoutAFlag) {
  // q = 2, stated sigma = 2, true noise sigma / m = 1.33 (the least the margin allows), a
  // constant load on a level's centre (where a reading stays on its level most): 100 s at 1 kHz.
  SignalValidator::Params p;
  p.noise_std = {2.0};
  p.resolution = {2.0};
  OneValidatedChannel c(p, 1e-3);
  constexpr unsigned kSeed = 20261208;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 2.0 / 1.5);
  int flagged = 0;
  for (int k = 0; k < 100000; ++k) flagged += c.step(2.0 * std::round((200.0 + noise(rng)) / 2.0)) != FaultType::none;
  EXPECT_EQ(flagged, 0);
}

TEST(SignalValidator, ACoarselyQuantisedHealthySensorThatRepeatsItselfIsNotFrozen) {
  // 5 N steps, 1 N noise (sigma < q / 2): a constant load reads the same value for ever; an
  // unloaded foot reads exact zeros. Neither is a fault.
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.resolution = {5.0};
  OneValidatedChannel c(p, 1e-3);
  constexpr unsigned kSeed = 11;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  int flagged = 0;
  for (int k = 0; k < 20000; ++k) {
    const double load = k < 10000 ? 0.0 : 203.4;
    flagged += c.step(5.0 * std::round((load + noise(rng)) / 5.0)) != FaultType::none;
  }
  EXPECT_EQ(flagged, 0);
}

TEST(SignalValidator, HealthyNoisyQuantisedSensorsRaiseNothingAtAnyRate) {
  // sigma = 3, q = 5 (sigma >= q / 2: the stale test is on) on a slow load, 100 s at 1 kHz and at
  // 200 Hz; the bound: no flag at all (target one false alarm a day per test).
  constexpr unsigned kSeed = 12;
  std::printf("seed %u\n", kSeed);
  for (const double period : {1e-3, 5e-3}) {
    SignalValidator::Params p;
    p.noise_std = {3.0};
    p.resolution = {5.0};
    OneValidatedChannel c(p, period);
    std::mt19937_64 rng(kSeed);
    std::normal_distribution<double> noise(0.0, 3.0);
    int flagged = 0;
    for (double t = 0.0; t < 100.0; t += period) {
      const double load = 300.0 + 200.0 * std::sin(2.0 * std::numbers::pi * 1.0 * t);
      flagged += c.step(5.0 * std::round((load + noise(rng)) / 5.0)) != FaultType::none;
    }
    EXPECT_EQ(flagged, 0) << "T = " << period;
  }
}

TEST(SignalValidator, AFrozenOutputThatStillCarriesNoiseIsCaughtAgainstTheReference) {
  // The load swings 100..500 N at 1 Hz; the sensor follows it with 2 N noise, then from t = 3 s
  // its output stays at 250 N plus the same noise. The signal-only stale test cannot see it; the
  // reference test must, within two windows of the first reference move of min_reference_change.
  SignalValidator::Params p;
  p.noise_std = {2.0};
  p.reference = true;
  p.reference_noise_std = {5.0};
  p.window_s = 0.1;
  OneValidatedChannel c(p, 1e-3);
  constexpr unsigned kSeed = 13;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  double first_flag = -1.0;
  for (int k = 0; k < 5000; ++k) {
    const double t = k * 1e-3;
    const double load = 300.0 + 200.0 * std::sin(2.0 * std::numbers::pi * t);
    const double reading = (t < 3.0 ? load : 250.0) + 2.0 * noise(rng);
    const FaultType found = c.step(reading, load + 5.0 * noise(rng));
    if (t < 3.0) {
      ASSERT_EQ(found, FaultType::none) << "t = " << t;
    } else if (found == FaultType::frozen && first_flag < 0.0) {
      first_flag = t;
    }
  }
  std::printf("frozen at 3 s, flagged at %.3f s\n", first_flag);
  ASSERT_GE(first_flag, 3.0);
  EXPECT_LE(first_flag, 3.2);
}

// A ramp of slope 0.5 per tick with unit noise, one reading 100 off at tick 50 (and with a
// reference, the ramp with noise of sigma_r = 1): flagged spikes from tick 51 to 90, the first
// spike's hold of 40 ticks, and nothing else.
void expect_the_ramps_spike_flagged_from_51_to_90(bool with_reference, unsigned seed) {
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.reference = with_reference;
  p.reference_noise_std = {1.0};
  p.window_s = 0.02;      // 20 ticks
  p.spike_hold_s = 0.04;  // 40 ticks: a first spike's rate is unknown
  OneValidatedChannel c(p, 1e-3);
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int k = 0; k < 150; ++k) {
    const double load = 0.5 * k;
    const double reading = load + noise(rng) + (k == 50 ? 100.0 : 0.0);
    const FaultType found = with_reference ? c.step(reading, load + noise(rng)) : c.step(reading);
    EXPECT_EQ(found, k >= 51 && k < 91 ? FaultType::spikes : FaultType::none) << "tick " << k;
  }
}

TEST(SignalValidator, ASpikeIsFlaggedOneTickLateAndHeldForSpikeHold) {
  expect_the_ramps_spike_flagged_from_51_to_90(false, 16);
}

TEST(SignalValidator, WithAReferenceASpikeOfTheReadingAloneIsFlaggedOnTheSameTicks) {
  // The spike at tick 50 is in x - r as in x, so it is flagged on the same ticks.
  expect_the_ramps_spike_flagged_from_51_to_90(true, 61);
}

TEST(SignalValidator, ASpikeOfTheReferenceOrOneItExplainsIsNoSpikeOfTheReading) {
  // A steady reading (alternating +-1: no spike, no noise, not frozen) and its reference:
  // (a) the reference alone jumps by 100 for tick 50: x shows nothing, so nothing is flagged;
  // (b) at tick 50 the reading jumps by 30 and the reference by 80 (the load moved, and the
  //     reference saw more of it): x - r spikes by -50, beyond its bound but against x's own
  //     spike, so nothing is flagged; without the sign rule it would be;
  // (c) the reading jumps by 30 while the reference jumps by 25: x - r spikes by 5, within its
  //     bound (5.70 x 1.5 x sqrt(1.5 x 2) = 14.8): nothing; (d) the reference stays: a spike.
  struct Case {
    double reading_jump, reference_jump;
    bool flagged;
  };
  for (const Case& e : {Case{0.0, 100.0, false}, Case{30.0, 80.0, false}, Case{30.0, 25.0, false},
                        Case{30.0, 0.0, true}}) {
    SignalValidator::Params p;
    p.noise_std = {1.0};
    p.reference = true;
    p.reference_noise_std = {1.0};
    p.window_s = 0.02;
    p.tests = {"frozen", "spikes", "noise"};  // (a reference's one-tick jump moves its low-pass: no follow test)
    OneValidatedChannel c(p, 1e-3);
    int flagged = 0;
    for (int k = 0; k < 150; ++k) {
      const double wobble = k % 2 == 0 ? 1.0 : -1.0;
      const FaultType found = c.step(100.0 + wobble + (k == 50 ? e.reading_jump : 0.0),
                                     100.0 + (k == 50 ? e.reference_jump : 0.0));
      flagged += found != FaultType::none;
      if (found != FaultType::none) {
        EXPECT_EQ(found, FaultType::spikes) << "tick " << k;
      }
    }
    EXPECT_EQ(flagged > 0, e.flagged) << "reading +" << e.reading_jump << ", reference +" << e.reference_jump;
  }
}

TEST(SignalValidator, ALoadThatBouncesFasterThanTheRateIsNoiseOrSpikesUnlessTheReferenceShowsIt) {
  // A foot that bounces on and off the ground for 0.3 s at 1 kHz: its load (0.5 N sensor noise)
  // is 0 or 28 N in runs of 1 to 3 ticks; its reference sees 90 % of each move, with noise of
  // sigma_r = 1 N. Judged on the reading alone the bounce is noise and spikes; with the
  // reference, the residual x - r moves by a tenth of each step (2.8 N, within its bounds), so
  // nothing is flagged. And a sensor's own noise burst (20 N, 0.3 s later) is flagged with the
  // reference: the reference does not show it.
  for (const bool with_reference : {false, true}) {
    SignalValidator::Params p;
    p.noise_std = {0.5};
    p.reference = with_reference;
    p.reference_noise_std = {1.0};
    p.tests = {"frozen", "spikes", "noise"};
    OneValidatedChannel c(p, 1e-3);
    constexpr unsigned kSeed = 62;
    std::printf("seed %u\n", kSeed);
    std::mt19937_64 rng(kSeed);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_int_distribution<int> run(1, 3);
    int bounce_flags = 0, burst_flags = 0, burst_noise = 0;
    double level = 28.0;
    int left = 0;
    for (int k = 0; k < 2000; ++k) {
      double load = 20.0 + 10.0 * std::sin(0.002 * k);
      if (k >= 500 && k < 800) {
        if (left == 0) {
          level = level > 0.0 ? 0.0 : 28.0;
          left = run(rng);
        }
        --left;
        load = level;
      }
      const double burst = k >= 1100 && k < 1400 ? 20.0 * noise(rng) : 0.0;
      const double reading = load + 0.5 * noise(rng) + burst;
      const double reference = 0.9 * load + (k >= 500 && k < 800 ? 0.1 * 28.0 : 0.1 * load) + noise(rng);
      const FaultType found = c.step(reading, reference);
      if (found == FaultType::none) continue;
      if (k < 1100) ++bounce_flags;
      if (k >= 1100 && k < 1400) {
        // Its first large second differences are spikes until the noise count passes its bound.
        EXPECT_TRUE(found == FaultType::noise || found == FaultType::spikes) << "tick " << k;
        ++burst_flags;
        burst_noise += found == FaultType::noise;
      }
    }
    std::printf("%s: bounce flagged on %d ticks, burst on %d of 300 (noise on %d)\n",
                with_reference ? "with reference" : "alone", bounce_flags, burst_flags, burst_noise);
    if (with_reference) {
      EXPECT_EQ(bounce_flags, 0);
    } else {
      EXPECT_GT(bounce_flags, 0);
    }
    EXPECT_GT(burst_flags, 250);
    EXPECT_GT(burst_noise, 200);
  }
}

TEST(SignalValidator, ASpikeTrainIsHeldThroughItsGapsAndClearsAfterTheGapItsRateMakesUnlikely) {
  // Spikes of 50 sigma every 50 ticks (20 per second at 1 kHz) from tick 1000 to 2000, on a
  // reading alternating +-1 (d2 = +-4: no spike, no noise, not frozen). Each is seen one tick
  // late. From the second on the rate is measured exactly: 20 Hz, so the flag holds
  // ln(1 / 0.01) / 20 Hz = 0.2303 s, 230.3 ticks, after the last: flagged from 1001 to 2231.
  // The first alone would hold spike_hold_s (0.8 s), longer than its gap: the flag never drops.
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.window_s = 0.1;
  OneValidatedChannel c(p, 1e-3);
  int first = -1, last = -1, flagged = 0;
  for (int k = 0; k < 4000; ++k) {
    const bool spike = k >= 1000 && k <= 2000 && (k - 1000) % 50 == 0;
    const FaultType found = c.step(100.0 + (k % 2 == 0 ? 1.0 : -1.0) + (spike ? 50.0 : 0.0));
    if (found == FaultType::none) continue;
    EXPECT_EQ(found, FaultType::spikes) << "tick " << k;
    if (first < 0) first = k;
    last = k;
    ++flagged;
  }
  EXPECT_EQ(first, 1001);
  EXPECT_EQ(last, 2231);
  EXPECT_EQ(flagged, 2231 - 1001 + 1);  // no gap in between
}

TEST(SignalValidator, ASpikeHoldShorterThanTheWindowIsTheWindowAndABlindChannelEndsItsEpisode) {
  // spike_hold_s 0.01 s under window_s 0.02 s: a lone spike holds the window, 20 ticks.
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.window_s = 0.02;
  p.spike_hold_s = 0.01;
  p.guard = true;
  SignalValidator validator(p, StageContext(1e-3, "v", {{"signal", 1}, {"guard", 1}}));
  validator.reset();
  std::vector<double> x{0.0}, g{0.0}, fault{0.0}, type{0.0};
  const auto step = [&](double reading, double guard) {
    x[0] = reading;
    g[0] = guard;
    const std::span<const double> ins[] = {x, g};
    const std::span<double> outs[] = {fault, type};
    validator.step(StepIO{0.0, ins, outs});
    return static_cast<FaultType>(static_cast<int>(type[0]));
  };
  for (int k = 0; k < 100; ++k) {
    const FaultType found = step(100.0 + (k % 2 == 0 ? 1.0 : -1.0) + (k == 50 ? 50.0 : 0.0), 0.0);
    EXPECT_EQ(found, k >= 51 && k < 71 ? FaultType::spikes : FaultType::none) << "tick " << k;
  }
  // A spike, then a guard that stays on: no tick is seen, so the hold does not run out; the
  // episode ends after 2 spike_hold_s (here the window, 20 ticks: 40) of ticks without a spike.
  for (int k = 100; k < 200; ++k) {
    const FaultType found = step(100.0 + (k % 2 == 0 ? 1.0 : -1.0) + (k == 150 ? 50.0 : 0.0), k > 151 ? 1.0 : 0.0);
    EXPECT_EQ(found, k >= 151 && k < 191 ? FaultType::spikes : FaultType::none) << "tick " << k;
  }
}

TEST(SignalValidator, AStepIsNeitherASpikeNorNoise) {
  // A clean 100-unit step (an offset fault's onset, a landing) on white noise: not a validator
  // fault (the residual detectors judge offsets).
  SignalValidator::Params p;
  p.noise_std = {1.0};
  OneValidatedChannel c(p, 1e-3);
  constexpr unsigned kSeed = 14;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  int flagged = 0;
  for (int k = 0; k < 2000; ++k) flagged += c.step((k >= 1000 ? 100.0 : 0.0) + noise(rng)) != FaultType::none;
  EXPECT_EQ(flagged, 0);
}

TEST(SignalValidator, ANoiseBurstIsFlaggedWithinAWindowAndClearsAfterIt) {
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.window_s = 0.1;
  OneValidatedChannel c(p, 1e-3);
  constexpr unsigned kSeed = 15;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  int first = -1;
  int last = -1;
  for (int k = 0; k < 3000; ++k) {
    const double sigma = k >= 1000 && k < 1500 ? 4.0 : 1.0;  // 0.5 s of 4x noise
    const FaultType found = c.step(50.0 + sigma * noise(rng));
    if (found != FaultType::none) {
      EXPECT_TRUE(found == FaultType::noise || found == FaultType::spikes) << "tick " << k;
      if (first < 0) first = k;
      last = k;
    }
  }
  std::printf("noise 1000..1499: flagged %d..%d\n", first, last);
  EXPECT_GE(first, 1000);
  EXPECT_LE(first, 1100);
  EXPECT_LE(last, 1500 + 100 + 1);
}

// 3 s of white noise (sigma 1, seed 19) at 1 kHz around 50, ten times that over ticks 1000..1799
// when `burst`, guarded over [guard_from, guard_to): the ticks flagged.
std::vector<int> guarded_burst_flags(bool burst, int guard_from, int guard_to) {
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.window_s = 0.1;
  p.guard = true;
  SignalValidator validator(p, StageContext(1e-3, "v", {{"signal", 1}, {"guard", 1}}));
  validator.reset();
  std::vector<double> x{0.0}, g{0.0}, fault{0.0}, type{0.0};
  std::mt19937_64 rng(19);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<int> flagged;
  for (int k = 0; k < 3000; ++k) {
    x[0] = 50.0 + (burst && k >= 1000 && k < 1800 ? 10.0 : 1.0) * noise(rng);
    g[0] = k >= guard_from && k < guard_to ? 1.0 : 0.0;
    const std::span<const double> ins[] = {x, g};
    const std::span<double> outs[] = {fault, type};
    validator.step(StepIO{k * 1e-3, ins, outs});
    if (fault[0] != 0.0) flagged.push_back(k);
  }
  return flagged;
}

TEST(SignalValidator, ANoiseBurstKeepsItsFlagThroughAGuardThatHidesIt) {
  // 0.8 s of 10x noise (ticks 1000..1799) with a guard over ticks 1300..1449 (a landing's 0.15 s,
  // longer than the 0.1 s window): the guarded ticks are not seen, so the window keeps the burst's
  // ticks and the flag holds through the guard, to the burst's end and at most a window after it.
  // (Counted as quiet, the guard emptied the window and the flag fell on tick 1300 + 100 or
  // so.) Healthy noise with the same guard is never flagged.
  std::printf("seed 19\n");
  EXPECT_TRUE(guarded_burst_flags(false, 1300, 1450).empty());
  const std::vector<int> flagged = guarded_burst_flags(true, 1300, 1450);
  ASSERT_FALSE(flagged.empty());
  const int first = flagged.front(), last = flagged.back();
  std::printf("noise 1000..1799, guard 1300..1449: flagged %d..%d, %zu ticks\n", first, last, flagged.size());
  EXPECT_GE(first, 1000);
  EXPECT_LE(first, 1100);
  EXPECT_GE(last, 1799);
  EXPECT_LE(last, 1800 + 100 + 1);
  EXPECT_EQ(static_cast<int>(flagged.size()), last - first + 1);  // no gap: held through the guard
}

TEST(SignalValidator, AGuardThatStaysOnLetsTheNoiseVerdictLapseAfterTwoWindows) {
  // The same burst, guarded from tick 1300 to the end: the verdict holds for two windows of
  // guarded ticks (200), then the window empties; last flagged on tick 1498.
  std::printf("seed 19\n");
  const std::vector<int> flagged = guarded_burst_flags(true, 1300, 3000);
  ASSERT_FALSE(flagged.empty());
  EXPECT_EQ(flagged.back(), 1498);
}

TEST(SignalValidator, ABurstIsNoiseThoughItsSamplesLookLikeSpikesAndSparseSpikesStaySpikes) {
  // 0.5 s of 10x noise: many of its samples pass the spike test on their own. Once the window's
  // count shows the burst (within 0.1 s), every tick to the burst's end is typed noise. Then
  // spikes of 40 sigma at 5 per second (0.2 s apart, so at most one in a 0.1 s window) are spikes.
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.window_s = 0.1;
  OneValidatedChannel c(p, 1e-3);
  constexpr unsigned kSeed = 16;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  int first_noise = -1, noise_ticks = 0, spike_ticks = 0, other = 0;
  for (int k = 0; k < 4000; ++k) {
    const bool burst = k >= 1000 && k < 1500;
    const bool spike = k >= 2500 && (k - 2500) % 200 == 0;
    const FaultType found = c.step(50.0 + (burst ? 10.0 : 1.0) * noise(rng) + (spike ? 40.0 : 0.0));
    if (found == FaultType::noise && first_noise < 0) first_noise = k;
    if (first_noise >= 0 && k < 1500) noise_ticks += found == FaultType::noise;
    if (k >= 2500) spike_ticks += found == FaultType::spikes;
    if (k >= 2500) other += found != FaultType::spikes && found != FaultType::none;
  }
  std::printf("burst 1000..1499: noise from %d, %d noise ticks; %d spike ticks, %d others after 2500\n", first_noise,
              noise_ticks, spike_ticks, other);
  ASSERT_GE(first_noise, 1000);
  EXPECT_LE(first_noise, 1100);
  EXPECT_EQ(noise_ticks, 1500 - first_noise);
  EXPECT_GT(spike_ticks, 0);
  EXPECT_EQ(other, 0);
}

TEST(SignalValidator, OnlyTheChosenTestsRunBesidesInvalidAndSaturation) {
  // tests = [frozen]: a 100-sigma spike and a 10x noise burst raise nothing; a NaN and a reading at
  // the upper limit still do, and a reading that stops moving is frozen.
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.upper_limit = {1000.0};
  p.tests = {"frozen"};
  OneValidatedChannel c(p, 1e-3);
  constexpr unsigned kSeed = 17;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  int flagged = 0;
  for (int k = 0; k < 2000; ++k) {
    const double sigma = k >= 1000 && k < 1500 ? 10.0 : 1.0;
    flagged += c.step(50.0 + sigma * noise(rng) + (k == 500 ? 100.0 : 0.0)) != FaultType::none;
  }
  EXPECT_EQ(flagged, 0);
  EXPECT_EQ(c.step(std::numeric_limits<double>::quiet_NaN()), FaultType::invalid);
  EXPECT_EQ(c.step(1000.0), FaultType::saturation);
  FaultType last = FaultType::none;
  for (int k = 0; k < 200; ++k) last = c.step(50.0);
  EXPECT_EQ(last, FaultType::frozen);
}

TEST(SignalValidator, WithoutTheFrozenOrFollowTestAStillOrUnfollowingReadingIsNotFrozen) {
  // A reading that stops moving is frozen by the `frozen` test; one that does not follow its
  // moving reference by the `follow` test. tests = [spikes, noise] raises neither; [frozen,
  // spikes, noise] the still one only; the default tests both.
  struct Case {
    std::vector<std::string> tests;
    bool still_frozen, unfollowing_frozen;
  };
  for (const Case& e : {Case{{"spikes", "noise"}, false, false}, Case{{"frozen", "spikes", "noise"}, true, false},
                        Case{{}, true, true}}) {
    SignalValidator::Params p;
    p.noise_std = {1.0};
    p.reference = true;
    p.reference_noise_std = {1.0};
    if (!e.tests.empty()) p.tests = e.tests;
    OneValidatedChannel still(p, 1e-3), unfollowing(p, 1e-3);
    FaultType last_still = FaultType::none, last_unfollowing = FaultType::none;
    for (int k = 0; k < 500; ++k) {
      const double load = 100.0 + 200.0 * std::sin(0.01 * k);  // 200 N swings, 0.6 s period
      last_still = still.step(100.0, 100.0);
      // Alternating +-1 (d2 = +-4, so not stale by the frozen test; no spike, no noise) while the reference swings.
      last_unfollowing = unfollowing.step(100.0 + (k % 2 ? 1.0 : -1.0), load);
    }
    EXPECT_EQ(last_still, e.still_frozen ? FaultType::frozen : FaultType::none) << e.tests.size() << " tests";
    EXPECT_EQ(last_unfollowing, e.unfollowing_frozen ? FaultType::frozen : FaultType::none) << e.tests.size() << " tests";
  }
}

TEST(SignalValidator, ARunOnTheRestValueIsNoFrozenEvidenceButARunElsewhereStillIs) {
  // A foot force sensor whose driver reports an unloaded foot as exactly 0 N: loaded, it reads
  // 6 +- 1 alternating (sigma = 1, d2 = +-4; no spike where it lifts off); from tick f it is in
  // the air and reads 0; it lands at tick l and reads 10 +- 1. Without rest_value the window of
  // zeros is frozen on the tick the last nonzero d2 (d2(f + 1) = x(f - 1) = 7: 49, above the stale
  // bound) leaves it, f + n + 1, until the landing's d2(l) = 9; with rest_value 0 nothing is
  // flagged. Then it freezes at 11 from tick g: frozen on tick g + n - 2 either way (as in the
  // test above), since no reading of that window is at rest.
  for (const bool with_rest : {false, true}) {
    SignalValidator::Params p;
    p.noise_std = {1.0};
    p.window_s = 0.05;
    p.noise_margin = 1.0;  // the stale bound of the test above
    p.repeat_min_s = 1.0;  // the run of repeats off: the window's test alone
    if (with_rest) p.rest_value = {0.0};
    OneValidatedChannel c(p, 1e-3);
    const int n = static_cast<int>(c.validator.window_ticks());
    constexpr int kAir = 300, kLanding = 800, kFreeze = 1200;
    double last = 0.0;
    for (int k = 0; k < kFreeze + 200; ++k) {
      const bool air = k >= kAir && k < kLanding;
      const double alternating = k % 2 ? 1.0 : -1.0;
      if (k < kFreeze) last = air ? 0.0 : (k < kAir ? 6.0 : 10.0) + alternating;
      const FaultType expected = k >= kFreeze + n - 2                   ? FaultType::frozen
                                 : !with_rest && air && k >= kAir + n + 1 ? FaultType::frozen
                                                                          : FaultType::none;
      ASSERT_EQ(c.step(last), expected) << (with_rest ? "rest 0" : "no rest") << ", tick " << k;
    }
  }
}

TEST(SignalValidator, StuckAgainAtThePreviousEpisodesValueIsSaturationElsewhereFrozen) {
  // No limits given. A reading that alternates 6 +- 1 (sigma = 1, d2 = +-4: not stale) sticks at 11
  // from tick 100, moves again from 300, sticks at 11 from 500, moves from 700 and sticks at 11.001
  // from 900. Entering a stretch from 7, 5 gives d2 = 2, then -4, then 0: the window keeps d2 = 4,
  // 16 (sum 20, below the stale bound, 31.55) from tick s + n - 1 on; one tick earlier it also
  // holds the 16 before (36). The first stretch is frozen (one stuck value cannot tell a clip from a
  // freeze), the second saturation (a clip returns to its ceiling), the third frozen (another
  // value, by 1 mN: q = 0, so only an exact repeat is the same value). Moving, nothing is flagged.
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.window_s = 0.05;
  p.noise_margin = 1.0;  // the stale bound of the tests above
  p.repeat_min_s = 1.0;  // the run of repeats off: the window's test alone
  OneValidatedChannel c(p, 1e-3);
  const int n = static_cast<int>(c.validator.window_ticks());
  for (int k = 0; k < 1100; ++k) {
    const int start = k >= 900 ? 900 : k >= 500 && k < 700 ? 500 : k >= 100 && k < 300 ? 100 : -1;
    const double x = start < 0 ? 6.0 + (k % 2 ? 1.0 : -1.0) : start == 900 ? 11.001 : 11.0;
    FaultType expected = FaultType::none;
    if (start >= 0 && k >= start + n - 1) expected = start == 500 ? FaultType::saturation : FaultType::frozen;
    ASSERT_EQ(c.step(x), expected) << "tick " << k;
  }
}

TEST(SignalValidator, AReadingStuckOnItsRestValueIsFrozenWhenItsReferenceMoves) {
  // rest_value 0 keeps the frozen test off on exact zeros; the follow test still sees a reading
  // that stays at 0 while its reference (the load it should carry) swings by 200 N, and nothing
  // while the reference is 0 too (the foot in the air).
  SignalValidator::Params p;
  p.noise_std = {1.0};
  p.rest_value = {0.0};
  p.reference = true;
  p.reference_noise_std = {1.0};
  OneValidatedChannel c(p, 1e-3);
  int flagged_in_air = 0;
  for (int k = 0; k < 1000; ++k) flagged_in_air += c.step(0.0, 0.0) != FaultType::none;
  EXPECT_EQ(flagged_in_air, 0);
  FaultType last = FaultType::none;
  for (int k = 0; k < 500; ++k) last = c.step(0.0, 100.0 + 100.0 * std::sin(0.01 * k));
  EXPECT_EQ(last, FaultType::frozen);
}

TEST(SignalValidator, NoiseMarginKeepsAHealthySensorNoisierOrQuieterThanStatedUnflagged) {
  // A slow load with white noise of 1.3 and of 1 / 1.3 times the stated sigma = 1, 100 s at 1 kHz
  // (seed 41). With the default margin (1.5) none of the tests flags anything; with no margin the
  // noisier sensor raises the noise or spike test and the quieter one the frozen test (the bounds'
  // false-alarm target assumes sigma exactly). A tenfold noise burst is still noise with the
  // margin; a margin under 1 is a config error.
  constexpr unsigned kSeed = 41;
  std::printf("seed %u\n", kSeed);
  for (const double margin : {1.5, 1.0}) {
    for (const double ratio : {1.3, 1.0 / 1.3}) {
      SignalValidator::Params p;
      p.noise_std = {1.0};
      p.noise_margin = margin;
      OneValidatedChannel c(p, 1e-3);
      std::mt19937_64 rng(kSeed);
      std::normal_distribution<double> noise(0.0, ratio);
      int flagged = 0;
      for (int k = 0; k < 100000; ++k) {
        flagged += c.step(300.0 + 100.0 * std::sin(2.0 * std::numbers::pi * 0.5 * k * 1e-3) + noise(rng)) != FaultType::none;
      }
      std::printf("margin %.1f, noise x%.2f: %d ticks flagged\n", margin, ratio, flagged);
      if (margin > 1.0) {
        EXPECT_EQ(flagged, 0) << "noise x" << ratio;
      } else {
        EXPECT_GT(flagged, 0) << "noise x" << ratio;  // noisier: noise or spikes; quieter: frozen
      }
    }
  }
  SignalValidator::Params p;
  p.noise_std = {1.0};
  OneValidatedChannel c(p, 1e-3);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  FaultType last = FaultType::none;
  for (int k = 0; k < 300; ++k) last = c.step(300.0 + (k >= 100 ? 10.0 : 1.0) * noise(rng));
  EXPECT_EQ(last, FaultType::noise);
  p.noise_margin = 0.5;
  EXPECT_THROW(SignalValidator(p, StageContext(1e-3, "v", {{"signal", 1}})), ConfigError);
}

TEST(SignalValidator, AnUnknownOrRepeatedTestIsAConfigError) {
  Diagnostics d;
  (void)load_params<SignalValidator::Params>(Json::parse(R"({"tests": ["frozen", "spike", "frozen"]})"),
                                             "/stages/2/params", "signal_validator", d);
  ASSERT_EQ(d.errors().size(), 2u);
  EXPECT_EQ(d.errors()[0].path, "/stages/2/params/tests/1");
  EXPECT_NE(d.errors()[0].message.find("did you mean 'spikes'?"), std::string::npos);
  EXPECT_EQ(d.errors()[1].path, "/stages/2/params/tests/2");
  EXPECT_NE(d.errors()[1].message.find("twice"), std::string::npos);
}

TEST(SignalValidator, RefusesAWindowOfTooFewTicks) {
  SignalValidator::Params p;
  p.window_s = 0.005;
  EXPECT_THROW(SignalValidator(p, StageContext(1e-3, "v", {{"signal", 1}})), ConfigError);
}

}  // namespace
}  // namespace ftsense
