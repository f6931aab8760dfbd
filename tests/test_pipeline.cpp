// Pipeline building and stepping on valid configs.

#include <algorithm>
#include <cmath>
#include <vector>
#include <limits>

#include <gtest/gtest.h>

#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "test_configs.hpp"

namespace ftsense {
namespace {

Pipeline build(const Json& config) { return Pipeline::build(config, reference_plugins::registry()); }

void set_inputs(Pipeline& p, std::initializer_list<double> measured, std::initializer_list<double> reference) {
  std::copy(measured.begin(), measured.end(), p.input_values(0).begin());
  std::copy(reference.begin(), reference.end(), p.input_values(1).begin());
}

TEST(Pipeline, BuildsAndStepsTheBaseConfig) {
  Pipeline p = build(test::base_config());
  EXPECT_TRUE(p.warnings().empty());
  ASSERT_EQ(p.stage_count(), 3u);
  ASSERT_EQ(p.inputs().size(), 2u);
  EXPECT_EQ(p.inputs()[0].name, "measured");  // inputs are in name order
  set_inputs(p, {10, 20, 30}, {10, 25, 30});
  p.step(0.0);
  const auto residual = p.values(p.signal("residual.residual"));
  EXPECT_EQ(residual[0], 0.0);
  EXPECT_EQ(residual[1], -5.0);
  // The low-pass starts at the first sample; |-5| > 5 is false, so no flag yet.
  EXPECT_EQ(p.values(p.signal("smooth.filtered"))[1], -5.0);
  EXPECT_EQ(p.values(p.monitor()[MonitorColumn::fault])[1], 0.0);
  set_inputs(p, {10, 10, 30}, {10, 25, 30});
  for (int k = 1; k < 2000; ++k) p.step(k * 1e-3);
  EXPECT_EQ(p.values(p.monitor()[MonitorColumn::fault])[1], 1.0);
  EXPECT_EQ(p.values(p.monitor()[MonitorColumn::fault_type])[1], 1.0);  // unclassified
  EXPECT_EQ(p.values(p.monitor()[MonitorColumn::fault])[0], 0.0);
}

// The monitor's cannot_judge: without a wire, 1 exactly where the virtual value is NaN (the
// virtual sensor not ready); with one, the wired signal.
TEST(Pipeline, TheMonitorsCannotJudgeIsTheVirtualSensorNotReadyUnlessWired) {
  Pipeline derived = build(test::base_config());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  set_inputs(derived, {10, 20, 30}, {10, nan, 30});
  derived.step(0.0);
  const auto cannot_judge = derived.values(derived.monitor()[MonitorColumn::cannot_judge]);
  EXPECT_EQ(std::vector<double>(cannot_judge.begin(), cannot_judge.end()), (std::vector<double>{0.0, 1.0, 0.0}));
  set_inputs(derived, {10, 20, 30}, {nan, 25, 30});
  derived.step(1e-3);
  EXPECT_EQ(std::vector<double>(cannot_judge.begin(), cannot_judge.end()), (std::vector<double>{1.0, 0.0, 0.0}));

  Json config = test::base_config();
  config["monitor"]["cannot_judge"] = "input.measured";  // any signal of one value per channel
  Pipeline wired = build(config);
  set_inputs(wired, {10, 20, 30}, {10, nan, 27});
  wired.step(0.0);
  const auto wired_column = wired.values(wired.monitor()[MonitorColumn::cannot_judge]);
  EXPECT_EQ(std::vector<double>(wired_column.begin(), wired_column.end()), (std::vector<double>{10.0, 20.0, 30.0}));
}

TEST(Pipeline, RunOrderFollowsDependenciesNotListing) {
  Json config = test::base_config();
  std::reverse(config["stages"].begin(), config["stages"].end());
  const Pipeline p = build(config);
  ASSERT_EQ(p.stage_count(), 3u);
  EXPECT_EQ(p.stage_name(0), "residual");
  EXPECT_EQ(p.stage_name(1), "smooth");
  EXPECT_EQ(p.stage_name(2), "detect");
}

TEST(Pipeline, ConcatenatedWiresAreGatheredEveryTick) {
  const Json config = Json::parse(R"({
    "sample_period_s": 0.01,
    "inputs": {
      "left": {"columns": ["l1", "l2"], "unit": "N"},
      "right": {"columns": ["r1"], "unit": "N"},
      "model": {"columns": ["m1", "m2", "m3"], "unit": "N"}
    },
    "stages": [
      {"name": "residual", "plugin": "difference_residual",
       "inputs": {"measured": ["input.left", "input.right"], "virtual": "input.model"}}
    ]
  })");
  Pipeline p = build(config);
  EXPECT_FALSE(p.has_monitor());
  const SignalRef residual = p.signal("residual.residual");
  ASSERT_EQ(residual.dim, 3u);
  for (int k = 0; k < 3; ++k) {
    p.input_values(0)[0] = 1.0 * k;
    p.input_values(0)[1] = 2.0 * k;
    p.input_values(2)[0] = 3.0 * k;  // "right" (inputs are in name order: left, model, right)
    std::fill(p.input_values(1).begin(), p.input_values(1).end(), 1.0);
    p.step(0.01 * k);
    EXPECT_EQ(p.values(residual)[0], 1.0 * k - 1.0);
    EXPECT_EQ(p.values(residual)[1], 2.0 * k - 1.0);
    EXPECT_EQ(p.values(residual)[2], 3.0 * k - 1.0);
  }
}

TEST(Pipeline, UnitsPropagateThroughGenericStages) {
  const Pipeline p = build(test::base_config());
  std::map<std::string, std::string> units;
  for (const auto& [name, unit] : p.signal_names()) units[name] = unit;
  EXPECT_EQ(units.at("residual.residual"), "N");
  EXPECT_EQ(units.at("smooth.filtered"), "N");
  EXPECT_EQ(units.at("detect.fault"), "1");
  EXPECT_EQ(p.monitor().unit, "N");
}

TEST(Pipeline, UnknownSignalNamesTheClosest) {
  const Pipeline p = build(test::base_config());
  try {
    (void)p.signal("smooth.filterd");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'smooth.filtered'?"), std::string::npos) << e.what();
  }
}

TEST(Pipeline, ResetRestoresTheInitialState) {
  Pipeline p = build(test::base_config());
  auto run = [&p] {
    p.reset();
    std::vector<double> trace;
    for (int k = 0; k < 300; ++k) {
      set_inputs(p, {1.0 * k, 2.0, 3.0}, {0.5, 0.5, 0.5});
      p.step(k * 1e-3);
      const auto f = p.values(p.signal("smooth.filtered"));
      trace.insert(trace.end(), f.begin(), f.end());
    }
    return trace;
  };
  EXPECT_EQ(run(), run());
}

// A feedback loop through previous_tick: r(t) = u(t) - r(t - 1), r(-1) = the declared initial
// value. The loop feeds u into its own virtual sensor, which the independence rule reports unless
// allowed (a warning here).
TEST(Pipeline, APreviousTickSignalIsItsSignalOneTickLate) {
  const Json config = Json::parse(R"({
    "sample_period_s": 0.001,
    "allow_dependent_virtual_sensor": true,
    "inputs": {"u": {"columns": ["u"], "unit": "N"}},
    "previous_tick": {"last": {"signal": "residual.residual", "dim": 1, "unit": "N", "initial": 0.5}},
    "stages": [
      {"name": "residual", "plugin": "difference_residual",
       "inputs": {"measured": "input.u", "virtual": "previous_tick.last"}}
    ]
  })");
  Pipeline p = build(config);
  ASSERT_EQ(p.warnings().size(), 1u);
  EXPECT_NE(p.warnings()[0].message.find("independence rule"), std::string::npos) << p.warnings()[0].message;
  const auto r = p.values(p.signal("residual.residual"));
  const auto last = p.values(p.signal("previous_tick.last"));
  const std::vector<double> u{1.0, 2.0, 3.0, 4.0};
  const std::vector<double> expected{0.5, 1.5, 1.5, 2.5};
  for (int pass = 0; pass < 2; ++pass) {
    EXPECT_EQ(last[0], 0.5);  // the initial value, again after reset()
    for (std::size_t k = 0; k < u.size(); ++k) {
      p.input_values(0)[0] = u[k];
      p.step(static_cast<double>(k) * 1e-3);
      EXPECT_EQ(r[0], expected[k]) << "tick " << k << ", pass " << pass;
      // After the tick, the value this tick read (the monitor and --record see it so).
      EXPECT_EQ(last[0], k == 0 ? 0.5 : expected[k - 1]) << "tick " << k;
    }
    p.reset();
  }
  const auto names = p.signal_names();
  EXPECT_NE(std::find(names.begin(), names.end(), std::pair<std::string, std::string>{"previous_tick.last", "N"}),
            names.end());
}

