// sum_constraint_residual: exact leave-one-out values, residuals and signatures on small cases,
// missing readings and references; composed by JSON with cusum_detector and signature_isolator on
// a trotting four-footed robot, it blames the faulty foot, and says "cannot judge" while the fault
// sits on a loaded foot whose loaded neighbour it cannot be told from.

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/generic/sum_constraint_residual.hpp"
#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::SumConstraintResidual> {
  static Json params() { return Json::object(); }
  static std::size_t input_dim(std::string_view port) { return port == "reference" ? 1 : 3; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = port == "reference" ? 30.0 : 10.0 + static_cast<double>(i);
  }
  static double sample_period_s() { return 1e-3; }
  static int settle_ticks() { return 1; }
  static double random_step() { return 1.0; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(SumConstraint, PluginContract, ::testing::Types<generic::SumConstraintResidual>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::SumConstraintResidual;

struct Outputs {
  std::vector<double> virtual_value, residual, signature, sum_residual, row_weight;
};

// One step of a stage of `channels` channels in groups of `group_size` (0: one group).
Outputs step_once(int group_size, bool with_loadable, const std::vector<double>& x, const std::vector<double>& reference,
                  const std::vector<double>& loadable = {}) {
  SumConstraintResidual::Params p;
  p.group_size = group_size;
  p.loadable = with_loadable;
  std::vector<std::pair<std::string, std::size_t>> dims{{"signal", x.size()}, {"reference", reference.size()}};
  if (with_loadable) dims.emplace_back("loadable", loadable.size());
  SumConstraintResidual stage(p, StageContext(1e-3, "sum", dims));
  stage.reset();
  const std::size_t g = group_size > 0 ? static_cast<std::size_t>(group_size) : x.size();
  Outputs o{std::vector<double>(x.size()), std::vector<double>(x.size()), std::vector<double>(x.size() * g),
            std::vector<double>(reference.size()), std::vector<double>(x.size())};
  std::vector<std::span<const double>> ins{x, reference};
  if (with_loadable) ins.emplace_back(loadable);
  const std::span<double> outs[] = {o.virtual_value, o.residual, o.signature, o.sum_residual, o.row_weight};
  stage.step(StepIO{0.0, ins, outs});
  return o;
}

TEST(SumConstraintResidual, LeaveOneOutValuesResidualsAndSignatureOfOneGroup) {
  // Reference 10 N, readings 2, 3, 4 N; channel 2 off the ground.
  const Outputs o = step_once(0, true, {2.0, 3.0, 4.0}, {10.0}, {1.0, 1.0, 0.0});
  EXPECT_EQ(o.virtual_value, (std::vector<double>{3.0, 4.0, 0.0}));  // 10 - (3 + 4), 10 - (2 + 4), airborne
  EXPECT_EQ(o.residual, (std::vector<double>{-1.0, -1.0, 4.0}));      // the sum residual, its own reading
  EXPECT_EQ(o.sum_residual, (std::vector<double>{-1.0}));
  EXPECT_EQ(o.signature, (std::vector<double>{1, 1, 1,  //
                                              1, 1, 1,  //
                                              0, 0, 1}));
  // The two loaded rows are one observation (the sum residual), the airborne row one of its own.
  EXPECT_EQ(o.row_weight, (std::vector<double>{0.5, 0.5, 1.0}));
}

TEST(SumConstraintResidual, WithoutLoadableEveryChannelIsJudgedOnTheSum) {
  const Outputs o = step_once(0, false, {2.0, 3.0, 4.0}, {10.0});
  EXPECT_EQ(o.virtual_value, (std::vector<double>{3.0, 4.0, 5.0}));
  EXPECT_EQ(o.residual, (std::vector<double>{-1.0, -1.0, -1.0}));
  EXPECT_EQ(o.signature, std::vector<double>(9, 1.0));
  EXPECT_EQ(o.row_weight, std::vector<double>(3, 1.0 / 3.0));
}

TEST(SumConstraintResidual, TheVirtualValueIsBoundedByWhatPhysicsAllowsTheResidualIsNot) {
  // Reference 4 N, readings 2, 3: channel 0's leave-one-out value 1 N, channel 1's 2 N; with a
  // floor of 1.5 N channel 0's virtual value is 1.5 N, and both residuals stay the sum residual.
  SumConstraintResidual::Params p;
  p.virtual_min = {1.5};
  SumConstraintResidual stage(p, StageContext(1e-3, "sum", {{"signal", 2}, {"reference", 1}}));
  std::vector<double> x{2.0, 3.0}, reference{4.0}, v(2), r(2), s(4), sum(1), w(2);
  const std::span<const double> ins[] = {x, reference};
  const std::span<double> outs[] = {v, r, s, sum, w};
  stage.step(StepIO{0.0, ins, outs});
  EXPECT_EQ(v, (std::vector<double>{1.5, 2.0}));
  EXPECT_EQ(r, (std::vector<double>{1.0, 1.0}));
  EXPECT_EQ(sum, (std::vector<double>{1.0}));
}

// With corrections (a recovery's, one tick late), each virtual value takes the others as
// corrected, x_i - c_i; the residuals stay the readings' own. Reference 10 N, readings 2, 3, 4 N,
// corrections 0.5, 1, 2:
//   v_0 = 10 - (3 - 1) - (4 - 2) = 6,  v_1 = 10 - (2 - 0.5) - (4 - 2) = 6.5,
//   v_2 = 10 - (2 - 0.5) - (3 - 1) = 6.5.
// Channel 2 off the ground: its virtual value is 0, the others' take it corrected as before.
TEST(SumConstraintResidual, CorrectionsReachTheOthersVirtualValuesNotTheResiduals) {
  for (const bool airborne : {false, true}) {
    SumConstraintResidual::Params p;
    p.loadable = true;
    p.correction = true;
    SumConstraintResidual stage(p, StageContext(1e-3, "sum", {{"signal", 3}, {"reference", 1}, {"loadable", 3},
                                                             {"correction", 3}, {"substituted", 3}}));
    ASSERT_EQ(stage.ports().inputs().size(), 5u);
    EXPECT_EQ(stage.ports().inputs()[3].name, "correction");
    EXPECT_EQ(stage.ports().inputs()[4].name, "substituted");
    std::vector<double> x{2.0, 3.0, 4.0}, reference{10.0}, loadable{1.0, 1.0, airborne ? 0.0 : 1.0},
        correction{0.5, 1.0, 2.0}, substituted{0.0, 0.0, 0.0}, v(3), r(3), s(9), sum(1), w(3);
    const std::span<const double> ins[] = {x, reference, loadable, correction, substituted};
    const std::span<double> outs[] = {v, r, s, sum, w};
    stage.step(StepIO{0.0, ins, outs});
    EXPECT_EQ(v, airborne ? (std::vector<double>{6.0, 6.5, 0.0}) : (std::vector<double>{6.0, 6.5, 6.5}));
    EXPECT_EQ(r, airborne ? (std::vector<double>{-1.0, -1.0, 4.0}) : (std::vector<double>{-1.0, -1.0, -1.0}));
    EXPECT_EQ(sum, (std::vector<double>{-1.0}));
    // Reading 2 substituted (or its correction not a number): it stands for nothing. On the ground
    // its load is unknown, so the others cannot be judged (NaN) while its own virtual value
    // stands; off the ground it carries 0, whatever it reads: v_0 = 10 - 2 - 0 = 8, v_1 = 8.5.
    for (const bool by_nan : {false, true}) {
      substituted[2] = by_nan ? 0.0 : 1.0;
      correction[2] = by_nan ? std::nan("") : 2.0;
      stage.step(StepIO{0.0, ins, outs});
      if (airborne) {
        EXPECT_EQ(v, (std::vector<double>{8.0, 8.5, 0.0}));
      } else {
        EXPECT_TRUE(std::isnan(v[0]) && std::isnan(v[1]));
        EXPECT_EQ(v[2], 6.5);
      }
      EXPECT_EQ(sum, (std::vector<double>{-1.0}));  // the readings' own
    }
  }
  // Without loadable, correction and substituted are the third and fourth inputs; a missing reading leaves its own
  // virtual value, taken from the others as corrected: 10 - (2 - 0.5) - (4 - 1) = 5.5.
  SumConstraintResidual::Params p;
  p.correction = true;
  SumConstraintResidual stage(p, StageContext(1e-3, "sum", {{"signal", 3}, {"reference", 1}, {"correction", 3},
                                                           {"substituted", 3}}));
  std::vector<double> x{2.0, std::nan(""), 4.0}, reference{10.0}, correction{0.5, 7.0, 1.0}, substituted(3, 0.0),
      v(3), r(3), s(9), sum(1), w(3);
  const std::span<const double> ins[] = {x, reference, correction, substituted};
  const std::span<double> outs[] = {v, r, s, sum, w};
  stage.step(StepIO{0.0, ins, outs});
  EXPECT_EQ(v[1], 5.5);
  EXPECT_TRUE(std::isnan(v[0]) && std::isnan(v[2]));
}

TEST(SumConstraintResidual, GroupsHaveTheirOwnReferences) {
  // Two groups of two: (1, 2) sum to 5, (3, 4) sum to 6.
  const Outputs o = step_once(2, false, {1.0, 2.0, 3.0, 4.0}, {5.0, 6.0});
  EXPECT_EQ(o.virtual_value, (std::vector<double>{3.0, 4.0, 2.0, 3.0}));
  EXPECT_EQ(o.residual, (std::vector<double>{-2.0, -2.0, 1.0, 1.0}));
  EXPECT_EQ(o.sum_residual, (std::vector<double>{-2.0, 1.0}));
  EXPECT_EQ(o.signature, std::vector<double>(8, 1.0));
  EXPECT_EQ(o.row_weight, std::vector<double>(4, 0.5));
}

TEST(SumConstraintResidual, AMissingReadingLeavesItsOwnVirtualValueAndNothingElseJudgedOnTheSum) {
  const double nan = std::nan("");
  const Outputs o = step_once(0, true, {2.0, nan, 4.0, 1.0}, {10.0}, {1.0, 1.0, 1.0, 0.0});
  EXPECT_TRUE(std::isnan(o.virtual_value[0]));
  EXPECT_EQ(o.virtual_value[1], 3.0);  // 10 - (2 + 4 + 1): what the others leave, for recovery
  EXPECT_TRUE(std::isnan(o.virtual_value[2]));
  EXPECT_EQ(o.virtual_value[3], 0.0);  // off the ground: known without the sum
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::isnan(o.residual[i])) << i;
  EXPECT_EQ(o.residual[3], 1.0);  // still judged on its own reading
  EXPECT_TRUE(std::isnan(o.sum_residual[0]));

  // Two missing: nobody's virtual value is known from the sum.
  const Outputs two = step_once(0, false, {nan, nan, 4.0}, {10.0});
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::isnan(two.virtual_value[i])) << i;
}

