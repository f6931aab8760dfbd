// UnmeasuredContactLoads: the plane relations of a sole's layout, and the loads of substituted
// channels from the sum and those relations, against exact values.

#include "ftsense/generic/unmeasured_contact_loads.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

namespace ftsense::generic {
namespace {

// SURALP's sole: four pads on a 0.24 m x 0.15 m rectangle (configs/suralp_robust.json).
const std::vector<std::array<double, 2>> kSole = {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}};

// Loads a + b x + c y of the sole's pads: what a rigid sole on equal pads carries.
std::array<double, 4> plane_loads(double a, double b, double c) {
  std::array<double, 4> n{};
  for (std::size_t i = 0; i < 4; ++i) n[i] = a + b * kSole[i][0] + c * kSole[i][1];
  return n;
}

// Both feet's fault-free statistics: the sum residual and each foot's relation alternate +-e.
void learn(UnmeasuredContactLoads& loads, double sum_error, double plane_error) {
  for (int k = 0; k < 200; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    loads.observe_sum(sign * sum_error);
    // A plane plus e on pads 1 and 4 and -e on 2 and 3: relation (N1 + N4 - N2 - N3) / 2 = 2e.
    auto n = plane_loads(250.0, 400.0, -300.0);
    n[0] += 0.5 * sign * plane_error;
    n[3] += 0.5 * sign * plane_error;
    n[1] -= 0.5 * sign * plane_error;
    n[2] -= 0.5 * sign * plane_error;
    loads.observe_foot(0, n);
    loads.observe_foot(1, n);
  }
}

TEST(UnmeasuredContactLoads, ARectangleOfFourPadsHasOneRelationTheirDiagonalsBalanced) {
  const UnmeasuredContactLoads loads(kSole, 4, 2);
  ASSERT_EQ(loads.relations_per_foot(), 1U);
  // (N1 + N4 - N2 - N3) / 2, up to its sign.
  const double s = loads.relation_weight(0, 0) > 0 ? 1.0 : -1.0;
  EXPECT_NEAR(s * loads.relation_weight(0, 0), 0.5, 1e-12);
  EXPECT_NEAR(s * loads.relation_weight(1, 0), -0.5, 1e-12);
  EXPECT_NEAR(s * loads.relation_weight(2, 0), -0.5, 1e-12);
  EXPECT_NEAR(s * loads.relation_weight(3, 0), 0.5, 1e-12);
}

TEST(UnmeasuredContactLoads, RelationsAreThePointsBeyondWhatAPlaneFits) {
  // Three points span a plane: nothing left. Three on a line: one (loads affine along it). Five: two.
  const std::vector<std::array<double, 2>> triangle = {{0.1, 0.0}, {-0.1, 0.05}, {-0.1, -0.05}};
  const std::vector<std::array<double, 2>> line = {{0.1, 0.0}, {0.0, 0.0}, {-0.2, 0.0}};
  std::vector<std::array<double, 2>> five = kSole;
  five.push_back({0.0, 0.0});
  EXPECT_EQ(UnmeasuredContactLoads(triangle, 3, 1).relations_per_foot(), 0U);
  EXPECT_EQ(UnmeasuredContactLoads(line, 3, 1).relations_per_foot(), 1U);
  EXPECT_EQ(UnmeasuredContactLoads(five, 5, 1).relations_per_foot(), 2U);
  EXPECT_EQ(UnmeasuredContactLoads({}, 4, 2).relations_per_foot(), 0U);
  // A point foot: one point, no relation.
  const std::vector<std::array<double, 2>> point = {{0.0, 0.0}};
  EXPECT_EQ(UnmeasuredContactLoads(point, 1, 4).relations_per_foot(), 0U);
}

TEST(UnmeasuredContactLoads, TheSumAloneSharesTheLeftoverEquallyWithinTheBounds) {
  UnmeasuredContactLoads loads({}, 4, 2);
  std::vector<double> n(8, 100.0);
  std::vector<char> unknown(8, 0);
  unknown[1] = unknown[6] = 1;
  std::vector<double> lower(8, 0.0);
  const std::vector<char> usable(2, 1);
  loads.solve(n, unknown, lower, usable, 300.0);
  EXPECT_EQ(n[1], 150.0);
  EXPECT_EQ(n[6], 150.0);
  EXPECT_EQ(n[0], 100.0);  // known loads are left as they are
  // A saturated pad carries at least its ceiling; the other takes what is left.
  lower[1] = 200.0;
  loads.solve(n, unknown, lower, usable, 300.0);
  EXPECT_EQ(n[1], 200.0);
  EXPECT_EQ(n[6], 100.0);
  // Nothing left (the total force below the known loads): no pad pulls.
  lower[1] = 0.0;
  loads.solve(n, unknown, lower, usable, -40.0);
  EXPECT_EQ(n[1], 0.0);
  EXPECT_EQ(n[6], 0.0);
}

TEST(UnmeasuredContactLoads, OnePadLostOnEachFootIsRecoveredExactlyFromTheirPlanes) {
  UnmeasuredContactLoads loads(kSole, 4, 2);
  learn(loads, 8.0, 14.0);
  const auto left = plane_loads(300.0, 900.0, 400.0);    // rolling onto the toes, to the left
  const auto right = plane_loads(200.0, -700.0, -200.0);  // on the heel, to the right
  std::vector<double> truth(left.begin(), left.end());
  truth.insert(truth.end(), right.begin(), right.end());
  const double total = [&] {
    double s = 0.0;
    for (double x : truth) s += x;
    return s;
  }();
  std::vector<char> unknown(8, 0);
  unknown[3] = unknown[6] = 1;  // l_foot/p4, r_foot/p3
  std::vector<double> n = truth;
  n[3] = n[6] = 0.0;
  const double known = total - truth[3] - truth[6];
  loads.solve(n, unknown, std::vector<double>(8, 0.0), std::vector<char>(2, 1), total - known);
  EXPECT_NEAR(n[3], truth[3], 1e-6) << "left heel pad";
  EXPECT_NEAR(n[6], truth[6], 1e-6) << "right heel pad";
  // The sum alone would have split their 2 x 103.0 N equally.
  EXPECT_GT(std::abs(truth[3] - truth[6]), 100.0);
}

TEST(UnmeasuredContactLoads, DisagreeingRelationsAreWeighedByTheirMeasuredErrors) {
  // A known left pad reads 20 N above the plane, so the left relation puts the lost left pad
  // 20 N low (d3 = -20); the right relation says d6 = 0; the total force, exact, says d3 + d6 = 0.
  // Learnt: the sum residual's variance e_s^2, each relation's e_p^2; a relation weighs a pad by
  // w = 1/2, so in newtons of that pad its equation has variance V = e_p^2 / w^2 = 4 e_p^2.
  // Least squares: (d3 + 20) / V + (d3 + d6) / e_s^2 = 0, d6 / V + (d3 + d6) / e_s^2 = 0, so
  // d6 = d3 + 20 and d3 = -20 (1/V + 1/e_s^2) / (1/V + 2/e_s^2).
  UnmeasuredContactLoads loads(kSole, 4, 2);
  const double e_s = 8.0, e_p = 14.0;
  learn(loads, e_s, e_p);
  const auto left = plane_loads(300.0, 900.0, 400.0);
  const auto right = plane_loads(200.0, -700.0, -200.0);
  std::vector<double> truth(left.begin(), left.end());
  truth.insert(truth.end(), right.begin(), right.end());
  std::vector<char> unknown(8, 0);
  unknown[3] = unknown[6] = 1;
  std::vector<double> n = truth;
  n[0] += 20.0;
  n[3] = n[6] = 0.0;
  const double leftover = truth[3] + truth[6];  // what the exact total force leaves the two
  loads.solve(n, unknown, std::vector<double>(8, 0.0), std::vector<char>(2, 1), leftover);
  const double v = 4.0 * e_p * e_p, s = e_s * e_s;
  const double d3 = -20.0 * (1.0 / v + 1.0 / s) / (1.0 / v + 2.0 / s);
  std::printf("d3 = %.4f N, d6 = %.4f N\n", d3, d3 + 20.0);
  EXPECT_NEAR(n[3] - truth[3], d3, 1e-6);
  EXPECT_NEAR(n[6] - truth[6], d3 + 20.0, 1e-6);
}

TEST(UnmeasuredContactLoads, DiagonalPadsOfOneFootShareWhatThePlaneLeavesThem) {
  UnmeasuredContactLoads loads(kSole, 4, 2);
  learn(loads, 8.0, 14.0);
  const auto left = plane_loads(300.0, 900.0, 400.0);
  std::vector<double> n(left.begin(), left.end());
  n.insert(n.end(), 4, 0.0);  // the right foot in the air
  const double pair = left[1] + left[2];
  n[1] = n[2] = 0.0;
  std::vector<char> unknown(8, 0);
  unknown[1] = unknown[2] = 1;
  std::vector<char> usable = {1, 0};
  loads.solve(n, unknown, std::vector<double>(8, 0.0), usable, pair);
  // N2 and N3 enter the relation alike: the plane fixes their sum only, and they share it.
  EXPECT_NEAR(n[1], 0.5 * pair, 1e-4);  // the free direction, kept by a ridge of 1e-9
  EXPECT_NEAR(n[2], 0.5 * pair, 1e-4);
}

TEST(UnmeasuredContactLoads, OneUnknownOrUnlearntRelationsLeaveItToTheSum) {
  const auto left = plane_loads(300.0, 900.0, 400.0);
  std::vector<double> truth(left.begin(), left.end());
  truth.insert(truth.end(), left.begin(), left.end());
  std::vector<char> unknown(8, 0);
  unknown[3] = 1;
  {
    // One unknown: the sum determines it (here 30 N above the plane's value).
    UnmeasuredContactLoads loads(kSole, 4, 2);
    learn(loads, 8.0, 14.0);
    std::vector<double> n = truth;
    loads.solve(n, unknown, std::vector<double>(8, 0.0), std::vector<char>(2, 1), truth[3] + 30.0);
    EXPECT_EQ(n[3], truth[3] + 30.0);
  }
  {
    // Two unknowns, but fewer than kMinSamples fault-free ticks seen: equal shares.
    UnmeasuredContactLoads loads(kSole, 4, 2);
    unknown[6] = 1;
    std::vector<double> n = truth;
    loads.solve(n, unknown, std::vector<double>(8, 0.0), std::vector<char>(2, 1), 500.0);
    EXPECT_EQ(n[3], 250.0);
    EXPECT_EQ(n[6], 250.0);
    // A foot not in full contact gives no relation either.
    learn(loads, 8.0, 14.0);
    loads.solve(n, unknown, std::vector<double>(8, 0.0), std::vector<char>(2, 0), 500.0);
    EXPECT_EQ(n[3], 250.0);
    EXPECT_EQ(n[6], 250.0);
  }
}

}  // namespace
}  // namespace ftsense::generic