// A wire that would be a cycle is a loop once one of its signals is read one tick late: the
// run order ignores it, and the delayed signal carries any selection of its source.
TEST(Pipeline, APreviousTickSignalCutsACycleAndKeepsTheRunOrder) {
  Json config = test::base_config();
  config["previous_tick"] = Json::parse(R"({"smoothed": {"signal": "smooth.filtered[1:3]", "dim": 2, "unit": "N"}})");
  config["stages"].push_back(Json::parse(R"({"name": "echo", "plugin": "difference_residual",
      "inputs": {"measured": "input.measured[1:3]", "virtual": "previous_tick.smoothed"}})"));
  config["stages"][0]["inputs"]["measured"] = Json::array({"input.measured[0:1]", "echo.residual"});
  config["allow_dependent_virtual_sensor"] = true;
  Pipeline p = build(config);
  ASSERT_EQ(p.stage_count(), 4u);
  EXPECT_EQ(p.stage_name(0), "echo");  // reads smooth's output one tick late: runs first
  EXPECT_EQ(p.stage_name(1), "residual");
  set_inputs(p, {10, 20, 30}, {0, 0, 0});
  p.step(0.0);
  // Tick 0: echo = measured - 0 (the initial value); the low-pass starts at its first sample.
  EXPECT_EQ(p.values(p.signal("echo.residual"))[0], 20.0);
  EXPECT_EQ(p.values(p.signal("smooth.filtered"))[1], 20.0);
  EXPECT_EQ(p.values(p.signal("previous_tick.smoothed"))[0], 0.0);
  p.step(1e-3);
  EXPECT_EQ(p.values(p.signal("previous_tick.smoothed"))[0], 20.0);
  EXPECT_EQ(p.values(p.signal("previous_tick.smoothed"))[1], 30.0);
  EXPECT_EQ(p.values(p.signal("echo.residual"))[0], 0.0);  // 20 - 20
  EXPECT_EQ(p.values(p.signal("echo.residual"))[1], 0.0);  // 30 - 30
  // The monitor reads a previous-tick signal as the stages did: alone (in place) or gathered.
  config["monitor"]["extra"] = Json::parse(R"({"alone": "previous_tick.smoothed",
      "gathered": ["previous_tick.smoothed[0:1]", "echo.residual"]})");
  config["previous_tick"]["smoothed"]["signal"] = "smooth.filtered";
  config["previous_tick"]["smoothed"]["dim"] = 3;
  config["stages"][3]["inputs"]["virtual"] = "previous_tick.smoothed[1:3]";
  Pipeline q = build(config);
  set_inputs(q, {10, 20, 30}, {0, 0, 0});
  q.step(0.0);
  set_inputs(q, {11, 21, 31}, {0, 0, 0});
  q.step(1e-3);
  ASSERT_EQ(q.monitor().extra.size(), 2u);
  const auto alone = q.values(q.monitor().extra[0].signal);
  const auto gathered = q.values(q.monitor().extra[1].signal);
  ASSERT_EQ(alone.size(), 3u);
  EXPECT_EQ(std::vector<double>(alone.begin(), alone.end()), (std::vector<double>{10.0, 20.0, 30.0}));  // tick 0's
  EXPECT_EQ(gathered[0], 10.0);
}