TEST(SumConstraintResidual, AnUnknownReferenceIsNotJudgedAndUnknownContactCountsAsLoadable) {
  const double nan = std::nan("");
  const Outputs o = step_once(0, true, {2.0, 3.0}, {nan}, {nan, 0.0});
  EXPECT_TRUE(std::isnan(o.virtual_value[0]));  // contact unknown: loadable, needs the reference
  EXPECT_TRUE(std::isnan(o.residual[0]));
  EXPECT_EQ(o.virtual_value[1], 0.0);
  EXPECT_EQ(o.residual[1], 3.0);
  EXPECT_TRUE(std::isnan(o.sum_residual[0]));
  EXPECT_EQ(o.row_weight, (std::vector<double>{1.0, 1.0}));  // one loaded row: the sum once
}

TEST(SumConstraintResidual, GroupsMustBeWholeAndOfTwoOrMore) {
  SumConstraintResidual::Params p;
  p.group_size = 3;
  EXPECT_THROW(SumConstraintResidual(p, StageContext(1e-3, "sum", {{"signal", 4}})), ConfigError);
  p.group_size = 0;
  EXPECT_THROW(SumConstraintResidual(p, StageContext(1e-3, "sum", {{"signal", 1}})), ConfigError);
}

// A four-footed robot trotting (period 1 s: feet 0 and 3 loaded in the first half, 1 and 2 in the
// second, each with half of a weight that rocks by 10 %), its reference (the total vertical
// force from an IMU) off by N(0, 3^2) N, the sensors' noise N(0, 0.5^2) N. Each fault adds its
// size to its foot's reading from its onset. The JSON pipeline: sum_constraint_residual ->
// cusum_detector (sigma 3 N, the larger of the two regimes; changes of 10 N; one false alarm a
// day) -> signature_isolator (up to `max_faults` a group, rows weighed by the sum's row_weight).
// Returns the time each foot is first blamed (-1: never) and fails the test if a foot is blamed
// before its fault; `cannot_judge_s` is how long foot 0 was reported "cannot judge".
struct TrotFault {
  int foot;
  double onset_s, size_N;
};
std::array<double, 4> first_blames(const std::vector<TrotFault>& faults, int max_faults, double& cannot_judge_s) {
  Json config = Json::parse(R"({
    "sample_period_s": 0.001,
    "inputs": {
      "force": {"columns": ["f0", "f1", "f2", "f3"], "unit": "N"},
      "total": {"columns": ["fz"], "unit": "N"},
      "contact": {"columns": ["c0", "c1", "c2", "c3"], "unit": "1"}
    },
    "stages": [
      {"name": "sum", "plugin": "sum_constraint_residual", "params": {"loadable": true},
       "inputs": {"signal": "input.force", "reference": "input.total", "loadable": "input.contact"}},
      {"name": "detect", "plugin": "cusum_detector",
       "params": {"noise_std": [3.0], "min_change": [10.0], "false_alarm_interval_s": 86400},
       "inputs": {"residual": "sum.residual"}},
      {"name": "isolate", "plugin": "signature_isolator",
       "params": {"group_size": 4, "residual_noise_std": [3.0], "row_weights": true},
       "inputs": {"residual": "sum.residual", "alarm": "detect.fault", "signature": "sum.signature",
                  "row_weight": "sum.row_weight"}}
    ]
  })");
  config["stages"][2]["params"]["max_faults"] = max_faults;
  Pipeline p = Pipeline::build(config, reference_plugins::registry());
  const SignalRef blamed = p.signal("isolate.fault");
  const SignalRef cannot = p.signal("isolate.cannot_judge");
  std::size_t force = 0, total = 0, contact = 0;
  for (std::size_t i = 0; i < p.inputs().size(); ++i) {
    if (p.inputs()[i].name == "force") force = i;
    if (p.inputs()[i].name == "total") total = i;
    if (p.inputs()[i].name == "contact") contact = i;
  }
  constexpr unsigned kSeed = 11;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> sensor_noise(0.0, 0.5), reference_error(0.0, 3.0);
  constexpr double kWeight = 130.0;
  std::array<double, 4> first{-1.0, -1.0, -1.0, -1.0};
  cannot_judge_s = 0.0;
  for (int k = 0; k < 8000; ++k) {
    const double t = k * 1e-3;
    const bool first_pair = std::fmod(t, 1.0) < 0.5;
    const double per_foot = 0.5 * kWeight * (1.0 + 0.1 * std::sin(2.0 * std::numbers::pi * 2.0 * t));
    double total_load = 0.0;
    std::array<double, 4> fault_since{-1.0, -1.0, -1.0, -1.0};
    for (int f = 0; f < 4; ++f) {
      const bool loaded = (f == 0 || f == 3) == first_pair;
      const double load = loaded ? per_foot : 0.0;
      total_load += load;
      double reading = load + sensor_noise(rng);
      for (const TrotFault& fault : faults) {
        if (fault.foot == f && t >= fault.onset_s) {
          reading += fault.size_N;
          fault_since[f] = fault.onset_s;
        }
      }
      p.input_values(force)[f] = reading;
      p.input_values(contact)[f] = loaded ? 1.0 : 0.0;
    }
    p.input_values(total)[0] = total_load + reference_error(rng);
    p.step(t);
    for (std::size_t f = 0; f < 4; ++f) {
      if (p.values(blamed)[f] == 0.0) continue;
      EXPECT_GE(fault_since[f], 0.0) << "healthy foot " << f << " blamed at t = " << t;
      if (fault_since[f] < 0.0) return first;
      if (first[f] < 0.0) first[f] = t;
    }
    if (p.values(cannot)[0] == 1.0) cannot_judge_s += 1e-3;
  }
  return first;
}

