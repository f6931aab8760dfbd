// TickNoise: sigma = median(|d2|) / (0.67449 sqrt(6)) from the second differences of a reading,
// exact on small sequences; a step in the load barely moves it; exact repeats are left out; NaN
// breaks the sequence. Quantised readings: the step found, the noise from the share of changes
// (below half a step) or from the binned second differences less q^2 / 12 (above), on synthetic
// quantised noise with fixed seeds; C(r) against its definition.

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/generic/tick_noise.hpp"

namespace ftsense {
namespace {

using generic::TickNoise;

const double kScale = 0.6744897501960817 * std::sqrt(6.0);

TEST(TickNoise, AlternatingNoiseOnAConstantLoad) {
  // x = 5 + 2 (-1)^k: every d2 is +-8, so sigma = 8 / (0.67449 sqrt 6).
  TickNoise q;
  EXPECT_TRUE(std::isnan(q.standard_deviation()));
  for (int k = 0; k < 20; ++k) q.add(5.0 + (k % 2 == 0 ? 2.0 : -2.0));
  EXPECT_EQ(q.count(), 18u);
  EXPECT_NEAR(q.standard_deviation(), 8.0 / kScale, 1e-12);
}

TEST(TickNoise, SlowMotionIsRemovedAndAStepBarelyCounts) {
  // A ramp of 3 per tick (d2 = 0) under the same noise, with a 100 step at k = 10: the step puts
  // two large d2 among 28; the median is still 8.
  TickNoise q;
  for (int k = 0; k < 30; ++k) q.add(3.0 * k + (k >= 10 ? 100.0 : 0.0) + (k % 2 == 0 ? 2.0 : -2.0));
  EXPECT_NEAR(q.standard_deviation(), 8.0 / kScale, 1e-12);
}

TEST(TickNoise, ExactRepeatsAreLeftOut) {
  // Half the log reads exactly 0 (a foot in the air), half 5 + 2 (-1)^k: only the d2 of the noisy
  // half (and the two at the change) count, so sigma is still 8 / (0.67449 sqrt 6); a reading
  // that only repeats has no noise to see.
  TickNoise q, flat;
  for (int k = 0; k < 40; ++k) q.add(k < 20 ? 0.0 : 5.0 + (k % 2 == 0 ? 2.0 : -2.0));
  for (int k = 0; k < 40; ++k) flat.add(3.0);
  EXPECT_NEAR(q.standard_deviation(), 8.0 / kScale, 1e-12);
  EXPECT_TRUE(std::isnan(flat.standard_deviation()));
}

TEST(TickNoise, EvenCountsTakeTheMiddlePairAndNaNBreaksTheSequence) {
  // 0, 0, 1 gives d2 = 1; then NaN; then 0, 0, 3 gives d2 = 3: median (1 + 3) / 2 = 2.
  TickNoise q;
  for (double x : {0.0, 0.0, 1.0, std::nan(""), 0.0, 0.0, 3.0}) q.add(x);
  EXPECT_EQ(q.count(), 2u);
  EXPECT_NEAR(q.standard_deviation(), 2.0 / kScale, 1e-15);
}

TEST(TickNoise, ChangeProbabilityOfAQuantisedReading) {
  // Small r: only the step boundary nearest u matters, and C(r) -> 2 r / sqrt(pi) (the integral
  // of 2 Phi(t) (1 - Phi(t)) over t is 2 / sqrt(pi)). Large r: 1 - C(r) -> 1 / (2 r sqrt(pi))
  // (sum_l p_l^2 ~ q / (2 sigma sqrt(pi))).
  EXPECT_NEAR(TickNoise::change_probability(0.01), 2.0 * 0.01 / std::sqrt(M_PI), 1e-5);
  EXPECT_NEAR(TickNoise::change_probability(0.05), 2.0 * 0.05 / std::sqrt(M_PI), 1e-4);
  EXPECT_NEAR(1.0 - TickNoise::change_probability(20.0), 1.0 / (2.0 * 20.0 * std::sqrt(M_PI)), 1e-5);
  // The closed form against the definition 1 - E_u[sum_l p_l(u)^2], by midpoint quadrature over u.
  for (double r : {0.05, 0.2, 0.5, 1.0, 3.0}) {
    const auto cdf = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
    double stay = 0.0;
    constexpr int kPlaces = 4000;
    for (int i = 0; i < kPlaces; ++i) {
      const double u = (i + 0.5) / kPlaces;
      for (int l = -40; l <= 40; ++l) {
        const double p = cdf((l + 0.5 - u) / r) - cdf((l - 0.5 - u) / r);
        stay += p * p / kPlaces;
      }
    }
    EXPECT_NEAR(TickNoise::change_probability(r), 1.0 - stay, 1e-6) << "r = " << r;
  }
  // Increasing, and the inverse returns r.
  double before = 0.0;
  for (double r : {0.02, 0.1, 0.3, 0.5, 1.0, 3.0, 10.0}) {
    const double c = TickNoise::change_probability(r);
    EXPECT_GT(c, before) << "r = " << r;
    before = c;
    EXPECT_NEAR(TickNoise::noise_over_step(c), r, 1e-6 * r) << "r = " << r;
  }
}

// x = q round((s + n) / q), n ~ N(0, sigma^2), s a slow triangle sweep over 14.6 steps (so the
// place u within a step is uniform), interrupted by 2000 readings clamped at 0 (an unloaded foot).
std::vector<double> quantised_sweep(double sigma, double q, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> x;
  for (int k = 0; k < 40000; ++k) {
    if (k >= 20000 && k < 22000) {
      x.push_back(0.0);
      continue;
    }
    const double phase = std::fmod(k / 20000.0, 1.0);
    const double s = 100.0 + 14.6 * q * (phase < 0.5 ? 2.0 * phase : 2.0 - 2.0 * phase);
    x.push_back(q * std::round((s + noise(rng)) / q));
  }
  return x;
}

TEST(TickNoise, QuantisedNoiseBelowAndAboveAStep) {
  constexpr unsigned kSeed = 20261127;
  std::printf("TickNoise quantised sweeps: seed %u\n", kSeed);
  for (double r : {0.01, 0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 1.0, 2.0, 5.0}) {
    for (double q : {1.0, 5.0}) {
      TickNoise t;
      for (double x : quantised_sweep(r * q, q, kSeed)) t.add(x);
      EXPECT_NEAR(t.resolution(), q, 1e-12 * q) << "r = " << r;
      std::printf("  q %g r %g: sigma %.4f (true %.4f)\n", q, r, t.standard_deviation(), r * q);
      EXPECT_NEAR(t.standard_deviation() / (r * q), 1.0, 0.1) << "q = " << q << ", r = " << r;
    }
  }
}

TEST(TickNoise, ANoiselessRampOnALatticeWithAnOffsetAndAClamp) {
  // Levels 0.3 + 2 k up and down a triangle, each held 50 readings (a slow load, no noise), with
  // a clamp to 0 for 300 readings every 8000 (10 changes off the lattice among about 800): the
  // step is 2, and the noise is found far below it (no change but the load's own), not refused.
  TickNoise t;
  for (int k = 0; k < 40000; ++k) {
    const int level = (k / 50) % 40 < 20 ? (k / 50) % 40 : 40 - (k / 50) % 40;
    t.add(k % 8000 < 300 ? 0.0 : 0.3 + 2.0 * level);
  }
  EXPECT_NEAR(t.resolution(), 2.0, 1e-12);
  EXPECT_GT(t.count(), 0u);
  EXPECT_LT(t.standard_deviation(), 0.05 * 2.0);
}

TEST(TickNoise, AContinuousReadingHasNoStep) {
  // The same sweep without quantisation: no lattice, and sigma from the plain median.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.5);
  TickNoise t;
  for (int k = 0; k < 20000; ++k) t.add(100.0 + 30.0 * std::sin(2.0 * M_PI * k / 20000.0) + noise(rng));
  EXPECT_EQ(t.resolution(), 0.0);
  EXPECT_NEAR(t.standard_deviation(), 1.5, 0.05);
}

}  // namespace
}  // namespace ftsense