TEST(Pipeline, SurvivesBeingMoved) {
  Pipeline original = build(test::base_config());
  Pipeline moved = std::move(original);
  set_inputs(moved, {1, 2, 3}, {0, 0, 0});
  moved.step(0.0);
  EXPECT_EQ(moved.values(moved.signal("residual.residual"))[2], 3.0);
}

// A leave-one-out virtual sensor (channel j computed from every sensor but j) may be compared
// with exactly the sensors it leaves out, in a stage as in the monitor; anything else that
// depends on those sensors still trips the independence rule.
Json leave_one_out_config(const std::string& virtual_wire) {
  return parse_json_text(R"({
    "sample_period_s": 0.001,
    "inputs": {
      "forces": {"columns": ["f1", "f2", "f3", "f4", "f5", "f6", "f7", "f8"], "unit": "N"},
      "total_force": {"columns": ["fx", "fy", "fz"], "unit": "N"},
      "l_pos": {"columns": ["lx", "ly", "lz"], "unit": "m"},
      "l_rpy": {"columns": ["lr", "lp", "lw"], "unit": "rad"},
      "r_pos": {"columns": ["rx", "ry", "rz"], "unit": "m"},
      "r_rpy": {"columns": ["rr", "rp", "rw"], "unit": "rad"}
    },
    "stages": [
      {"name": "pads", "plugin": "contact_point_height",
       "params": {"points": [[0.1, 0.05], [0.1, -0.05], [-0.1, 0.05], [-0.1, -0.05]]},
       "inputs": {"foot_pos": ["input.l_pos", "input.r_pos"], "foot_rpy": ["input.l_rpy", "input.r_rpy"]}},
      {"name": "fdi", "plugin": "contact_force_fdi",
       "params": {"points_per_foot": 4, "weight_N": 1000.0},
       "inputs": {"measured": "input.forces", "total_force": "input.total_force", "point_height": "pads.point_height"}},
      {"name": "residual", "plugin": "difference_residual",
       "inputs": {"measured": "input.forces", "virtual": ")" + virtual_wire + R"("}}
    ]
  })", "leave_one_out.json");
}

