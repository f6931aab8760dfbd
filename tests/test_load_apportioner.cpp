// load_apportioner: with one unknown channel its virtual value is the sum's leave-one-out value
// exactly; two substituted pads on feet in full contact are set apart by their feet's planes
// exactly on loads that lie on them; without a plane (no layout, a foot's pad at its air level,
// relations not yet learnt) unknowns on two feet are not judged (NaN), and two diagonal pads of
// one foot share what the relations leave them equally.

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/generic/load_apportioner.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::LoadApportioner> {
  static Json params() {
    return {{"points_per_foot", 4},
            {"points", {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}}}};
  }
  static std::size_t input_dim(std::string_view port) { return port == "reference" ? 1 : 8; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      v[i] = port == "signal"      ? 100.0 + 10.0 * static_cast<double>(i)
             : port == "reference" ? 1100.0
             : port == "loadable"  ? 1.0
                                   : 0.0;
    }
  }
  static double sample_period_s() { return 1e-3; }
  // Small steps keep every channel standing and on the ground (substituted below 1/2, loadable
  // above): the not-a-number answers are tested below, on purpose.
  static double random_step() { return 0.01; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(LoadApportioner, PluginContract, ::testing::Types<generic::LoadApportioner>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::LoadApportioner;

// SURALP's sole: four pads on a 0.24 m x 0.15 m rectangle (configs/suralp_robust.json).
const std::vector<std::array<double, 2>> kApportionSole = {
    {0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}};

// Two feet of four pads, noise 2 N (b = z 1.5 2 = 17.1 N at one false alarm a day at 1 kHz).
LoadApportioner two_soles(bool with_layout) {
  LoadApportioner::Params p;
  p.points_per_foot = 4;
  if (with_layout) p.points = kApportionSole;
  p.noise_std = {2.0};
  return LoadApportioner(p, StageContext(1e-3, "apportion", {{"signal", 8}, {"reference", 1}}));
}

struct Tick {
  std::vector<double> x = std::vector<double>(8, 0.0);
  double reference = 0.0;
  std::vector<double> loadable = std::vector<double>(8, 1.0);
  std::vector<double> correction = std::vector<double>(8, 0.0);
  std::vector<double> substituted = std::vector<double>(8, 0.0);
  std::vector<double> flagged = std::vector<double>(8, 0.0);
};

std::vector<double> apportion(LoadApportioner& part, const Tick& tick) {
  std::vector<double> reference{tick.reference}, v(8);
  const std::span<const double> ins[] = {tick.x, reference, tick.loadable, tick.correction, tick.substituted,
                                         tick.flagged};
  const std::span<double> outs[] = {v};
  part.step(StepIO{0.0, ins, outs});
  return v;
}

// Loads a + b x + c y on a sole's pads: what a rigid sole on equal pads carries.
void plane_loads(std::vector<double>& x, std::size_t foot, double a, double b, double c) {
  for (std::size_t i = 0; i < 4; ++i) x[foot * 4 + i] = a + b * kApportionSole[i][0] + c * kApportionSole[i][1];
}

// Double support, both feet's loads on their planes, the reference their exact sum.
Tick double_support() {
  Tick t;
  plane_loads(t.x, 0, 280.0, 900.0, 300.0);
  plane_loads(t.x, 1, 220.0, -600.0, -500.0);
  double sum = 0.0;
  for (const double x : t.x) sum += x;
  t.reference = sum;
  return t;
}

// 200 healthy ticks in double support: the sum residual alternates +-10 N, each foot's relation
// +-5 N (pads 1 and 4 up, 2 and 3 down by 1.25 N).
void learn(LoadApportioner& part, double flagged) {
  for (int k = 0; k < 200; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    Tick t;
    plane_loads(t.x, 0, 300.0, 500.0, -400.0);
    plane_loads(t.x, 1, 250.0, -300.0, 200.0);
    for (const std::size_t j : {0U, 3U, 4U, 7U}) t.x[j] += 1.25 * sign;
    for (const std::size_t j : {1U, 2U, 5U, 6U}) t.x[j] -= 1.25 * sign;
    double sum = 0.0;
    for (const double x : t.x) sum += x;
    t.reference = sum - 10.0 * sign;
    t.flagged[5] = flagged;
    apportion(part, t);
  }
}

TEST(LoadApportioner, OneUnknownChannelIsTheSumsLeaveOneOutValue) {
  LoadApportioner part = two_soles(true);
  Tick t;
  t.x = {120.0, 80.0, 200.0, 150.0, 0.5, -1.0, 2.0, 0.0};
  t.loadable = {1, 1, 1, 1, 0, 0, 0, 0};  // the right foot in the air
  t.reference = 600.0;
  const auto v = apportion(part, t);
  EXPECT_DOUBLE_EQ(v[0], 600.0 - (80.0 + 200.0 + 150.0));
  EXPECT_DOUBLE_EQ(v[1], 600.0 - (120.0 + 200.0 + 150.0));
  EXPECT_DOUBLE_EQ(v[2], 600.0 - (120.0 + 80.0 + 150.0));
  EXPECT_DOUBLE_EQ(v[3], 600.0 - (120.0 + 80.0 + 200.0));
  for (std::size_t j = 4; j < 8; ++j) EXPECT_EQ(v[j], 0.0) << "a foot in the air carries nothing";
  // A corrected reading enters as corrected; a pad the sum would make negative is held at 0.
  t.correction[1] = 30.0;
  t.reference = 380.0;
  const auto w = apportion(part, t);
  EXPECT_DOUBLE_EQ(w[0], 0.0);  // 380 - (50 + 200 + 150) = -20
  EXPECT_DOUBLE_EQ(w[1], 0.0);  // its own correction is not its load: 380 - 470
  EXPECT_DOUBLE_EQ(w[2], 380.0 - (120.0 + 50.0 + 150.0));
  EXPECT_DOUBLE_EQ(w[3], 380.0 - (120.0 + 50.0 + 200.0));
  // No reference: nothing on a guess.
  t.reference = std::numeric_limits<double>::quiet_NaN();
  const auto u = apportion(part, t);
  EXPECT_TRUE(std::isnan(u[0]));
  EXPECT_EQ(u[4], 0.0);
}

TEST(LoadApportioner, TwoSubstitutedPadsOnFeetInFullContactAreSetApartByTheirPlanes) {
  LoadApportioner part = two_soles(true);
  learn(part, 0.0);
  std::printf("learnt: plane relation RMS %.4f N per foot\n", part.relations().relation_rms(0, 0));
  EXPECT_NEAR(part.relations().relation_rms(0, 0), 2.5, 1e-9);  // (1.25 * 4) / 2: W's entries are +-1/2
  // l_foot/p4 and r_foot/p3 substituted.
  Tick t = double_support();
  const double l4 = t.x[3], r3 = t.x[6], l2 = t.x[1];
  t.x[3] = 60.0;   // frozen
  t.x[6] = 40.0;   // frozen
  t.substituted[3] = 1.0;
  t.substituted[6] = 1.0;
  const auto v = apportion(part, t);
  std::printf("l4 %.3f (true %.3f), r3 %.3f (true %.3f), l2 %.3f (true %.3f) N\n", v[3], l4, v[6], r3, v[1], l2);
  EXPECT_NEAR(v[3], l4, 1e-6);
  EXPECT_NEAR(v[6], r3, 1e-6);
  // A third unknown: l_foot/p2 left out too; its plane still separates it from p4 (not diagonal).
  EXPECT_NEAR(v[1], l2, 1e-6);
  // Without the layout, the sum alone fixes only what the two carry together, on two feet: an
  // equal share between them would be no measure, so neither is judged.
  LoadApportioner sum_only = two_soles(false);
  learn(sum_only, 0.0);
  const auto e = apportion(sum_only, t);
  EXPECT_TRUE(std::isnan(e[3]));
  EXPECT_TRUE(std::isnan(e[6]));
  EXPECT_TRUE(std::isnan(e[0])) << "l_foot/p1 with l4 and r3 unknown: three on two feet";
  EXPECT_TRUE(std::isnan(e[4])) << "r_foot/p1 likewise";
}

TEST(LoadApportioner, TwoUnknownPadsOfOneFootShareWhatTheRelationsLeaveThemEqually) {
  Tick t = double_support();
  const double l1 = t.x[0], l4 = t.x[3];
  t.substituted[0] = 1.0;
  t.substituted[3] = 1.0;
  // Diagonal pads: the plane's relation weighs them alike, so only the sum parts them, and it
  // fixes only what they carry together (the other foot being known): each takes half, to the
  // solver's ridge (unmeasured_contact_loads.cpp: within 1e-4 N).
  LoadApportioner part = two_soles(true);
  learn(part, 0.0);
  const auto v = apportion(part, t);
  std::printf("diagonal pads: %.6f and %.6f N, half their sum %.6f N\n", v[0], v[3], 0.5 * (l1 + l4));
  EXPECT_NEAR(v[0], 0.5 * (l1 + l4), 1e-4);
  EXPECT_NEAR(v[3], 0.5 * (l1 + l4), 1e-4);
  EXPECT_GT(std::abs(l1 - l4), 100.0) << "the test's loads must differ for the share to be tested";
  // A neighbour on the same foot (not diagonal): the plane parts them exactly.
  t.substituted[3] = 0.0;
  t.substituted[1] = 1.0;
  const auto w = apportion(part, t);
  EXPECT_NEAR(w[0], l1, 1e-6);
  EXPECT_NEAR(w[1], t.x[1], 1e-6);
}

TEST(LoadApportioner, AFootWithAPadAtItsAirLevelOrUnlearntRelationsLeavesItToTheSumAlone) {
  Tick t = double_support();
  const double l4 = t.x[3], r3 = t.x[6];
  t.substituted[3] = 1.0;
  t.substituted[6] = 1.0;
  {
    // The right foot's heel has lifted: r_foot/p4 reads 10 N, below b = 17.1 N. Its plane is not
    // used; the left's sets l4, the sum gives r3 what is left.
    LoadApportioner part = two_soles(true);
    learn(part, 0.0);
    EXPECT_NEAR(part.loaded_above(7), 17.1176523, 1e-6);  // z 5.7058841 x 1.5 x 2 N
    Tick lifted = t;
    const double shift = 10.0 - lifted.x[7];
    lifted.x[7] = 10.0;
    lifted.reference += shift;
    const auto v = apportion(part, lifted);
    EXPECT_NEAR(v[3], l4, 1e-6);
    EXPECT_NEAR(v[6], r3, 1e-6);
    // Both feet's planes out (the left's p1 at its air level too): the sum alone, not judged.
    lifted.reference += 5.0 - lifted.x[0];
    lifted.x[0] = 5.0;
    const auto w = apportion(part, lifted);
    EXPECT_TRUE(std::isnan(w[3]));
    EXPECT_TRUE(std::isnan(w[6]));
  }
  {
    // Learnt while a pad was flagged: no sum statistic, so no plane; the sum alone, not judged.
    LoadApportioner part = two_soles(true);
    learn(part, 1.0);
    EXPECT_TRUE(std::isnan(part.relations().relation_rms(1, 0)));
    const auto v = apportion(part, t);
    EXPECT_TRUE(std::isnan(v[3]));
    part.reset();
    learn(part, 0.0);
    EXPECT_NEAR(apportion(part, t)[3], l4, 1e-6);
  }
}

}  // namespace
}  // namespace ftsense
