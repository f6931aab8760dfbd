// plane_fit_residual: on four pads of a rectangle each row is x_j less the plane through the
// other three (r_1 = x_1 - x_2 - x_3 + x_4), zero on loads that lie on a plane, and a step on one
// pad moves its own row by the step and the others by -+ it; on five points a row is the
// leave-one-out residual of a least-squares plane; a foot not in full contact is not judged.

#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/generic/plane_fit_residual.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::PlaneFitResidual> {
  static Json params() {
    return {{"points_per_foot", 4},
            {"points", {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}}},
            {"loadable", true},
            {"substituted", true}};
  }
  static std::size_t input_dim(std::string_view) { return 8; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      v[i] = port == "signal" ? 100.0 + 10.0 * static_cast<double>(i) : port == "loadable" ? 1.0 : 0.0;
    }
  }
  static double sample_period_s() { return 1e-3; }
  // Readings of 1e-300 N are pads that have lifted: no foot is in full contact, no row has a value.
  static bool tiny_inputs_have_no_value() { return true; }
  // Small steps keep every pad loaded, on the ground and standing: the NaN rows are tested below.
  static double random_step() { return 0.01; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(PlaneFitResidual, PluginContract, ::testing::Types<generic::PlaneFitResidual>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::PlaneFitResidual;

const std::vector<std::array<double, 2>> kPlaneSole = {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}};

// Two feet, noise 2 N: a pad counts as loaded above z 1.5 2 = 17.12 N (z = 5.706: one false alarm a
// day at 1 kHz).
PlaneFitResidual plane_two_feet(bool loadable, bool substituted) {
  PlaneFitResidual::Params p;
  p.points = kPlaneSole;
  p.loadable = loadable;
  p.substituted = substituted;
  p.noise_std = {2.0};
  return PlaneFitResidual(p, StageContext(1e-3, "plane", {{"signal", 8}}));
}

std::vector<double> plane_rows(PlaneFitResidual& part, const std::vector<std::vector<double>>& inputs) {
  std::vector<double> r(inputs[0].size());
  std::vector<std::span<const double>> ins(inputs.begin(), inputs.end());
  const std::span<double> outs[] = {r};
  part.step(StepIO{0.0, ins, outs});
  return r;
}

TEST(PlaneFitResidual, ARectanglesRowIsItsPadLessThePlaneThroughTheOtherThree) {
  PlaneFitResidual part = plane_two_feet(false, false);
  EXPECT_NEAR(part.loaded_above(0), 17.12, 0.01);
  // Left foot on a plane a + b x + c y; right foot off it by 12 N on pad 2.
  std::vector<double> x(8);
  for (std::size_t i = 0; i < 4; ++i) {
    x[i] = 300.0 + 500.0 * kPlaneSole[i][0] - 400.0 * kPlaneSole[i][1];
    x[4 + i] = 250.0 - 300.0 * kPlaneSole[i][0] + 200.0 * kPlaneSole[i][1];
  }
  x[5] += 12.0;
  const auto r = plane_rows(part, {x});
  for (std::size_t j = 0; j < 4; ++j) EXPECT_NEAR(r[j], 0.0, 1e-9) << "loads on a plane leave no residual";
  // r_1 = x_1 - x_2 - x_3 + x_4 and its kin: pad 2's 12 N is +12 in its own row, -+12 in the others.
  EXPECT_NEAR(r[4], x[4] - x[5] - x[6] + x[7], 1e-9);
  EXPECT_NEAR(r[4], -12.0, 1e-9);
  EXPECT_NEAR(r[5], 12.0, 1e-9);
  EXPECT_NEAR(r[6], 12.0, 1e-9);
  EXPECT_NEAR(r[7], -12.0, 1e-9);
  EXPECT_NEAR(part.row_weight(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(part.row_weight(0, 1), -1.0, 1e-12);
  EXPECT_NEAR(part.row_weight(0, 2), -1.0, 1e-12);
  EXPECT_NEAR(part.row_weight(0, 3), 1.0, 1e-12);
}

TEST(PlaneFitResidual, OnFivePointsARowIsTheLeaveOneOutResidualOfALeastSquaresPlane) {
  // A rectangle and a point off its centre: two relations.
  const std::vector<std::array<double, 2>> points = {
      {0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}, {0.03, 0.01}};
  PlaneFitResidual::Params p;
  p.points_per_foot = 5;
  p.points = points;
  p.noise_std = {2.0};
  PlaneFitResidual part(p, StageContext(1e-3, "plane", {{"signal", 5}}));
  const std::vector<double> x = {310.0, 190.0, 260.0, 205.0, 280.0};
  const auto r = plane_rows(part, {x});
  // The oracle: for each j, fit a + b x + c y to the other four by the normal equations (3 x 3,
  // Cramer's rule) and evaluate it at point j.
  for (std::size_t j = 0; j < 5; ++j) {
    double m[3][3] = {}, rhs[3] = {};
    for (std::size_t k = 0; k < 5; ++k) {
      if (k == j) continue;
      const double row[3] = {1.0, points[k][0], points[k][1]};
      for (int a = 0; a < 3; ++a) {
        rhs[a] += row[a] * x[k];
        for (int b = 0; b < 3; ++b) m[a][b] += row[a] * row[b];
      }
    }
    const auto det = [](const double (&q)[3][3]) {
      return q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
             q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
    };
    const double d = det(m);
    double coef[3];
    for (int c = 0; c < 3; ++c) {
      double q[3][3];
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) q[a][b] = b == c ? rhs[a] : m[a][b];
      }
      coef[c] = det(q) / d;
    }
    const double fitted = coef[0] + coef[1] * points[j][0] + coef[2] * points[j][1];
    EXPECT_NEAR(r[j], x[j] - fitted, 1e-8) << "point " << j;
  }
}

TEST(PlaneFitResidual, AFootNotInFullContactIsNotJudged) {
  PlaneFitResidual part = plane_two_feet(true, true);
  std::vector<double> x = {200.0, 180.0, 220.0, 205.0, 150.0, 160.0, 140.0, 155.0};
  std::vector<double> loadable(8, 1.0), substituted(8, 0.0);
  auto r = plane_rows(part, {x, loadable, substituted});
  for (const double v : r) EXPECT_TRUE(std::isfinite(v));
  // A pad within its noise margin of zero may have lifted: 17.0 N < 17.12 N.
  x[2] = 17.0;
  r = plane_rows(part, {x, loadable, substituted});
  for (std::size_t j = 0; j < 4; ++j) EXPECT_TRUE(std::isnan(r[j])) << "left row " << j;
  for (std::size_t j = 4; j < 8; ++j) EXPECT_TRUE(std::isfinite(r[j])) << "right row " << j;
  x[2] = 17.2;  // above it
  r = plane_rows(part, {x, loadable, substituted});
  EXPECT_NEAR(r[0], 200.0 - 180.0 - 17.2 + 205.0, 1e-9);
  // A pad off the ground by kinematics, a substituted reading, a reading that is not a number.
  loadable[5] = 0.0;
  r = plane_rows(part, {x, loadable, substituted});
  for (std::size_t j = 4; j < 8; ++j) EXPECT_TRUE(std::isnan(r[j]));
  EXPECT_TRUE(std::isfinite(r[0]));
  loadable[5] = 1.0;
  substituted[1] = 1.0;
  r = plane_rows(part, {x, loadable, substituted});
  for (std::size_t j = 0; j < 4; ++j) EXPECT_TRUE(std::isnan(r[j]));
  for (std::size_t j = 4; j < 8; ++j) EXPECT_TRUE(std::isfinite(r[j]));
  substituted[1] = 0.0;
  x[7] = std::numeric_limits<double>::quiet_NaN();
  r = plane_rows(part, {x, loadable, substituted});
  for (std::size_t j = 4; j < 8; ++j) EXPECT_TRUE(std::isnan(r[j]));
  EXPECT_TRUE(std::isfinite(r[3]));
}

TEST(PlaneFitResidual, PointsThatLeaveNoRelationAreAConfigError) {
  PlaneFitResidual::Params p;
  p.points_per_foot = 3;
  p.points = {{0.1, 0.05}, {0.1, -0.05}, {-0.1, 0.0}};
  EXPECT_THROW(PlaneFitResidual(p, StageContext(1e-3, "plane", {{"signal", 6}})), ConfigError);
  p.points_per_foot = 4;
  p.points = {{0.1, 0.0}, {0.05, 0.0}, {-0.05, 0.0}, {-0.1, 0.0}};  // on a line: a line's loads are any
  // Four points on a line: P = [1 x 0] has rank 2, two relations, and each row is finite.
  EXPECT_NO_THROW(PlaneFitResidual(p, StageContext(1e-3, "plane", {{"signal", 4}})));
  p.points = {{0.1, 0.0}, {0.05, 0.0}, {-0.05, 0.0}};  // three points for a foot of four
  EXPECT_THROW(PlaneFitResidual(p, StageContext(1e-3, "plane", {{"signal", 4}})), ConfigError);
}

}  // namespace
}  // namespace ftsense
