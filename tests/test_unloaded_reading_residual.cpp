// unloaded_reading_residual: judged on the exact ticks; composed by JSON with cusum_detector, it
// isolates a pad that reads a load in swing and holds its verdict through stance.

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/generic/unloaded_reading_residual.hpp"
#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::UnloadedReadingResidual> {
  static Json params() { return Json::object(); }
  static std::size_t input_dim(std::string_view) { return 3; }
  // Unloaded pads: judged (finite) once settled; loaded ones are NaN by design ("not judged").
  static void nominal_input(std::string_view port, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = port == "loadable" ? 0.0 : 1.0 + 0.25 * static_cast<double>(i);
  }
  static double sample_period_s() { return 1e-3; }
  static int settle_ticks() { return 20; }      // settle_s = 0.02 s
  static double random_step() { return 0.01; }  // loadable stays below 1/2 over the 500 ticks
};
INSTANTIATE_TYPED_TEST_SUITE_P(Unloaded, PluginContract, ::testing::Types<generic::UnloadedReadingResidual>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

TEST(UnloadedReadingResidual, JudgedFromTheSettledTickOnlyWhileUnloaded) {
  generic::UnloadedReadingResidual::Params p;
  p.settle_s = 0.003;  // 3 ticks
  p.zero = {1.0};
  generic::UnloadedReadingResidual residual(p, StageContext(1e-3, "r", {{"signal", 1}, {"loadable", 1}}));
  residual.reset();
  std::vector<double> x{0.0}, loadable{1.0}, r{0.0};
  const std::span<const double> ins[] = {x, loadable};
  const std::span<double> outs[] = {r};
  const double load[] = {1, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, std::nan("")};
  const bool judged[] = {false, false, false, false, true, true, true, false, false, false, true, false};
  for (int k = 0; k < 12; ++k) {
    x[0] = 10.0 + k;
    loadable[0] = load[k];
    residual.step(StepIO{k * 1e-3, ins, outs});
    if (judged[k]) {
      EXPECT_EQ(r[0], 10.0 + k - 1.0) << "tick " << k;
    } else {
      EXPECT_TRUE(std::isnan(r[0])) << "tick " << k;
    }
  }
}

TEST(UnloadedReadingResidual, WithACusumByJsonItIsolatesAPadThatReadsALoadInSwing) {
  // Two pads, each in swing 0.3 s of every 1 s (pad 1 half a period after pad 0). Healthy, an
  // unloaded pad reads N(0, 2^2); from t = 3.1 s pad 1 reads 20 N more. The CUSUM (sigma 2 N,
  // smallest change 10 N, one false alarm a day) must flag pad 1 during its first swing after
  // the fault and keep it flagged through stance (not judged there), and never flag pad 0.
  const Json config = Json::parse(R"({
    "sample_period_s": 0.001,
    "inputs": {
      "force": {"columns": ["p0", "p1"], "unit": "N"},
      "loadable": {"columns": ["c0", "c1"], "unit": "1"}
    },
    "stages": [
      {"name": "unloaded", "plugin": "unloaded_reading_residual", "params": {"settle_s": 0.02},
       "inputs": {"signal": "input.force", "loadable": "input.loadable"}},
      {"name": "detect", "plugin": "cusum_detector",
       "params": {"noise_std": [2.0], "min_change": [10.0], "false_alarm_interval_s": 86400},
       "inputs": {"residual": "unloaded.residual"}}
    ]
  })");
  Pipeline p = Pipeline::build(config, reference_plugins::registry());
  const SignalRef fault = p.signal("detect.fault");
  const SignalRef judged = p.signal("detect.judged");
  constexpr unsigned kSeed = 5;
  std::printf("seed %u\n", kSeed);
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 2.0);
  double first_flag = -1.0;
  for (int k = 0; k < 8000; ++k) {
    const double t = k * 1e-3;
    const bool swing0 = std::fmod(t, 1.0) < 0.3;
    const bool swing1 = std::fmod(t + 0.5, 1.0) < 0.3;
    const double load0 = swing0 ? 0.0 : 300.0;
    const double load1 = swing1 ? 0.0 : 300.0;
    p.input_values(0)[0] = load0 + noise(rng);
    p.input_values(0)[1] = load1 + noise(rng) + (t >= 3.1 ? 20.0 : 0.0);
    p.input_values(1)[0] = swing0 ? 0.0 : 1.0;
    p.input_values(1)[1] = swing1 ? 0.0 : 1.0;
    p.step(t);
    ASSERT_EQ(p.values(fault)[0], 0.0) << "pad 0 flagged at t = " << t;
    if (t < 3.1) {
      ASSERT_EQ(p.values(fault)[1], 0.0) << "pad 1 flagged before its fault, t = " << t;
    }
    if (p.values(fault)[1] == 1.0 && first_flag < 0.0) first_flag = t;
    if (first_flag >= 0.0) {
      ASSERT_EQ(p.values(fault)[1], 1.0) << "pad 1 cleared at t = " << t;
    }
    if (!swing1) {
      EXPECT_EQ(p.values(judged)[1], 0.0) << t;
    }
  }
  // Pad 1's first swing after 3.1 s starts at 3.5 s; judged from its 20th unloaded tick, 3.519 s.
  std::printf("pad 1 flagged at %.3f s\n", first_flag);
  EXPECT_GE(first_flag, 3.519 - 1e-9);
  EXPECT_LT(first_flag, 3.8);
}

}  // namespace
}  // namespace ftsense