// One fault: when its foot is first blamed.
double first_blame(int faulty, double onset_s, double& cannot_judge_s) {
  return first_blames({{faulty, onset_s, 30.0}}, 1, cannot_judge_s)[static_cast<std::size_t>(faulty)];
}

TEST(SumConstraintResidual, ByJsonAFaultOnAFootInTheAirIsBlamedAtOnce) {
  // Foot 2 is in the air over [3.0, 3.5) s: its own row and the loaded feet's rows all move.
  double cannot_judge_s = 0.0;
  const double t = first_blame(2, 3.1, cannot_judge_s);
  std::printf("foot 2 blamed at %.3f s, the group unjudged for %.3f s\n", t, cannot_judge_s);
  EXPECT_GE(t, 3.1);
  EXPECT_LT(t, 3.15);
  EXPECT_LT(cannot_judge_s, 0.05);
}

TEST(SumConstraintResidual, ByJsonAFaultOnALoadedFootCannotBeJudgedUntilItsPartnerIsToldApart) {
  // Foot 0 is loaded over [3.0, 3.5) s with foot 3: both loaded columns explain the sum alike,
  // so the isolator says "cannot judge" until foot 0 lifts at 3.5 s (its reading stays 30 N).
  double cannot_judge_s = 0.0;
  const double t = first_blame(0, 3.1, cannot_judge_s);
  std::printf("foot 0 blamed at %.3f s, the group unjudged for %.3f s\n", t, cannot_judge_s);
  EXPECT_GE(t, 3.5);
  EXPECT_LT(t, 3.55);
  EXPECT_GT(cannot_judge_s, 0.3);
  EXPECT_LT(cannot_judge_s, 0.45);
}