TEST(Pipeline, LeaveOneOutVirtualSensorMayJudgeTheSensorsItLeavesOut) {
  const Pipeline p = build(leave_one_out_config("fdi.virtual"));
  EXPECT_TRUE(p.warnings().empty());
  try {
    (void)build(leave_one_out_config("fdi.recovered"));  // channel j of recovered uses sensor j
    FAIL() << "a recovered signal judged against its own sensors was accepted";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems()[0].path, "/stages/2/inputs/virtual");
    EXPECT_NE(e.problems()[0].message.find("independence rule"), std::string::npos) << e.what();
  }
}

TEST(Pipeline, MonitorGathersConcatenatedSignals) {
  Json config = test::base_config();
  config["inputs"]["extra"] = Json::parse(R"({"columns": ["e"], "unit": "N"})");
  config["inputs"]["extra_model"] = Json::parse(R"({"columns": ["em"], "unit": "N"})");
  config["monitor"]["channels"] = Json::array({"c1", "c2", "c3", "e"});
  config["monitor"]["measured"] = Json::array({"input.measured", "input.extra"});
  for (const char* key : {"virtual", "fault_estimate", "recovered"}) {
    config["monitor"][key] = Json::array({config["monitor"][key], "input.extra_model"});
  }
  config["monitor"]["fault"] = Json::array({"detect.fault", "input.extra"});
  config["monitor"]["fault_type"] = Json::array({"detect.fault_type", "input.extra"});
  // fault/fault_type are dimensionless but "extra" is in N: allowed, the monitor checks only
  // that measured and virtual share a unit.
  Pipeline p = build(config);
  ASSERT_EQ(p.inputs()[0].name, "extra");  // inputs are in name order
  p.input_values(0)[0] = 7.0;
  p.step(0.0);
  EXPECT_EQ(p.values(p.monitor()[MonitorColumn::measured]).size(), 4u);
  EXPECT_EQ(p.values(p.monitor()[MonitorColumn::measured])[3], 7.0);
}

}  // namespace
}  // namespace ftsense

