// The shipped SURALP configs: they build, and the paper's literal measured-ZMP choice is caught
// by the independence rule unless explicitly allowed.

#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "ftsense/pipeline.hpp"
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

TEST(ShippedConfigs, SuralpTicksAllocateNothing) {
  // The whole reference pipeline (10 stages, QP solver included) over 10,000 ticks of a
  // synthetic walk: alternating single supports, a swaying CoM, noisy pads.
  Pipeline p = Pipeline::build(load("configs/suralp.json"), reference_plugins::registry());
  auto input = [&p](const std::string& name) {
    for (std::size_t i = 0; i < p.inputs().size(); ++i) {
      if (p.inputs()[i].name == name) return p.input_values(i);
    }
    throw std::logic_error("no input " + name);
  };
  const auto l_forces = input("l_forces"), r_forces = input("r_forces"), imu = input("imu_acc");
  const auto l_pos = input("l_foot_pos"), r_pos = input("r_foot_pos"), zmp = input("planned_zmp");
  const auto contact = input("contact_plan");
  auto tick = [&](int k) {
    const double t = k * 1e-3;
    const double phase = std::fmod(t, 2.0);
    const bool left = phase < 1.2, right = phase >= 0.8 || phase < 0.2;
    contact[0] = left, contact[1] = right;
    l_pos[1] = 0.1, r_pos[1] = -0.1;
    zmp[0] = 0.1 * t, zmp[1] = 0.08 * std::sin(3.14159 * t);
    imu[0] = 0.2 * std::cos(3.0 * t), imu[1] = -0.5 * std::sin(3.14159 * t), imu[2] = 9.81;
    for (int j = 0; j < 4; ++j) {
      l_forces[j] = left ? 250.0 + 30.0 * std::sin(7.0 * t + j) : 0.0;
      r_forces[j] = right ? 250.0 + 30.0 * std::cos(5.0 * t + j) : 0.0;
    }
    p.step(t);
  };
  tick(0);
  testing::AllocationScope scope;
  for (int k = 1; k <= 10000; ++k) tick(k);
  EXPECT_EQ(scope.allocations(), 0u);
  for (double v : p.values(p.monitor()[MonitorColumn::recovered])) EXPECT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace ftsense
