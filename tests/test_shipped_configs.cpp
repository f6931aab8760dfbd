// The shipped SURALP configs: they build, and the paper's literal measured-ZMP choice is caught
// by the independence rule unless explicitly allowed. Every shipped config is plausible: no
// parameter outside its plausible range (params.hpp), so no warning but that one.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "ftsense/pipeline.hpp"
#include "ftsense/pipeline_document.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/testing/allocation_counter.hpp"

namespace ftsense {
namespace {

Json load(const std::string& relative) {
  const std::string path = std::string(FTSENSE_SOURCE_DIR) + "/" + relative;
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return parse_json_text(text.str(), path);
}

TEST(ShippedConfigs, SuralpBuildsWithoutWarnings) {
  const Pipeline p = Pipeline::build(load("configs/suralp.json"), reference_plugins::registry());
  EXPECT_TRUE(p.warnings().empty());
  EXPECT_EQ(p.monitor().channels.size(), 8u);
  EXPECT_EQ(p.monitor().unit, "N");
}

// configs/*.json, the insole example's config and the CLI tests' config. A config whose
// plugins ftsense does not ship (the insole example's own) has its document and the parameters
// of every stage with a reference plugin checked; the others are built whole.
TEST(ShippedConfigs, EveryShippedConfigIsPlausible) {
  namespace fs = std::filesystem;
  const fs::path root(FTSENSE_SOURCE_DIR);
  std::vector<fs::path> paths{root / "examples/insole_fdi/config/insole_fdi.json", root / "tests/cli/good.json"};
  for (const auto& entry : fs::directory_iterator(root / "configs")) {
    if (entry.path().extension() == ".json") paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  ASSERT_GE(paths.size(), 6u);
  const PluginRegistry registry = reference_plugins::registry();
  for (const fs::path& path : paths) {
    SCOPED_TRACE(path.string());
    const Json config = load(fs::relative(path, root).string());
    bool all_known = true;
    for (const Json& stage : config.at("stages")) all_known = all_known && registry.find(stage.at("plugin").get<std::string>());
    std::vector<Diagnostic> warnings;
    if (all_known) {
      warnings = Pipeline::build(config, registry, path.parent_path()).warnings();
    } else {
      Diagnostics diag;
      (void)read_pipeline_document(config, diag);
      std::size_t checked = 0;
      for (std::size_t i = 0; i < config.at("stages").size(); ++i) {
        const Json& stage = config.at("stages")[i];
        const PluginInfo* plugin = registry.find(stage.at("plugin").get<std::string>());
        if (plugin == nullptr) continue;
        plugin->check_params(stage.value("params", Json::object()), "/stages/" + std::to_string(i) + "/params", diag);
        ++checked;
      }
      EXPECT_GT(checked, 0u);
      EXPECT_FALSE(diag.has_errors());
      warnings = diag.warnings();
    }
    for (const Diagnostic& w : warnings) {
      // The measured ZMP is computed from the force sensors; suralp_generic.json feeds the
      // recovery's corrections back into the leave-one-out forces (previous_tick).
      const bool allowed_dependence =
          (path.filename() == "suralp_measured_zmp.json" || path.filename() == "suralp_generic.json") &&
          w.message.find("allow_dependent_virtual_sensor") != std::string::npos;
      EXPECT_TRUE(allowed_dependence) << w.text();
    }
  }
}

// The recovery's corrections fed back one tick late depend on the force sensors they correct:
// the independence rule reports the loop, through previous_tick, unless allowed.
TEST(ShippedConfigs, FedBackCorrectionsTripTheIndependenceRuleUnlessAllowed) {
  Json config = load("configs/suralp_generic.json");
  const Pipeline allowed = Pipeline::build(config, reference_plugins::registry(), std::filesystem::path(FTSENSE_SOURCE_DIR) / "configs");
  ASSERT_EQ(allowed.warnings().size(), 10u);
  EXPECT_EQ(allowed.warnings()[0].path, "/stages/3/inputs/correction");
  EXPECT_EQ(allowed.warnings()[1].path, "/stages/3/inputs/substituted");
  // load_apportioner's: the recovery's corrections and substitutions, and the flags that keep a
  // relation's variance to fault-free ticks.
  EXPECT_EQ(allowed.warnings()[2].path, "/stages/4/inputs/correction");
  EXPECT_EQ(allowed.warnings()[3].path, "/stages/4/inputs/substituted");
  EXPECT_EQ(allowed.warnings()[4].path, "/stages/4/inputs/flagged");
  // plane_fit_residual's: the readings as corrected, and a substituted one's foot left unjudged.
  EXPECT_EQ(allowed.warnings()[5].path, "/stages/5/inputs/correction");
  EXPECT_EQ(allowed.warnings()[6].path, "/stages/5/inputs/substituted");
  // gain_isolator's: the substituted readings, and the pads other isolators placed a fault on.
  EXPECT_EQ(allowed.warnings()[7].path, "/stages/11/inputs/substituted");
  EXPECT_EQ(allowed.warnings()[8].path, "/stages/11/inputs/flagged");
  EXPECT_EQ(allowed.warnings()[9].path, "/stages/13/inputs/flagged");  // still_reading_isolator's
  config["allow_dependent_virtual_sensor"] = false;
  try {
    (void)Pipeline::build(config, reference_plugins::registry(), std::filesystem::path(FTSENSE_SOURCE_DIR) / "configs");
    FAIL() << "the fed-back corrections make the virtual sensor depend on the monitored sensors";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 10u) << e.what();
    for (const Diagnostic& problem : e.problems()) {
      EXPECT_NE(problem.message.find("independence rule"), std::string::npos) << e.what();
      EXPECT_NE(problem.message.find("'l_forces', 'r_forces'"), std::string::npos) << e.what();
    }
  }
}

TEST(ShippedConfigs, MeasuredZmpTripsTheIndependenceRuleUnlessAllowed) {
  Json config = load("configs/suralp_measured_zmp.json");
  const Pipeline allowed = Pipeline::build(config, reference_plugins::registry());
  ASSERT_FALSE(allowed.warnings().empty());
  config["allow_dependent_virtual_sensor"] = false;
  try {
    (void)Pipeline::build(config, reference_plugins::registry());
    FAIL() << "the measured ZMP makes the virtual sensor depend on the monitored sensors";
  } catch (const ConfigError& e) {
    ASSERT_FALSE(e.problems().empty());
    EXPECT_NE(e.problems()[0].message.find("independence rule"), std::string::npos) << e.what();
    EXPECT_NE(e.problems()[0].message.find("'l_forces', 'r_forces'"), std::string::npos) << e.what();
  }
}

class SuralpConfigs : public ::testing::TestWithParam<const char*> {};

TEST_P(SuralpConfigs, TicksAllocateNothing) {
  // The whole pipeline (the reference one: 10 stages, QP solver included; the robust one) over
  // 10,000 ticks of a synthetic walk: alternating single supports with the swing foot lifted, a
  // swaying CoM, a jittering pad (the noise test's window sums), a pad reading minus its load
  // (the sign-flip fit), a frozen pad.
  Pipeline p = Pipeline::build(load(GetParam()), reference_plugins::registry());
  // The gait plan (planned ZMP, contact plan) is read by the reference pipeline only.
  auto input = [&p](const std::string& name, bool required = true) {
    for (std::size_t i = 0; i < p.inputs().size(); ++i) {
      if (p.inputs()[i].name == name) return p.input_values(i);
    }
    if (required) throw std::logic_error("no input " + name);
    return std::span<double>();
  };
  const auto l_forces = input("l_forces"), r_forces = input("r_forces"), imu = input("imu_acc");
  const auto l_pos = input("l_foot_pos"), r_pos = input("r_foot_pos"), zmp = input("planned_zmp", false);
  const auto contact = input("contact_plan", false);
  auto tick = [&](int k) {
    const double t = k * 1e-3;
    const double phase = std::fmod(t, 2.0);
    const bool left = phase < 1.2, right = phase >= 0.8 || phase < 0.2;
    if (!contact.empty()) contact[0] = left, contact[1] = right;
    l_pos[1] = 0.1, r_pos[1] = -0.1;
    if (!zmp.empty()) zmp[0] = 0.1 * t, zmp[1] = 0.08 * std::sin(3.14159 * t);
    imu[0] = 0.2 * std::cos(3.0 * t), imu[1] = -0.5 * std::sin(3.14159 * t), imu[2] = 9.81;
    l_pos[2] = left ? 0.0 : 0.05, r_pos[2] = right ? 0.0 : 0.05;
    for (int j = 0; j < 4; ++j) {
      l_forces[j] = left ? 250.0 + 30.0 * std::sin(7.0 * t + j) : 0.0;
      r_forces[j] = right ? 250.0 + 30.0 * std::cos(5.0 * t + j) : 0.0;
    }
    if (t > 3.0 && t < 3.5) r_forces[0] += k % 2 == 0 ? 60.0 : -60.0;
    if (t > 5.0 && t < 6.0) l_forces[1] = -l_forces[1];
    if (t > 7.0 && t < 8.0) l_forces[2] = 180.0;
    p.step(t);
  };
  tick(0);
  testing::AllocationScope scope;
  for (int k = 1; k <= 10000; ++k) tick(k);
  EXPECT_EQ(scope.allocations(), 0u);
  for (double v : p.values(p.monitor()[MonitorColumn::recovered])) EXPECT_TRUE(std::isfinite(v));
}

INSTANTIATE_TEST_SUITE_P(ShippedConfigs, SuralpConfigs,
                         ::testing::Values("configs/suralp.json", "configs/suralp_robust.json"));

}  // namespace
}  // namespace ftsense
