// onset_shape: a ramp (drift) is chosen over a step (offset) when its chi-square is lower by more
// than z^2 and it fits within the chi-square bound; exact values on small hand-checked traces
// (unit variances, so a chi-square is the sum of squared misfits). The ramp's chi-squares were
// checked once against a brute-force search over the onset (least squares on a grid of
// 200,001 onsets; a one-off script, not kept).

#include <array>
#include <cmath>
#include <limits>
#include <span>

#include <gtest/gtest.h>

#include "ftsense/generic/onset_shape.hpp"

namespace ftsense::generic {
namespace {

template <std::size_t N>
std::array<LevelPoint, N> unit_points(const std::array<double, N>& levels) {
  std::array<LevelPoint, N> p{};
  for (std::size_t i = 0; i < N; ++i) p[i] = {static_cast<double>(i), levels[i], 1.0};
  return p;
}

TEST(OnsetShape, AStepWithinAPointFitsAStepThatFellInsideABlock) {
  // 0, 0, 5, 10, 10: a step inside the third block (its mean half of it), exactly (k = 2).
  EXPECT_NEAR(step_within_a_point_chi2(unit_points<5>({0.0, 0.0, 5.0, 10.0, 10.0})), 0.0, 1e-12);
  // 0, 0, 3, 6, 9, a ramp: k = 1 leaves (3, 6, 9) about 6, 18; k = 2 leaves (6, 9) about 7.5, 4.5;
  // k = 3 leaves (0, 0, 3) about 1, 6. The least: 4.5.
  EXPECT_NEAR(step_within_a_point_chi2(unit_points<5>({0.0, 0.0, 3.0, 6.0, 9.0})), 4.5, 1e-12);
  // Too few points, or a level of no stated variance: no fit.
  EXPECT_TRUE(std::isinf(step_within_a_point_chi2(unit_points<2>({0.0, 1.0}))));
  auto p = unit_points<4>({0.0, 0.0, 1.0, 2.0});
  p[1].variance = 0.0;
  EXPECT_TRUE(std::isinf(step_within_a_point_chi2(p)));
}

TEST(OnsetShape, ALevelThatRisesAlongALineAfterHealthyOnesIsARampFromItsOnset) {
  // 5 per second from t0 = 2.4: levels 3 and 8 at t = 3 and 4. The best step (0, 0, 0, 3 | 8)
  // leaves 3 x 0.75^2 + 2.25^2 = 6.75; the ramp fits exactly.
  const auto p = unit_points<5>({0.0, 0.0, 0.0, 3.0, 8.0});
  const OnsetShape shape = onset_shape(p, 2.0);
  EXPECT_TRUE(shape.ramp);
  EXPECT_EQ(shape.first_faulty, 3u);
  EXPECT_NEAR(shape.onset_s, 2.4, 1e-12);
  EXPECT_NEAR(shape.slope, 5.0, 1e-12);
  EXPECT_NEAR(shape.healthy_level, 0.0, 1e-12);
  EXPECT_NEAR(shape.step_chi2, 6.75, 1e-12);
  EXPECT_NEAR(shape.ramp_chi2, 0.0, 1e-12);
  // The same evidence at z = 3 (6.75 < 9) is not enough: a step.
  const OnsetShape strict = onset_shape(p, 3.0);
  EXPECT_FALSE(strict.ramp);
  EXPECT_EQ(strict.first_faulty, 4u);
  EXPECT_NEAR(strict.step_chi2, 6.75, 1e-12);
}

TEST(OnsetShape, ALevelThatStepsAndStaysIsAStep) {
  const auto p = unit_points<5>({0.0, 0.0, 0.0, 10.0, 10.0});
  const OnsetShape shape = onset_shape(p, 2.0);
  EXPECT_FALSE(shape.ramp);
  EXPECT_EQ(shape.first_faulty, 3u);
  EXPECT_EQ(shape.onset_s, 3.0);
  EXPECT_NEAR(shape.step_chi2, 0.0, 1e-12);
  EXPECT_NEAR(shape.ramp_chi2, 50.0 / 3.0, 1e-9);  // the ramp's best: onset 5/3, 5 per second
}

TEST(OnsetShape, OneFaultyLevelAfterHealthyOnesIsAStepAsMuchAsARamp) {
  // Both fit exactly; ties go to the step.
  const auto p = unit_points<4>({1.0, 1.0, 1.0, 30.0});
  const OnsetShape shape = onset_shape(p, 1.0);
  EXPECT_FALSE(shape.ramp);
  EXPECT_EQ(shape.first_faulty, 3u);
  EXPECT_NEAR(shape.healthy_level, 1.0, 1e-12);
  EXPECT_NEAR(shape.step_chi2, 0.0, 1e-12);
}

TEST(OnsetShape, AStepInsideOneWindowIsNoRampThoughARampFitsItBetter) {
  // A level between (50: half the window healthy) then 100: the ramp's 1750 beats the step's 1875
  // by far more than z^2 = 4, but is no fit of 8 unit-variance points.
  const auto p = unit_points<8>({0.0, 0.0, 0.0, 0.0, 50.0, 100.0, 100.0, 100.0});
  const OnsetShape shape = onset_shape(p, 2.0);
  EXPECT_FALSE(shape.ramp);
  EXPECT_NEAR(shape.step_chi2, 1875.0, 1e-9);
  EXPECT_NEAR(shape.ramp_chi2, 1750.0, 1e-9);
}

TEST(OnsetShape, ALineWithNoHealthyLevelBeforeItIsARampOfItsSlope) {
  // The best step, (2, 4 | 6, 8), leaves 2 + 2 = 4: a ramp at z = 1.5 (4 > 2.25), a step at z = 3.
  const auto p = unit_points<4>({2.0, 4.0, 6.0, 8.0});
  const OnsetShape shape = onset_shape(p, 1.5);
  EXPECT_TRUE(shape.ramp);
  EXPECT_EQ(shape.first_faulty, 0u);
  EXPECT_NEAR(shape.slope, 2.0, 1e-12);
  EXPECT_NEAR(shape.step_chi2, 4.0, 1e-12);
  EXPECT_NEAR(shape.ramp_chi2, 0.0, 1e-12);
  EXPECT_FALSE(onset_shape(p, 3.0).ramp);
}

TEST(OnsetShape, TheVariancesWeighTheLevels) {
  // The same ramp as above, its levels known to a tenth of the unit: a chi-square 100 times larger
  // for the step, and the strict z = 3 now decides for the ramp.
  auto p = unit_points<5>({0.0, 0.0, 0.0, 3.0, 8.0});
  for (auto& point : p) point.variance = 0.01;
  const OnsetShape shape = onset_shape(p, 3.0);
  EXPECT_TRUE(shape.ramp);
  EXPECT_NEAR(shape.step_chi2, 675.0, 1e-9);
}

TEST(OnsetShape, FewerThanThreePointsAreAStep) {
  const auto p = unit_points<2>({0.0, 10.0});
  EXPECT_FALSE(onset_shape(p, 1.0).ramp);
  EXPECT_FALSE(onset_shape(std::span<const LevelPoint>{}, 1.0).ramp);
}

TEST(OnsetShape, AVarianceThatIsNoPositiveNumberMakesAStep) {
  // The ramp of the first test, one variance broken at a time.
  for (const double broken : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    auto p = unit_points<5>({0.0, 0.0, 0.0, 3.0, 8.0});
    p[1].variance = broken;
    EXPECT_FALSE(onset_shape(p, 2.0).ramp) << "variance " << broken;
  }
}

TEST(LevelHistory, KeepsTheLatestPointsOldestFirst) {
  LevelHistory history;
  const int pushed = static_cast<int>(LevelHistory::kCapacity) + 2;
  for (int i = 0; i < pushed; ++i) history.push({static_cast<double>(i), 0.0, 1.0});
  EXPECT_EQ(history.size(), LevelHistory::kCapacity);
  std::array<LevelPoint, LevelHistory::kCapacity> out{};
  ASSERT_EQ(history.ordered(out), LevelHistory::kCapacity);
  for (std::size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i].t_s, static_cast<double>(i + 2));
  history.clear();
  EXPECT_EQ(history.size(), 0u);
  EXPECT_EQ(history.ordered(out), 0u);
}

}  // namespace
}  // namespace ftsense::generic