namespace ftsense {
namespace {

TEST(Pipeline, ValuesOutsideAnInputsPlausibleRangeAreReadAsMissing) {
  Json config = test::base_config();
  config["inputs"]["measured"]["plausible_range"] = Json::array({-50.0, 5000.0});
  Pipeline p = Pipeline::build(config, reference_plugins::registry());
  const SignalRef measured = p.signal("input.measured");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::array<double, 3> row{1e12, -50.0, nan};
  std::copy(row.begin(), row.end(), p.input_values(0).begin());
  p.step(0.0);
  const auto v = p.values(measured);
  EXPECT_TRUE(std::isnan(v[0]));  // a burst beyond the range
  EXPECT_EQ(v[1], -50.0);         // the bound itself is plausible
  EXPECT_TRUE(std::isnan(v[2]));  // already missing: not counted
  EXPECT_EQ(p.implausible_counts(), (std::vector<std::size_t>{1, 0}));
  p.reset();
  EXPECT_EQ(p.implausible_counts()[0], 1u);
}

TEST(Pipeline, APlausibleRangeMustBeOrdered) {
  Json config = test::base_config();
  config["inputs"]["measured"]["plausible_range"] = Json::array({10.0, -10.0});
  try {
    (void)Pipeline::build(config, reference_plugins::registry());
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems().at(0).path, "/inputs/measured/plausible_range");
    EXPECT_EQ(e.problems().at(0).message, " = [10.0,-10.0] violates min < max");
  }
}

}  // namespace
}  // namespace ftsense

namespace ftsense {
namespace {

TEST(Pipeline, AnInputsScaleAndOffsetComeBeforeItsPlausibleRange) {
  // Raw counts: N = 0.25 counts - 200, per column or for all; the range is in newtons.
  Json config = test::base_config();
  config["inputs"]["measured"]["scale"] = 0.25;
  config["inputs"]["measured"]["offset"] = Json::array({-200.0, 0.0, 10.0});
  config["inputs"]["measured"]["plausible_range"] = Json::array({-150.0, 5000.0});
  Pipeline p = Pipeline::build(config, reference_plugins::registry());
  const std::array<double, 3> counts{1000.0, 8.0, -1000.0};
  std::copy(counts.begin(), counts.end(), p.input_values(0).begin());
  p.step(0.0);
  const auto v = p.values(p.signal("input.measured"));
  EXPECT_EQ(v[0], 50.0);           // 0.25 * 1000 - 200
  EXPECT_EQ(v[1], 2.0);            // 0.25 * 8 + 0
  EXPECT_TRUE(std::isnan(v[2]));   // 0.25 * -1000 + 10 = -240 N: outside the range
  EXPECT_EQ(p.implausible_counts()[0], 1u);
}

TEST(Pipeline, AWireMaySelectValuesOfASignal) {
  // "[i]" and "[i:j]" (0-based, j excluded) pick values out of a vector signal, alone or
  // concatenated with others.
  const Json config = Json::parse(R"({
    "sample_period_s": 0.01,
    "inputs": {
      "pos": {"columns": ["x", "y", "z"], "unit": "N"},
      "model": {"columns": ["m1", "m2", "m3"], "unit": "N"}
    },
    "stages": [
      {"name": "one", "plugin": "difference_residual",
       "inputs": {"measured": "input.pos[2]", "virtual": "input.model[0]"}},
      {"name": "three", "plugin": "difference_residual",
       "inputs": {"measured": ["input.pos[1:3]", "input.pos[0]"], "virtual": "input.model"}}
    ]
  })");
  Pipeline p = build(config);
  const std::array<double, 3> pos{1.0, 2.0, 3.0};
  const std::array<double, 3> model{0.5, 0.25, 0.125};
  std::copy(model.begin(), model.end(), p.input_values(0).begin());  // inputs in name order
  std::copy(pos.begin(), pos.end(), p.input_values(1).begin());
  p.step(0.0);
  ASSERT_EQ(p.signal("one.residual").dim, 1u);
  EXPECT_EQ(p.values(p.signal("one.residual"))[0], 3.0 - 0.5);
  const auto three = p.values(p.signal("three.residual"));
  EXPECT_EQ(three[0], 2.0 - 0.5);
  EXPECT_EQ(three[1], 3.0 - 0.25);
  EXPECT_EQ(three[2], 1.0 - 0.125);
}

}  // namespace
}  // namespace ftsense

