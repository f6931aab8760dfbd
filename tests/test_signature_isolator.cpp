// signature_isolator: on noiseless residual families it blames exactly the faulty channel with
// its exact size, holds the verdict while the group is raised, never blames a neighbour whose
// residual the fault excites, and says "cannot judge" when two channels' signatures are parallel;
// row weights count copies of one residual once; a second fault is blamed beside the first only
// when what the first leaves clears the margin on its own, with both sizes fitted jointly.

#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/signature_isolator.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::SignatureIsolator> {
  // Two faults a group, row weights and a raised alarm: the nominal and allocation checks run the
  // joint fit's path.
  static Json params() { return Json{{"group_size", 3}, {"max_faults", 2}, {"row_weights", true}}; }
  static std::size_t input_dim(std::string_view port) { return port == "signature" ? 9 : 3; }
  static double sample_period_s() { return 0.01; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      v[i] = port == "alarm"       ? 1.0
             : port == "signature"  ? (i % 4 == 0 ? 1.0 : 0.0)
             : port == "row_weight" ? 1.0
                                    : 0.5 * static_cast<double>(i);
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

TEST(SignatureIsolator, ABlamedChannelWhoseOwnRowClearsIsReleasedWhileTheGroupStaysRaised) {
  // Channel 1 blamed under the leave-one-out relations. Then its relation changes so that its row
  // sees only its own reading (a foot in the air: S row 1 = e_1), and that row is at 0 with its
  // detector down while channel 2's row stays raised (another fault): channel 1 is released on
  // that tick. With its row still seeing the others (the relations unchanged), it is held.
  for (const bool own_row : {true, false}) {
    Group g(kLeaveOneOut);
    g.fault_on(1, 40.0);
    ASSERT_EQ(g.fault[1], 1.0);
    if (own_row) g.signature = {1.0, -0.5, -0.5, 0.0, 1.0, 0.0, -0.5, -0.5, 1.0};
    g.r = {0.0, 0.0, 30.0};
    g.alarm = {0.0, 0.0, 1.0};
    const std::span<const double> ins[] = {g.r, g.alarm, g.signature};
    const std::span<double> outs[] = {g.fault, g.type, g.estimate, g.cannot};
    g.isolator.step(StepIO{0.01, ins, outs});
    EXPECT_EQ(g.fault[1], own_row ? 0.0 : 1.0) << (own_row ? "own row" : "shared row");
    if (own_row) {
      EXPECT_EQ(g.estimate[1], 0.0);
    }
  }
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
  p.max_faults = 3;  // more faults than a group has channels
  EXPECT_THROW(SignatureIsolator(p, StageContext(0.01, "iso", {{"residual", 4}, {"alarm", 4}, {"signature", 8}})),
               ConfigError);
}

// A group of four feet summing to a reference, as sum_constraint_residual gives it: a foot that
// can carry load has the sum residual as its row (signature all ones, weight 1 / L), a foot in
// the air its own reading (signature e_i, weight 1). Residuals of a fault f_j on each foot j.
struct Feet {
  SignatureIsolator isolator;
  std::vector<double> r = std::vector<double>(4, 0.0), alarm = std::vector<double>(4, 1.0);
  std::vector<double> signature = std::vector<double>(16, 0.0), weight = std::vector<double>(4, 0.0);
  std::vector<double> fault = std::vector<double>(4, 0.0), type = fault, estimate = fault, cannot = fault;

  explicit Feet(int max_faults, bool weights = true)
      : isolator(params(max_faults, weights),
                 StageContext(0.001, "iso",
                              {{"residual", 4}, {"alarm", 4}, {"signature", 16}, {"row_weight", weights ? 4u : 0u}})) {
    isolator.reset();
  }
  static SignatureIsolator::Params params(int max_faults, bool weights) {
    SignatureIsolator::Params p;
    p.group_size = 4;
    p.max_faults = max_faults;
    p.row_weights = weights;
    return p;
  }
  // One tick: which feet are in the air, each foot's fault, the sum residual's extra part (a
  // fault the feet's signatures do not carry); every residual raised unless `raised` is false.
  void tick(const std::array<bool, 4>& air, const std::array<double, 4>& f, double extra = 0.0,
            bool raised = true) {
    double sum = extra;
    std::size_t loaded = 0;
    for (std::size_t j = 0; j < 4; ++j) {
      sum += f[j];
      loaded += air[j] ? 0 : 1;
    }
    for (std::size_t i = 0; i < 4; ++i) {
      r[i] = air[i] ? f[i] : sum;
      weight[i] = air[i] ? 1.0 : 1.0 / static_cast<double>(loaded);
      alarm[i] = raised ? 1.0 : 0.0;
      for (std::size_t j = 0; j < 4; ++j) signature[i * 4 + j] = air[i] ? (i == j ? 1.0 : 0.0) : 1.0;
    }
    step();
  }
  // One step on the vectors as they stand.
  void step() {
    std::vector<std::span<const double>> ins{r, alarm, signature};
    if (isolator.ports().inputs().size() > 3) ins.emplace_back(weight);
    const std::span<double> outs[] = {fault, type, estimate, cannot};
    isolator.step(StepIO{0.0, ins, outs});
  }
};

TEST(SignatureIsolator, CopiesOfOneResidualCountOnceInTheFaultSize) {
  // Foot 2 in the air reads 40 N off; the loaded rows (the sum residual) read 44: 4 N more that no
  // foot's signature carries. Weighted, the sum counts once beside foot 2's own row: f = (44 + 40)
  // / 2 = 42. Unweighted, the three loaded rows would count three times: (3 x 44 + 40) / 4 = 43.
  const std::array<bool, 4> air{false, false, true, false};
  const std::array<double, 4> f{0.0, 0.0, 40.0, 0.0};
  Feet weighted(1), unweighted(1, false);
  weighted.tick(air, f, 4.0);
  unweighted.tick(air, f, 4.0);
  ASSERT_EQ(weighted.fault, (std::vector<double>{0, 0, 1, 0}));
  ASSERT_EQ(unweighted.fault, (std::vector<double>{0, 0, 1, 0}));
  EXPECT_NEAR(weighted.estimate[2], 42.0, 1e-12);
  EXPECT_NEAR(unweighted.estimate[2], 43.0, 1e-12);
}

TEST(SignatureIsolator, ASecondFaultIsBlamedBesideTheFirstWithBothSizesExact) {
  Feet feet(2);
  // Foot 0 in the air, 30 N off: blamed with its size.
  feet.tick({true, false, false, false}, {30.0, 0.0, 0.0, 0.0});
  ASSERT_EQ(feet.fault, (std::vector<double>{1, 0, 0, 0}));
  EXPECT_NEAR(feet.estimate[0], 30.0, 1e-12);
  // Foot 0 lands and foot 3 lifts, 20 N low: the sum reads 10, foot 3's own row -20. Foot 0's
  // column (the sum) leaves foot 3's row, which only foot 3 explains (feet 1 and 2 load as foot
  // 0 does: their columns are foot 0's, no candidates). Fitted jointly: 30 and -20.
  feet.tick({false, false, false, true}, {30.0, 0.0, 0.0, -20.0});
  EXPECT_EQ(feet.fault, (std::vector<double>{1, 0, 0, 1}));
  EXPECT_NEAR(feet.estimate[0], 30.0, 1e-12);
  EXPECT_NEAR(feet.estimate[3], -20.0, 1e-12);
  EXPECT_EQ(feet.cannot, (std::vector<double>(4, 0.0)));
  // Both land: their columns are alike. Foot 3 keeps the size it showed while apart, foot 0
  // takes what foot 3 leaves of the sum; foot 0 grows to 35 N: both stay blamed while the group
  // is raised, foot 0 followed, and both are free when it clears.
  feet.tick({false, false, false, false}, {35.0, 0.0, 0.0, -20.0});
  EXPECT_EQ(feet.fault, (std::vector<double>{1, 0, 0, 1}));
  EXPECT_NEAR(feet.estimate[0], 35.0, 1e-12);
  EXPECT_NEAR(feet.estimate[3], -20.0, 1e-12);
  feet.tick({false, false, false, false}, {0.0, 0.0, 0.0, 0.0}, 0.0, false);
  EXPECT_EQ(feet.fault, (std::vector<double>(4, 0.0)));
  EXPECT_EQ(feet.estimate, (std::vector<double>(4, 0.0)));

  // With one fault a group (the default), foot 3 is not blamed and nobody says cannot judge.
  Feet one(1);
  one.tick({true, false, false, false}, {30.0, 0.0, 0.0, 0.0});
  one.tick({false, false, false, true}, {30.0, 0.0, 0.0, -20.0});
  EXPECT_EQ(one.fault, (std::vector<double>{1, 0, 0, 0}));
  EXPECT_EQ(one.cannot, (std::vector<double>(4, 0.0)));
}

TEST(SignatureIsolator, AFurtherFaultMustItselfClearTheMargin) {
  // What foot 0 leaves is foot 3's own row, gain f3^2 (sigma 1, weight 1): blamed from the
  // margin up, and below it nobody is blamed or said to be unjudgeable.
  Feet probe(2);
  const double edge = std::sqrt(probe.isolator.isolation_margin());
  for (const double share : {0.99, 1.01}) {
    Feet feet(2);
    feet.tick({true, false, false, false}, {30.0, 0.0, 0.0, 0.0});
    feet.tick({false, false, false, true}, {30.0, 0.0, 0.0, -share * edge});
    EXPECT_EQ(feet.fault[3], share > 1.0 ? 1.0 : 0.0) << share;
    EXPECT_EQ(feet.cannot, (std::vector<double>(4, 0.0))) << share;
  }
}

TEST(SignatureIsolator, WhatTheBlamedLeaveOnAlikeFeetCannotBeJudged) {
  // Foot 0 blamed in the air; the three loaded feet's sum carries 50 N more that their alike
  // columns cannot tell apart: none is blamed, each says cannot judge, foot 0 stays blamed.
  Feet feet(2);
  feet.tick({true, false, false, false}, {30.0, 0.0, 0.0, 0.0});
  feet.tick({true, false, false, false}, {30.0, 0.0, 0.0, 0.0}, 50.0);
  EXPECT_EQ(feet.fault, (std::vector<double>{1, 0, 0, 0}));
  EXPECT_EQ(feet.cannot, (std::vector<double>{0, 1, 1, 1}));
  // Foot 0 is fitted on its own row and the sum alike (weight 1 each): (30 + 80) / 2.
  EXPECT_NEAR(feet.estimate[0], 55.0, 1e-12);
}

TEST(SignatureIsolator, NoFurtherVerdictWhileABlamedChannelIsUnseen) {
  // Foot 0 blamed; next tick no residual sees it (its column 0) while foot 3's row shows 20 N:
  // foot 0's fault cannot be taken out, so foot 3 is not blamed for what might be foot 0's; foot 0
  // stays blamed with its last size.
  Feet feet(2);
  feet.tick({true, false, false, false}, {30.0, 0.0, 0.0, 0.0});
  feet.tick({false, false, false, true}, {30.0, 0.0, 0.0, -20.0});
  Feet unseen(2);
  unseen.tick({true, false, false, false}, {30.0, 0.0, 0.0, 0.0});
  unseen.r = feet.r;
  unseen.signature = feet.signature;
  unseen.weight = feet.weight;
  // Feet 1 and 2 unseen too, so foot 3 is the only candidate (its gain on the raw z, 50, clears
  // the margin): only the rule keeps it from being blamed.
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 3; ++j) unseen.signature[i * 4 + j] = 0.0;
  }
  unseen.step();
  EXPECT_EQ(feet.fault, (std::vector<double>{1, 0, 0, 1}));  // seen: foot 3 blamed beside foot 0
  EXPECT_EQ(unseen.fault, (std::vector<double>{1, 0, 0, 0}));
  EXPECT_NEAR(unseen.estimate[0], 30.0, 1e-12);
  EXPECT_EQ(unseen.cannot, (std::vector<double>(4, 0.0)));
}

TEST(SignatureIsolator, ARowOfUnknownWeightIsLeftOut) {
  // Foot 2 in the air; the loaded rows' weight is not a number: only foot 2's own row is used,
  // so its size is its own reading's, 40, and the sum's 44 is not seen.
  Feet feet(1);
  const std::array<bool, 4> air{false, false, true, false};
  feet.tick(air, {0.0, 0.0, 40.0, 0.0}, 4.0);
  feet.weight = {std::nan(""), -1.0, 1.0, std::nan("")};
  feet.step();
  EXPECT_EQ(feet.fault, (std::vector<double>{0, 0, 1, 0}));
  EXPECT_NEAR(feet.estimate[2], 40.0, 1e-12);
}

}  // namespace
}  // namespace ftsense
