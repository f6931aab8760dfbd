// Config definitions and {"$ref": "#/definitions/<name>"} (config_definitions.hpp): exact
// substitution, nested use, and every misuse reported at its JSON Pointer.

#include <gtest/gtest.h>

#include "ftsense/config_definitions.hpp"
#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"

namespace ftsense {
namespace {

std::vector<std::string> problems(const Json& config) {
  Diagnostics diag;
  (void)resolve_definitions(config, diag);
  std::vector<std::string> out;
  try {
    diag.throw_if_errors();
  } catch (const ConfigError& e) {
    for (const auto& p : e.problems()) out.push_back(p.text());
  }
  return out;
}

TEST(ConfigDefinitions, ReferencesAreReplacedByCopiesNestedOnesToo) {
  const Json config = Json::parse(R"({
    "definitions": {"outline": [[1, 2], [3, 4]], "foot": {"points": {"$ref": "#/definitions/outline"}, "n": 2}},
    "stages": [{"params": {"points": {"$ref": "#/definitions/outline"}}},
               {"params": {"$ref": "#/definitions/foot"}}]
  })");
  Diagnostics diag;
  const Json resolved = resolve_definitions(config, diag);
  EXPECT_FALSE(diag.has_errors());
  EXPECT_EQ(resolved["stages"][0]["params"]["points"], Json::parse("[[1, 2], [3, 4]]"));
  EXPECT_EQ(resolved["stages"][1]["params"], Json::parse(R"({"points": [[1, 2], [3, 4]], "n": 2})"));
  EXPECT_EQ(resolved["definitions"], config["definitions"]);  // kept as written
}

TEST(ConfigDefinitions, MisusesAreReportedAtTheirPointer) {
  EXPECT_EQ(problems(Json::parse(R"({"definitions": {"outline": []}, "a": {"$ref": "#/definitions/outlin"}})")),
            std::vector<std::string>{"/a/$ref = \"#/definitions/outlin\": no definition named 'outlin'; did you mean 'outline'? known: outline"});
  EXPECT_EQ(problems(Json::parse(R"({"a": {"$ref": "#/stages/0"}})")),
            std::vector<std::string>{"/a/$ref = \"#/stages/0\" is not \"#/definitions/<name>\"; a config refers only to "
                                     "its own top-level definitions"});
  EXPECT_EQ(problems(Json::parse(R"({"definitions": {"x": 1}, "a": [{"$ref": "#/definitions/x", "y": 2}]})")),
            std::vector<std::string>{"/a/0: a reference has the key \"$ref\" alone; move the other keys into the definition"});
  const auto cycle = problems(Json::parse(
      R"({"definitions": {"x": {"$ref": "#/definitions/y"}, "y": [{"$ref": "#/definitions/x"}]}, "a": {"$ref": "#/definitions/x"}})"));
  ASSERT_EQ(cycle.size(), 1u);
  EXPECT_NE(cycle[0].find("refers back to itself (through the definitions of 'x', 'y')"), std::string::npos) << cycle[0];
  EXPECT_EQ(problems(Json::parse(R"({"definitions": [1]})")),
            std::vector<std::string>{"/definitions = [1] is not an object of named values (\"<name>\": value)"});
}

TEST(ConfigDefinitions, APipelineBuiltFromReferencesIsTheSameAsOneWrittenOut) {
  const Json written = Json::parse(R"({
    "sample_period_s": 0.001,
    "inputs": {"measured": {"columns": ["a", "b"], "unit": "N"}, "model": {"columns": ["c", "d"], "unit": "N"}},
    "stages": [{"name": "residual", "plugin": "difference_residual",
                "inputs": {"measured": "input.measured", "virtual": "input.model"}},
               {"name": "detect", "plugin": "threshold_detector", "params": {"thresholds": [5, 7]},
                "inputs": {"signal": "residual.residual"}}]
  })");
  Json referenced = written;
  referenced["definitions"] = {{"limits", {5, 7}}};
  referenced["stages"][1]["params"]["thresholds"] = {{"$ref", "#/definitions/limits"}};
  Pipeline a = Pipeline::build(written, reference_plugins::registry());
  Pipeline b = Pipeline::build(referenced, reference_plugins::registry());
  EXPECT_EQ(a.stage(1).params_json(), b.stage(1).params_json());
  referenced["stages"][1]["params"]["thresholds"] = {{"$ref", "#/definitions/limit"}};
  try {
    (void)Pipeline::build(referenced, reference_plugins::registry());
    FAIL() << "an unknown definition must not build";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].path, "/stages/1/params/thresholds/$ref");
  }
}

}  // namespace
}  // namespace ftsense