namespace ftsense {
namespace {

TEST(Pipeline, AQuadrupedByJsonSpreadsItsWeightOverTheFeetInContact) {
  // A 13 kg quadruped standing on three feet (the front-left one lifted 3 cm), by JSON alone:
  // F = m R f, contact from the feet's heights, F_z spread over the feet in contact about the
  // CoM's projection. Oracle: at rest the three feet carry m g with the CoM at their barycentre
  // (1/3 each), and conservation of force.
  const Json config = Json::parse(R"({
    "sample_period_s": 0.002,
    "inputs": {
      "imu_acc": {"columns": ["imu/ax", "imu/ay", "imu/az"], "unit": "m/s^2"},
      "base_rpy": {"columns": ["base/roll", "base/pitch", "base/yaw"], "unit": "rad"},
      "feet": {"columns": ["fl/x", "fl/y", "fl/z", "fr/x", "fr/y", "fr/z", "rl/x", "rl/y", "rl/z", "rr/x", "rr/y", "rr/z"],
               "unit": "m"},
      "com": {"columns": ["com/x", "com/y", "com/z"], "unit": "m"}
    },
    "stages": [
      {"name": "weight", "plugin": "total_ground_force", "params": {"mass_kg": 13.0},
       "inputs": {"imu_acc": "input.imu_acc", "base_rpy": "input.base_rpy"}},
      {"name": "contact", "plugin": "contact_from_foot_height", "params": {"touchdown_height_m": 0.01},
       "inputs": {"foot_pos": "input.feet"}},
      {"name": "support", "plugin": "support_force_distribution",
       "inputs": {"total_force": "weight.total_force", "cop": "input.com[0:2]", "foot_pos": "input.feet",
                  "contact": "contact.contact"}}
    ]
  })");
  Pipeline p = build(config);
  const std::array<double, 3> acc{0.0, 0.0, 9.806};
  const std::array<double, 3> rpy{0.0, 0.0, 0.0};
  const std::array<double, 12> feet{0.25, 0.15, 0.03, 0.25, -0.15, 0.0, -0.25, 0.15, 0.0, -0.25, -0.15, 0.0};
  // The barycentre of the three feet on the ground.
  const std::array<double, 3> com{(0.25 - 0.25 - 0.25) / 3.0, (-0.15 + 0.15 - 0.15) / 3.0, 0.3};
  std::copy(feet.begin(), feet.end(), p.input_values(2).begin());  // inputs in name order: base_rpy, com, feet, imu_acc
  std::copy(rpy.begin(), rpy.end(), p.input_values(0).begin());
  std::copy(com.begin(), com.end(), p.input_values(1).begin());
  std::copy(acc.begin(), acc.end(), p.input_values(3).begin());
  p.step(0.0);
  const auto f = p.values(p.signal("support.forces"));
  ASSERT_EQ(f.size(), 4u);
  const double weight = 13.0 * 9.806;
  EXPECT_EQ(f[0], 0.0);  // lifted
  for (int i = 1; i < 4; ++i) EXPECT_NEAR(f[i], weight / 3.0, 1e-4 * weight);
  EXPECT_NEAR(f[1] + f[2] + f[3], weight, 1e-9);
}

}  // namespace
}  // namespace ftsense
