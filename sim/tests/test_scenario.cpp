// Scenario loading: the shipped files load; bad documents give every problem with its path.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "scenario_dir.hpp"
#include "ftsense/sim/scenario.hpp"

using namespace ftsense::sim;
using ftsense::FaultType;
using nlohmann::json;

namespace {
using ftsense::sim::testing::kScenarioDir;

json minimal() {
  return json::parse(R"({"duration_s": 10, "gait": {"step_length_m": 0.15, "step_time_s": 1.0,
                        "double_support_ratio": 0.2}, "faults": []})");
}

std::vector<std::string> problems_of(const json& doc) {
  try {
    (void)parse_scenario(doc);
  } catch (const ScenarioError& e) {
    return e.problems();
  }
  return {};
}
}  // namespace

TEST(Scenario, ShippedScenariosLoad) {
  for (const char* name : {"paper.json", "clean.json", "mixed.json"}) {
    EXPECT_NO_THROW((void)load_scenario(kScenarioDir / name)) << name;
  }
}

TEST(Scenario, PaperScenarioHasTheFourFaultsAtFiveSeconds) {
  const Scenario s = load_scenario(kScenarioDir / "paper.json");
  ASSERT_EQ(s.faults.size(), 4u);
  for (const auto& f : s.faults) {
    EXPECT_EQ(f.start_s, 5.0);
    EXPECT_FALSE(f.end_s.has_value());
    EXPECT_GE(f.channel, 4);  // right foot
  }
  EXPECT_EQ(s.faults[0].type, FaultType::frozen);
  EXPECT_EQ(s.faults[0].value_N.value_or(-1.0), 0.0);
  EXPECT_EQ(s.faults[1].offset_N, 100.0);
  EXPECT_EQ(s.faults[2].slope_N_s, 15.0);
  EXPECT_EQ(s.faults[3].offset_N, -100.0);
}

TEST(Scenario, MixedScenarioCoversEveryOtherFaultTypeOnBothFeet) {
  const Scenario s = load_scenario(kScenarioDir / "mixed.json");
  std::set<FaultType> types;
  bool left = false, right = false, intermittent = false, frozen_last = false;
  for (const auto& f : s.faults) {
    types.insert(f.type);
    left |= f.channel < 4;
    right |= f.channel >= 4;
    intermittent |= f.end_s.has_value();
    frozen_last |= f.type == FaultType::frozen && !f.value_N;
  }
  for (auto t : {FaultType::gain, FaultType::noise, FaultType::spikes, FaultType::invalid,
                 FaultType::saturation, FaultType::frozen})
    EXPECT_TRUE(types.count(t)) << to_string(t);
  EXPECT_TRUE(left && right && intermittent && frozen_last);
}

TEST(Scenario, CleanScenarioIsLongAndFaultFree) {
  const Scenario s = load_scenario(kScenarioDir / "clean.json");
  EXPECT_GE(s.duration_s, 30.0);
  EXPECT_TRUE(s.faults.empty());
}

TEST(Scenario, MinimalDocumentGetsDefaults) {
  const Scenario s = parse_scenario(minimal());
  EXPECT_EQ(s.duration_s, 10.0);
  EXPECT_EQ(s.seed, 1u);
  EXPECT_EQ(s.gait.num_steps, -1);
  EXPECT_EQ(s.sensors.force_noise_std_N, SensorParams{}.force_noise_std_N);
}

