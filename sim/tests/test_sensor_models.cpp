// Random numbers and fault injection on one force channel, against the definitions in
// sensor_models.hpp (exact comparisons with the truth where the definition is deterministic).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ftsense/sim/sensor_models.hpp"

using namespace ftsense::sim;
using ftsense::FaultType;

namespace {
constexpr std::uint64_t kSensorSeed = 42;
constexpr double kDt = 0.001;

double truth(std::int64_t k) { return 300.0 + 200.0 * std::sin(0.003 * static_cast<double>(k)); }

FaultSpec fault(FaultType t, double start, std::optional<double> end = std::nullopt) {
  FaultSpec f;
  f.channel = 5;
  f.type = t;
  f.start_s = start;
  f.end_s = end;
  return f;
}

struct Trace {
  std::vector<double> y;
  std::vector<FaultType> code;
};

Trace run(const FaultSpec& f, std::int64_t n = 4000, double noise = 0.0) {
  ForceChannelModel ch(f.channel, noise, {f}, kDt, kSensorSeed);
  Trace tr;
  for (std::int64_t k = 0; k < n; ++k) {
    const auto o = ch.step(k, truth(k));
    tr.y.push_back(o.value);
    tr.code.push_back(o.fault);
  }
  return tr;
}
}  // namespace

TEST(Rng, IsDeterministicAndStreamsDiffer) {
  std::printf("seed %llu\n", static_cast<unsigned long long>(kSensorSeed));
  Rng a(kSensorSeed, 1), b(kSensorSeed, 1), c(kSensorSeed, 2);
  for (int i = 0; i < 100; ++i) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    EXPECT_NE(x, c.normal());
  }
}

TEST(Rng, StandardMt19937_64AndUniformRange) {
  std::mt19937_64 e;  // the standard fixes its 10000th output
  e.discard(9999);
  EXPECT_EQ(e(), 9981545732273789042ULL);
  Rng r(kSensorSeed, 3);
  for (int i = 0; i < 10000; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
}

TEST(Rng, NormalHasUnitMomentsOverManySamples) {
  Rng r(kSensorSeed, 4);
  const int n = 200000;
  double s1 = 0, s2 = 0, s4 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal();
    s1 += x;
    s2 += x * x;
    s4 += x * x * x * x;
  }
  EXPECT_NEAR(s1 / n, 0.0, 0.01);
  EXPECT_NEAR(s2 / n, 1.0, 0.01);
  EXPECT_NEAR(s4 / n, 3.0, 0.05);
}

TEST(ForceChannel, NoiseOnlyWithoutFaults) {
  ForceChannelModel ch(0, 2.0, {}, kDt, kSensorSeed);
  double s2 = 0.0;
  for (std::int64_t k = 0; k < 20000; ++k) {
    const auto o = ch.step(k, truth(k));
    EXPECT_EQ(o.fault, FaultType::none);
    s2 += std::pow(o.value - truth(k), 2);
  }
  EXPECT_NEAR(std::sqrt(s2 / 20000), 2.0, 0.05);
}

TEST(ForceChannel, OffsetIsExactInsideItsWindowOnly) {
  auto f = fault(FaultType::offset, 1.0, 2.5);
  f.offset_N = 100.0;
  const Trace tr = run(f);
  for (std::int64_t k = 0; k < 4000; ++k) {
    const bool on = k >= 1000 && k < 2500;
    EXPECT_EQ(tr.y[k], truth(k) + (on ? 100.0 : 0.0)) << k;
    EXPECT_EQ(tr.code[k], on ? FaultType::offset : FaultType::none) << k;
  }
}

TEST(ForceChannel, DriftGrowsWithSlopeTimesElapsedTime) {
  auto f = fault(FaultType::drift, 1.0);
  f.slope_N_s = 15.0;
  const Trace tr = run(f);
  for (std::int64_t k = 0; k < 4000; ++k) {
    const double expect = k < 1000 ? 0.0 : 15.0 * (static_cast<double>(k - 1000) * kDt);
    EXPECT_NEAR(tr.y[k] - truth(k), expect, 1e-9) << k;
  }
  EXPECT_NEAR(tr.y[3999] - truth(3999), 15.0 * 2.999, 1e-9);
}

