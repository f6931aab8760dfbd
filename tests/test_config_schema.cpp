// What the config reference's port tables and the config schema are made of: every reference
// plugin lists its ports from its example parameters, and the schema's wire form is the reader's.
// (tests/cli/check_config_schema.py validates the shipped configs against the committed schema.)

#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/config_schema.hpp"
#include "ftsense/pipeline_document.hpp"
#include "ftsense/reference_plugins.hpp"
#include "test_configs.hpp"

namespace ftsense {
namespace {

bool reader_accepts_wire(const std::string& wire) {
  Json config = test::base_config();
  config["stages"][1]["inputs"]["signal"] = wire;
  Diagnostics diag;
  (void)read_pipeline_document(config, diag);
  return !diag.has_errors();
}

TEST(ConfigSchema, WireEndPatternIsTheReadersForm) {
  // Known names only: the reader also resolves names, which no pattern can.
  const std::vector<std::string> good{"input.measured", "input.measured[0]", "input.measured[0:2]",
                                      "residual.residual", "residual.residual[2]", "residual.x_1[10:999999]"};
  const std::vector<std::string> bad{"input",          "inputmeasured",      "input.",
                                     ".measured",      "input.measured[",    "input.measured[]",
                                     "input.measured[a]", "input.measured[1:]", "input.measured[-1]",
                                     "input.measured[1;2]", "input.measured [0]", "input.measured[1234567]",
                                     "input.measured[0][1]", "input.measured.x", " input.measured"};
  const std::regex pattern{std::string(kWireEndPattern)};
  for (const std::string& wire : good) {
    EXPECT_TRUE(std::regex_match(wire, pattern)) << wire;
    EXPECT_TRUE(reader_accepts_wire(wire)) << wire;
  }
  for (const std::string& wire : bad) {
    EXPECT_FALSE(std::regex_match(wire, pattern)) << wire;
    EXPECT_FALSE(reader_accepts_wire(wire)) << wire;
  }
}

TEST(ConfigSchema, EveryReferencePluginListsItsPortsFromItsExample) {
  const PluginRegistry registry = reference_plugins::registry();
  const std::regex identifier{"[A-Za-z_][A-Za-z0-9_]*"};
  for (const PluginInfo& plugin : registry.plugins()) {
    Diagnostics diag;
    const auto ports = plugin.example_ports(0.001, diag);
    ASSERT_TRUE(ports.has_value()) << plugin.name << ": " << diag.errors().front().text();
    EXPECT_FALSE(ports->inputs().empty()) << plugin.name;
    EXPECT_FALSE(ports->outputs().empty()) << plugin.name;
    for (const auto* list : {&ports->inputs(), &ports->outputs()}) {
      for (const PortSpec& port : *list) {
        // Wires name ports as identifiers (kWireEndPattern).
        EXPECT_TRUE(std::regex_match(port.name, identifier)) << plugin.name << "." << port.name;
        EXPECT_FALSE(port.description.empty()) << plugin.name << "." << port.name;
        // A frame belongs in `frame`, not in the words.
        EXPECT_EQ(port.description.find("world frame"), std::string::npos) << plugin.name << "." << port.name;
      }
    }
  }
}

TEST(ConfigSchema, PortsAddedByParametersAreListed) {
  // The examples are a union: lipm_com_estimator's ZMP input depends on zmp_source, and
  // urdf_kinematics lists its ports without reading a URDF.
  const PluginRegistry registry = reference_plugins::registry();
  Diagnostics diag;
  const auto lipm = registry.find("lipm_com_estimator")->example_ports(0.001, diag);
  ASSERT_TRUE(lipm.has_value());
  EXPECT_TRUE(lipm->find_input("planned_zmp").has_value());
  EXPECT_TRUE(lipm->find_input("measured_zmp").has_value());
  EXPECT_TRUE(lipm->find_input("kinematic_com").has_value());
  const auto urdf = registry.find("urdf_kinematics")->example_ports(0.001, diag);
  ASSERT_TRUE(urdf.has_value()) << diag.errors().front().text();
  const PortSpec& joints = urdf->inputs().at(*urdf->find_input("joint_positions"));
  EXPECT_EQ(joints.dim, 6u);  // the example's six joints
  EXPECT_EQ(joints.dim_rule, "len(params.joints)");
  EXPECT_EQ(urdf->outputs().at(*urdf->find_output("com")).frame, "world");
}

TEST(ConfigSchema, SizeRulesInWordsHoldWhenTheWiringChanges) {
  // A port "as wired" takes the size wired to it, and a port "as `p`" that of port p: build each
  // plugin's first example with its "as wired" input wired to 5 values and compare.
  constexpr std::size_t kWired = 5;
  const PluginRegistry registry = reference_plugins::registry();
  std::size_t checked = 0;
  for (const PluginInfo& plugin : registry.plugins()) {
    Diagnostics diag;
    const auto example = plugin.example_ports(0.001, diag);
    ASSERT_TRUE(example.has_value()) << plugin.name;
    for (const PortSpec& wired : example->inputs()) {
      if (wired.dim_rule != "as wired") continue;
      Json params = plugin.example_params.empty() ? Json::object() : Json::parse(plugin.example_params);
      if (params.is_array()) params = params.back();
      const StageContext context(0.001, "stage", {{wired.name, kWired}});
      const auto stage = plugin.create(params, "/stages/0", context, diag);
      ASSERT_NE(stage, nullptr) << plugin.name << ": " << diag.errors().front().text();
      for (const auto* list : {&stage->ports().inputs(), &stage->ports().outputs()}) {
        for (const PortSpec& port : *list) {
          if (port.dim_rule == "as wired" || port.dim_rule == "as `" + wired.name + "`") {
            EXPECT_EQ(port.dim, kWired) << plugin.name << "." << port.name;
            ++checked;
          }
        }
      }
    }
  }
  EXPECT_GE(checked, 30u);  // the generic plugins' channels
}

TEST(ConfigSchema, StagesAreCheckedByTheirPlugin) {
  const PluginRegistry registry = reference_plugins::registry();
  const Json schema = config_json_schema(registry);
  EXPECT_EQ(schema.at("$schema"), kJsonSchemaDraft);
  const Json& stage = schema.at("definitions").at("stage");
  EXPECT_EQ(stage.at("properties").at("plugin").at("enum"), Json(registry.names()));
  ASSERT_EQ(stage.at("allOf").size(), registry.plugins().size());
  for (const PluginInfo& plugin : registry.plugins()) {
    const Json& params = schema.at("definitions").at("params." + plugin.name);
    EXPECT_EQ(params.at("properties").size(), plugin.params.size()) << plugin.name;
    for (const ParamInfo& p : plugin.params) {
      const Json& property = params.at("properties").at(p.key);
      if (p.required) {
        EXPECT_FALSE(property.contains("default")) << plugin.name << "." << p.key;
      } else {
        EXPECT_EQ(property.at("default"), p.default_value) << plugin.name << "." << p.key;
      }
    }
  }
  // Every key of every document section is a property of its definition.
  EXPECT_EQ(schema.at("properties").size(), document_section(DocumentSectionId::pipeline).keys.size());
  EXPECT_EQ(schema.at("definitions").at("input").at("properties").size(),
            document_section(DocumentSectionId::input).keys.size());
  EXPECT_EQ(schema.at("definitions").at("time").at("properties").at("unit").at("enum"),
            Json::array({"s", "ms", "us", "ns"}));
}

}  // namespace
}  // namespace ftsense
