// signature_isolator: on noiseless residual families it blames exactly the faulty channel with
// its exact size, holds the verdict while the group is raised, never blames a neighbour whose
// residual the fault excites, and says "cannot judge" when two channels' signatures are parallel.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/signature_isolator.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::SignatureIsolator> {
  static Json params() { return Json{{"group_size", 3}}; }
  static std::size_t input_dim(std::string_view port) { return port == "signature" ? 9 : 3; }
  static double sample_period_s() { return 0.01; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      v[i] = port == "alarm" ? 0.0 : port == "signature" ? (i % 4 == 0 ? 1.0 : 0.0) : 0.5 * static_cast<double>(i);
    }
  }
};
INSTANTIATE_TYPED_TEST_SUITE_P(SignatureIsolation, PluginContract, ::testing::Types<generic::SignatureIsolator>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::SignatureIsolator;

// One group of three channels with leave-one-out relations r_i = x_i - sum_k C_ik x_k: a fault f
// on channel j moves r by f (e_j - C e_j), the columns of S = I - C.
struct Group {
  SignatureIsolator isolator;
  std::vector<double> r = std::vector<double>(3, 0.0), alarm = std::vector<double>(3, 0.0);
  std::vector<double> signature;
  std::vector<double> fault = std::vector<double>(3, 0.0), type = fault, estimate = fault, cannot = fault;

  Group(const std::vector<double>& s, double sigma = 1.0)
      : isolator(params(sigma), StageContext(0.01, "iso", {{"residual", 3}, {"alarm", 3}, {"signature", 9}})),
        signature(s) {
    isolator.reset();
  }
  static SignatureIsolator::Params params(double sigma) {
    SignatureIsolator::Params p;
    p.group_size = 3;
    p.residual_noise_std = {sigma};
    return p;
  }
  // The residuals of a fault of size f on channel j (j < 0: none), raised where |r| > 1.
  void fault_on(long j, double f) {
    for (std::size_t i = 0; i < 3; ++i) {
      r[i] = j < 0 ? 0.0 : f * signature[i * 3 + static_cast<std::size_t>(j)];
      alarm[i] = std::abs(r[i]) > 1.0 ? 1.0 : 0.0;
    }
    const std::span<const double> ins[] = {r, alarm, signature};
    const std::span<double> outs[] = {fault, type, estimate, cannot};
    isolator.step(StepIO{0.0, ins, outs});
  }
};

// S = I - C with C = [[0, .5, .5], [.5, 0, .5], [.5, .5, 0]]: every relation sees every channel.
const std::vector<double> kLeaveOneOut{1.0, -0.5, -0.5, -0.5, 1.0, -0.5, -0.5, -0.5, 1.0};

TEST(SignatureIsolator, BlamesExactlyTheFaultyChannelWithItsSize) {
  for (long j = 0; j < 3; ++j) {
    Group g(kLeaveOneOut);
    g.fault_on(j, 40.0);  // every residual moves: 40 on j, -20 on the others, all raised
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(g.fault[k], k == static_cast<std::size_t>(j) ? 1.0 : 0.0) << "fault on " << j << ", channel " << k;
      EXPECT_EQ(g.cannot[k], 0.0);
      EXPECT_EQ(g.type[k], fault_code(k == static_cast<std::size_t>(j) ? FaultType::unclassified : FaultType::none));
    }
    EXPECT_NEAR(g.estimate[static_cast<std::size_t>(j)], 40.0, 1e-12);
  }
}

TEST(SignatureIsolator, HoldsItsVerdictWhileTheGroupIsRaisedAndFreesItAfter) {
  Group g(kLeaveOneOut);
  g.fault_on(1, 40.0);
  ASSERT_EQ(g.fault[1], 1.0);
  // The fault grows (a drift): still channel 1, its size followed.
  g.fault_on(1, 60.0);
  EXPECT_EQ(g.fault[1], 1.0);
  EXPECT_NEAR(g.estimate[1], 60.0, 1e-12);
  // The group clears: released.
  g.fault_on(-1, 0.0);
  EXPECT_EQ(g.fault[1], 0.0);
  EXPECT_EQ(g.estimate[1], 0.0);
  // A later fault elsewhere is judged afresh.
  g.fault_on(2, -30.0);
  EXPECT_EQ(g.fault[2], 1.0);
  EXPECT_EQ(g.fault[1], 0.0);
  EXPECT_NEAR(g.estimate[2], -30.0, 1e-12);
}

TEST(SignatureIsolator, ParallelSignaturesCannotBeJudged) {
  // Channels 0 and 1 move the residuals alike (two sensors that always load together): a fault
  // on either is raised, nobody is blamed, the group says it cannot judge.
  const std::vector<double> s{1.0, 1.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0};
  Group g(s);
  g.fault_on(0, 40.0);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(g.fault[k], 0.0) << k;
    EXPECT_EQ(g.cannot[k], 1.0) << k;
  }
  // Channel 2's signature stands apart: isolated.
  Group h(s);
  h.fault_on(2, 40.0);
  EXPECT_EQ(h.fault[2], 1.0);
  EXPECT_EQ(h.cannot[2], 0.0);
}

TEST(SignatureIsolator, TheRunnerUpMustLeaveTheMarginMore) {
  // sigma = 1, T = 0.01 s, a day's false-alarm interval: alpha = T / interval, and the margin is
  // chi^2_1(1 - alpha) = z^2 with P(|Z| > z) = erfc(z / sqrt 2) = alpha.
  Group g(kLeaveOneOut);
  const double margin = g.isolator.isolation_margin();
  EXPECT_NEAR(std::erfc(std::sqrt(margin / 2.0)) / (0.01 / 86400.0), 1.0, 1e-6);
  // A fault of size f on channel 0 leaves channel 1's hypothesis E_1 = |z|^2 - <t_1, z>^2 / |t_1|^2
  // = f^2 (1.5 - 0.75^2 / 1.5) = 1.125 f^2 unexplained, channel 0's none: blamed when 1.125 f^2
  // clears the margin.
  const double f_edge = std::sqrt(margin / 1.125);
  Group below(kLeaveOneOut), above(kLeaveOneOut);
  below.fault_on(0, 0.99 * f_edge);
  above.fault_on(0, 1.01 * f_edge);
  EXPECT_EQ(below.fault[0], 0.0);
  EXPECT_EQ(below.cannot[0], 1.0);
  EXPECT_EQ(above.fault[0], 1.0);
}

TEST(SignatureIsolator, GroupsAreJudgedApartAndMustBeWhole) {
  SignatureIsolator::Params p;
  p.group_size = 2;
  EXPECT_THROW(SignatureIsolator(p, StageContext(0.01, "iso", {{"residual", 3}, {"alarm", 3}, {"signature", 6}})),
               ConfigError);
}

}  // namespace
}  // namespace ftsense