TEST(SumConstraintResidual, ByJsonASecondFaultyFootIsBlamedBesideTheFirst) {
  // Foot 2 reads 30 N more from 3.1 s (in the air: blamed at once). Foot 1 reads 25 N less from
  // 4.2 s, while both are in the air: what foot 2 leaves shows on foot 1's own row, and with two
  // faults a group foot 1 is blamed beside foot 2. With one, foot 2's fault keeps the group raised
  // and foot 1 is never blamed.
  double cannot_judge_s = 0.0;
  const std::vector<TrotFault> faults{{2, 3.1, 30.0}, {1, 4.2, -25.0}};
  const std::array<double, 4> two = first_blames(faults, 2, cannot_judge_s);
  std::printf("max_faults 2: foot 2 blamed at %.3f s, foot 1 at %.3f s\n", two[2], two[1]);
  EXPECT_GE(two[2], 3.1);
  EXPECT_LT(two[2], 3.15);
  EXPECT_GE(two[1], 4.2);
  EXPECT_LT(two[1], 4.25);
  const std::array<double, 4> one = first_blames(faults, 1, cannot_judge_s);
  EXPECT_GE(one[2], 3.1);
  EXPECT_LT(one[2], 3.15);
  EXPECT_EQ(one[1], -1.0);
}

}  // namespace
}  // namespace ftsense