TEST(ForceChannel, FrozenAtValueAndAtLastValue) {
  auto f = fault(FaultType::frozen, 1.0, 3.0);
  f.value_N = 0.0;
  Trace tr = run(f);
  for (std::int64_t k = 1000; k < 3000; ++k) EXPECT_EQ(tr.y[k], 0.0);
  EXPECT_EQ(tr.y[3000], truth(3000));
  f.value_N.reset();
  tr = run(f, 4000, 2.0);  // with noise: holds the last noisy output before the start
  for (std::int64_t k = 1000; k < 3000; ++k) EXPECT_EQ(tr.y[k], tr.y[999]);
  EXPECT_NE(tr.y[3000], tr.y[999]);
  EXPECT_EQ(tr.code[1000], FaultType::frozen);
}

TEST(ForceChannel, GainMultipliesTheReading) {
  auto f = fault(FaultType::gain, 0.5);
  f.gain = 1.5;
  const Trace tr = run(f);
  for (std::int64_t k = 500; k < 4000; ++k) EXPECT_DOUBLE_EQ(tr.y[k], 1.5 * truth(k));
}

TEST(ForceChannel, NoiseBurstHasItsStandardDeviation) {
  auto f = fault(FaultType::noise, 0.0, 20.0);
  f.std_N = 40.0;
  const Trace tr = run(f, 20000);
  double s1 = 0, s2 = 0;
  for (std::int64_t k = 0; k < 20000; ++k) {
    s1 += tr.y[k] - truth(k);
    s2 += std::pow(tr.y[k] - truth(k), 2);
  }
  EXPECT_NEAR(s1 / 20000, 0.0, 1.0);
  EXPECT_NEAR(std::sqrt(s2 / 20000), 40.0, 1.0);
}

TEST(ForceChannel, SpikesAreSingleTicksOfTheAmplitudeAtTheRate) {
  auto f = fault(FaultType::spikes, 0.0);
  f.rate_hz = 20.0;
  f.amplitude_N = 250.0;
  const Trace tr = run(f, 50000);
  int spikes = 0;
  for (std::int64_t k = 0; k < 50000; ++k) {
    const double d = tr.y[k] - truth(k);
    if (d == 0.0) continue;
    ASSERT_NEAR(std::abs(d), 250.0, 1e-9) << k;
    ++spikes;
  }
  EXPECT_NEAR(spikes, 1000, 100);  // 20 Hz over 50 s
}

TEST(ForceChannel, InvalidIsNaN) {
  const Trace tr = run(fault(FaultType::invalid, 1.0, 1.2));
  for (std::int64_t k = 0; k < 4000; ++k) EXPECT_EQ(std::isnan(tr.y[k]), k >= 1000 && k < 1200) << k;
  EXPECT_EQ(tr.code[1100], FaultType::invalid);
}

TEST(ForceChannel, SaturationClamps) {
  auto f = fault(FaultType::saturation, 0.0);
  f.min_N = 150.0;
  f.max_N = 350.0;
  const Trace tr = run(f);
  for (std::int64_t k = 0; k < 4000; ++k) EXPECT_EQ(tr.y[k], std::clamp(truth(k), 150.0, 350.0));
}

TEST(ForceChannel, SameSeedSameOutputDifferentSeedDifferent) {
  auto f = fault(FaultType::spikes, 0.0);
  f.rate_hz = 50.0;
  f.amplitude_N = 10.0;
  const Trace a = run(f, 2000, 2.0), b = run(f, 2000, 2.0);
  EXPECT_EQ(a.y, b.y);
  ForceChannelModel other(f.channel, 2.0, {f}, kDt, kSensorSeed + 1);
  EXPECT_NE(other.step(0, truth(0)).value, a.y[0]);
}

