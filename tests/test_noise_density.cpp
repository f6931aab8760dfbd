// NoiseDensity: q = sqrt(mean(n_i T m_i^2)) over consecutive windows of w seconds, exact on small
// sequences; non-finite samples are left out of their window (which weighs by the time its
// samples cover), a partial window is dropped.

#include <cmath>

#include <gtest/gtest.h>

#include "ftsense/generic/noise_density.hpp"

namespace ftsense {
namespace {

using generic::NoiseDensity;

TEST(NoiseDensity, IsTheRmsOfWindowMeansTimesTheRootOfTheWindow) {
  NoiseDensity q(0.01, 0.04);  // 4 samples a window
  EXPECT_TRUE(std::isnan(q.density()));
  for (double r : {1.0, 1.0, 1.0, 1.0, 2.0, 4.0, 2.0, 4.0}) q.add(r);  // means 1 and 3
  EXPECT_EQ(q.windows(), 2u);
  EXPECT_NEAR(q.density(), std::sqrt(0.04 * (1.0 + 9.0) / 2.0), 1e-15);
}

TEST(NoiseDensity, AlternatingSamplesAverageOutInEvenWindows) {
  // +-s alternating (white at its fastest): every window of an even count has mean 0, so q = 0;
  // windows of 3 samples have means +-s / 3: q = sqrt(w) s / 3.
  NoiseDensity even(0.01, 0.04), odd(0.01, 0.03);
  for (int k = 0; k < 12; ++k) {
    even.add(k % 2 == 0 ? 2.0 : -2.0);
    odd.add(k % 2 == 0 ? 2.0 : -2.0);
  }
  EXPECT_EQ(even.density(), 0.0);
  EXPECT_EQ(odd.windows(), 4u);
  EXPECT_NEAR(odd.density(), std::sqrt(0.03) * 2.0 / 3.0, 1e-15);
}

TEST(NoiseDensity, LeavesNonFiniteSamplesOutAndDropsPartialWindows) {
  NoiseDensity q(0.01, 0.04);
  const double nan = std::nan("");
  for (double r : {nan, 2.0, 2.0, 2.0}) q.add(r);  // mean 2 over 3 finite samples: weight 3 T
  for (double r : {5.0, 5.0}) q.add(r);            // half a window ...
  q.break_sequence();                              // ... dropped at a reset
  for (double r : {nan, nan, nan, nan}) q.add(r);  // no finite sample: no window
  EXPECT_EQ(q.windows(), 1u);
  EXPECT_NEAR(q.density(), std::sqrt(0.03 * 4.0), 1e-15);
}

}  // namespace
}  // namespace ftsense
