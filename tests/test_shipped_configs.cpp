// The shipped SURALP configs: they build, and the paper's literal measured-ZMP choice is caught
// by the independence rule unless explicitly allowed.

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"

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

}  // namespace
}  // namespace ftsense