TEST(ForceChannel, FrozenWithNoiseKeepsItsValueAsTheMeanAndTheNoiseAsTheSpread) {
  auto f = fault(FaultType::frozen, 1.0, 3.0);
  f.value_N = 250.0;
  f.std_N = 5.0;
  const Trace tr = run(f);
  double sum = 0.0, sum2 = 0.0;
  for (std::int64_t k = 1000; k < 3000; ++k) {
    sum += tr.y[k] - 250.0;
    sum2 += (tr.y[k] - 250.0) * (tr.y[k] - 250.0);
    EXPECT_EQ(tr.code[k], FaultType::frozen);
  }
  const double mean = sum / 2000.0, std = std::sqrt(sum2 / 2000.0 - mean * mean);
  // 2000 samples of N(0, 5^2): the mean within 4 standard errors (0.45 N), the spread within 10 %.
  EXPECT_LT(std::abs(mean), 4.0 * 5.0 / std::sqrt(2000.0));
  EXPECT_NEAR(std, 5.0, 0.5);
  EXPECT_NE(tr.y[1500], tr.y[1501]);  // not an exact repeat
}

TEST(ForceChannel, ResolutionQuantisesEveryReadingFaultsIncluded) {
  FaultSpec f = fault(FaultType::offset, 1.0, 2.0);
  f.offset_N = 12.3;
  ForceChannelModel ch(f.channel, 2.0, {f}, kDt, kSensorSeed, kDt, 5.0);
  ForceChannelModel exact(f.channel, 2.0, {f}, kDt, kSensorSeed);  // the same noise, not quantised
  for (std::int64_t k = 0; k < 3000; ++k) {
    const double y = ch.step(k, truth(k)).value;
    const double x = exact.step(k, truth(k)).value;
    EXPECT_EQ(y, 5.0 * std::round(x / 5.0)) << k;
    EXPECT_FALSE(std::signbit(y) && y == 0.0) << k;  // never -0
  }
  FaultSpec dropout = fault(FaultType::invalid, 0.0);
  ForceChannelModel nan_channel(dropout.channel, 2.0, {dropout}, kDt, kSensorSeed, kDt, 5.0);
  EXPECT_TRUE(std::isnan(nan_channel.step(0, 100.0).value));
}

TEST(ForceChannel, ZeroClampReadsExactZerosBelowItFaultsIncluded) {
  // An unloaded foot (true force 0) under 0.5 N noise with a 1.5 N clamp, then loaded at 50 N
  // with a -80 N offset on part of it: every reading is the unclamped one where that is at least
  // 1.5 N, else exactly 0 (the offset's negative readings too). After quantisation (q = 1).
  FaultSpec f = fault(FaultType::offset, 3.0, 3.5);
  f.offset_N = -80.0;
  ForceChannelModel ch(f.channel, 0.5, {f}, kDt, kSensorSeed, kDt, 1.0, 1.5);
  ForceChannelModel plain(f.channel, 0.5, {f}, kDt, kSensorSeed, kDt, 1.0);  // the same noise, no clamp
  int zeros_unloaded = 0;
  for (std::int64_t k = 0; k < 4000; ++k) {
    const double load = k < 2000 ? 0.0 : 50.0;
    const double y = ch.step(k, load).value;
    const double x = plain.step(k, load).value;
    EXPECT_EQ(y, x < 1.5 ? 0.0 : x) << k;
    EXPECT_FALSE(std::signbit(y)) << k;
    if (k < 2000) zeros_unloaded += y == 0.0;
    if (k >= 3000 && k < 3500) {
      EXPECT_EQ(y, 0.0) << k;  // 50 - 80 N clamped
    }
  }
  // Unloaded, a reading is nonzero only where 0.5 N noise rounds to 2 N or more: P(n >= 1.5) =
  // 0.13 %; of 2000 ticks at least 1990 read exactly 0.
  EXPECT_GE(zeros_unloaded, 1990);
  FaultSpec dropout = fault(FaultType::invalid, 0.0);
  ForceChannelModel nan_channel(dropout.channel, 0.5, {dropout}, kDt, kSensorSeed, kDt, 0.0, 1.5);
  EXPECT_TRUE(std::isnan(nan_channel.step(0, 100.0).value));
}
