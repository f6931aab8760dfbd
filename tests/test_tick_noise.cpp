// TickNoise: sigma = median(|d2|) / (0.67449 sqrt(6)) from the second differences of a reading,
// exact on small sequences; a step in the load barely moves it; exact repeats are left out; NaN
// breaks the sequence.

#include <cmath>

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

}  // namespace
}  // namespace ftsense