TEST(Scenario, ABodyScalesEverySegmentsMassAndThePelvisHeightFollowsTheLegs) {
  json doc = minimal();
  doc["body"] = json::parse(R"({"total_mass_kg": 57, "upper_leg_m": 0.22, "lower_leg_m": 0.21,
                               "sole_ankle_m": 0.09, "foot_length_m": 0.18, "foot_width_m": 0.11})");
  const Scenario s = parse_scenario(doc);
  const RobotParams standard;
  EXPECT_EQ(s.robot.total_mass_kg, 57.0);
  EXPECT_EQ(s.robot.thigh_kg, 0.5 * standard.thigh_kg);  // 57 of 114 kg
  EXPECT_EQ(s.robot.foot_kg, 0.5 * standard.foot_kg);
  EXPECT_NEAR(s.robot.trunk_kg(), 0.5 * standard.trunk_kg(), 1e-12);  // the trunk keeps its share
  EXPECT_EQ(s.robot.foot_length_m, 0.18);
  EXPECT_EQ(s.robot.foot_width_m, 0.11);
  // The pelvis height's default scales with the leg (0.52 m hip to sole, against 0.674 m).
  EXPECT_NEAR(s.gait.pelvis_height_m, 0.60 * 0.52 / 0.674, 1e-12);
  // The paper's robot without "body": its own numbers, exactly.
  const Scenario paper = parse_scenario(minimal());
  EXPECT_EQ(paper.gait.pelvis_height_m, 0.60);
  EXPECT_EQ(paper.robot.total_mass_kg, 114.0);
  EXPECT_EQ(paper.robot.thigh_kg, standard.thigh_kg);
  // A pelvis height the shorter legs cannot reach is refused with the scaled range.
  doc["gait"]["pelvis_height_m"] = 0.6;
  const auto p = problems_of(doc);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].rfind("/gait/pelvis_height_m = 0.6 is out of range, expected >= 0.385", 0), 0u) << p[0];
}

struct BadCase {
  const char* what;
  const char* patch;     // JSON merge patch applied to minimal()
  const char* message;   // expected problem (exact)
};

class BadScenario : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScenario, ReportsPathValueAndRule) {
  json doc = minimal();
  doc.merge_patch(json::parse(GetParam().patch));
  const auto p = problems_of(doc);
  ASSERT_FALSE(p.empty()) << GetParam().what;
  EXPECT_NE(std::find(p.begin(), p.end(), std::string(GetParam().message)), p.end())
      << GetParam().what << ": got\n" << ScenarioError(p).what();
}

INSTANTIATE_TEST_SUITE_P(
    Table, BadScenario,
    ::testing::Values(
        BadCase{"wrong type", R"({"faults": [{"channel": "r_foot/p3", "type": "drift", "start_s": 5, "slope_N_s": "x"}]})",
                R"(/faults/0/slope_N_s = "x" has type string, expected number)"},
        BadCase{"missing required", R"({"gait": {"step_time_s": null}})",
                "/gait/step_time_s is missing (required number)"},
        BadCase{"unknown key", R"({"gait": {"stride": 1}})",
                "/gait/stride = 1 is not a known key (allowed here: com_feedback_gain, com_feedback_integral_gain_1_s, double_support_ratio, "
                "foot_half_spacing_m, initial_stand_s, num_steps, pelvis_height_m, preview_s, step_height_m, "
                "step_length_m, step_time_s)"},
        BadCase{"out of range", R"({"duration_s": -1})", "/duration_s = -1 is out of range, expected > 0 and <= 3600"},
        BadCase{"step time range", R"({"gait": {"step_time_s": 0.1}})",
                "/gait/step_time_s = 0.1 is out of range, expected >= 0.5 and <= 3"},
        BadCase{"non-integer", R"({"gait": {"num_steps": 2.5}})",
                "/gait/num_steps = 2.5 has type non-integer number, expected integer"},
        BadCase{"bad channel", R"({"faults": [{"channel": "r_foot/p5", "type": "offset", "start_s": 1, "offset_N": 1}]})",
                R"(/faults/0/channel = "r_foot/p5" is not one of: l_foot/p1, l_foot/p2, l_foot/p3, l_foot/p4, r_foot/p1, r_foot/p2, r_foot/p3, r_foot/p4)"},
        BadCase{"key of another type", R"({"faults": [{"channel": "r_foot/p1", "type": "offset", "start_s": 1, "offset_N": 1, "gain": 2}]})",
                "/faults/0/gain = 2 is not a known key (allowed here: channel, end_s, offset_N, start_s, type)"},
        BadCase{"end before start", R"({"faults": [{"channel": "r_foot/p1", "type": "invalid", "start_s": 3, "end_s": 2}]})",
                "/faults/0/end_s = 2 is out of range, expected > start_s (3)"},
        BadCase{"start after duration", R"({"faults": [{"channel": "r_foot/p1", "type": "invalid", "start_s": 11}]})",
                "/faults/0/start_s = 11 is out of range, expected >= 0 and <= 10"},
        BadCase{"overlap", R"({"faults": [{"channel": "r_foot/p1", "type": "invalid", "start_s": 1, "end_s": 3},
                                         {"channel": "r_foot/p1", "type": "offset", "start_s": 2, "offset_N": 5}]})",
                "/faults/1 overlaps /faults/0 in time on channel r_foot/p1; faults on one channel must not overlap "
                "(end_s of one <= start_s of the other)"},
        BadCase{"saturation bounds", R"({"faults": [{"channel": "r_foot/p1", "type": "saturation", "start_s": 1, "max_N": 10, "min_N": 20}]})",
                "/faults/0/min_N = 20 is out of range, expected < max_N (10)"},
        BadCase{"sensor vector size", R"({"sensors": {"imu": {"acc_bias_m_s2": [0, 0]}}})",
                "/sensors/imu/acc_bias_m_s2 = [0,0] has type array of size 2, expected array of 3 numbers"},
        BadCase{"faults not an array", R"({"faults": {"a": 1}})",
                R"(/faults = {"a":1} has type object, expected array)"},
        BadCase{"fault not an object", R"({"faults": [3]})", "/faults/0 = 3 has type number, expected object"},
        BadCase{"negative seed", R"({"seed": -3})",
                "/seed = -3 is out of range, expected >= 0 and <= 9223372036854775807"},
        BadCase{"huge seed", R"({"seed": 18446744073709551615})",
                "/seed = 18446744073709551615 is out of range, expected >= 0 and <= 9223372036854775807"},
        BadCase{"body out of range", R"({"body": {"total_mass_kg": 5}})",
                "/body/total_mass_kg = 5 is out of range, expected >= 30 and <= 250"},
        BadCase{"body unknown key", R"({"body": {"mass": 50}})",
                "/body/mass = 50 is not a known key (allowed here: foot_length_m, foot_width_m, lower_leg_m, "
                "sole_ankle_m, total_mass_kg, upper_leg_m)"},
        BadCase{"null duration", R"({"duration_s": null, "name": 5})", "/name = 5 has type number, expected string"}));

TEST(Scenario, FaultTypesAreTheCoresSensorFaultTypes) {
  // The accepted names come from include/ftsense/fault_type.hpp: every type but none and
  // unclassified (a detector's verdict, not something a sensor can be made to do).
  std::string names;
  for (const FaultType t : ftsense::sensor_fault_types()) names += (names.empty() ? "" : ", ") + std::string(to_string(t));
  EXPECT_EQ(names.rfind("offset, drift, frozen, gain, noise, spikes, invalid, saturation", 0), 0u) << names;
  for (const char* type : {"stuck", "none", "unclassified"}) {
    json doc = minimal();
    doc["faults"] = json::array({{{"channel", "r_foot/p1"}, {"type", type}, {"start_s", 1}}});
    const auto p = problems_of(doc);
    ASSERT_EQ(p.size(), 1u) << type;
    EXPECT_EQ(p[0], "/faults/0/type = \"" + std::string(type) + "\" is not one of: " + names);
  }
}

TEST(Scenario, AllProblemsAreCollectedTogether) {
  json doc = minimal();
  doc.merge_patch(json::parse(R"({"duration_s": "long", "gait": {"step_length_m": 9, "bogus": true},
      "faults": [{"channel": "r_foot/p1", "type": "drift", "start_s": 1}, {"type": "gain"}]})"));
  const auto p = problems_of(doc);
  EXPECT_GE(p.size(), 6u) << ScenarioError(p).what();
  for (const auto& m : p) EXPECT_EQ(m.front(), '/') << m;
}

TEST(Scenario, RootMustBeAnObject) {
  const auto p = problems_of(json::array());
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0], "(document root) = [] has type array, expected object");
}

TEST(Scenario, SyntaxErrorsAndMissingFilesAreScenarioErrors) {
  EXPECT_THROW((void)parse_scenario_text("{\"duration_s\": "), ScenarioError);
  try {
    (void)load_scenario(kScenarioDir / "does_not_exist.json");
    FAIL();
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_NE(e.problems()[0].find("cannot open"), std::string::npos);
  }
}
