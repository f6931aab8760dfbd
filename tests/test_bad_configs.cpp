// Table-driven bad-config tests: each row breaks the valid base config with a JSON Patch and
// names the JSON Pointer and the rule the error message must carry.

#include <gtest/gtest.h>

#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "test_configs.hpp"

namespace ftsense {
namespace {

struct BadConfigCase {
  const char* name;
  const char* patch;          // RFC 6902 JSON Patch applied to test::base_config()
  const char* path;           // expected JSON Pointer of the problem
  const char* message_part;   // expected part of the message (the rule, the suggestion)
};

std::ostream& operator<<(std::ostream& os, const BadConfigCase& c) { return os << c.name; }

const BadConfigCase kCases[] = {
    {"negative_cutoff", R"([{"op": "replace", "path": "/stages/1/params/cutoff_hz", "value": -1}])",
     "/stages/1/params/cutoff_hz", " = -1 violates > 0 (cut-off frequency f_c, below 1 / (2 T), Hz)"},
    {"cutoff_above_nyquist", R"([{"op": "replace", "path": "/stages/1/params/cutoff_hz", "value": 600}])",
     "/stages/1/params/cutoff_hz", " = 600 violates < 500 (Nyquist frequency"},
    {"wrong_type", R"([{"op": "replace", "path": "/stages/1/params/cutoff_hz", "value": "5"}])",
     "/stages/1/params/cutoff_hz", " = \"5\" has type string, expected number"},
    {"unknown_parameter", R"([{"op": "add", "path": "/stages/1/params/cutof_hz", "value": 3}])",
     "/stages/1/params/cutof_hz", "unknown parameter of low_pass; did you mean 'cutoff_hz'?"},
    {"unknown_choice", R"([{"op": "add", "path": "/stages/1/params/start", "value": "first"}])",
     "/stages/1/params/start", "violates one of: first_sample, zero"},
    {"threshold_not_positive", R"([{"op": "replace", "path": "/stages/2/params/thresholds", "value": [0]}])",
     "/stages/2/params/thresholds/0", " = 0 violates > 0"},
    {"threshold_count", R"([{"op": "replace", "path": "/stages/2/params/thresholds", "value": [1, 2]}])",
     "/stages/2/params/thresholds", "has 2 entries but the signal has 3 channels"},
    {"missing_sample_period", R"([{"op": "remove", "path": "/sample_period_s"}])",
     "/sample_period_s", "missing required key"},
    {"negative_sample_period", R"([{"op": "replace", "path": "/sample_period_s", "value": -0.001}])",
     "/sample_period_s", " = -0.001 violates > 0"},
    {"unknown_top_level_key", R"([{"op": "add", "path": "/stage", "value": []}])",
     "/stage", "unknown key in the pipeline config; did you mean 'stages'?"},
    {"unknown_plugin", R"([{"op": "replace", "path": "/stages/1/plugin", "value": "low_pas"}])",
     "/stages/1/plugin", "unknown plugin 'low_pas'; did you mean 'low_pass'?"},
    {"wire_to_missing_port", R"([{"op": "replace", "path": "/stages/1/inputs/signal", "value": "residual.resid"}])",
     "/stages/1/inputs/signal", "stage 'residual' (difference_residual) has no output 'resid'; did you mean 'residual'?"},
    {"wire_to_missing_stage", R"([{"op": "replace", "path": "/stages/1/inputs/signal", "value": "residul.residual"}])",
     "/stages/1/inputs/signal", "no stage named 'residul'"},
    {"wire_selection_beyond_the_signal",
     R"([{"op": "replace", "path": "/stages/1/inputs/signal", "value": "residual.residual[1:4]"}])",
     "/stages/1/inputs/signal", "\"residual.residual[1:4]\" selects values 1 to 3 of residual.residual, which has 3"},
    {"wire_selection_malformed",
     R"([{"op": "replace", "path": "/stages/1/inputs/signal", "value": "residual.residual[2:1]"}])",
     "/stages/1/inputs/signal", "has a selection that is not \"[i]\" or \"[i:j]\" with 0 <= i < j"},
    {"input_scale_zero", R"([{"op": "add", "path": "/inputs/measured/scale", "value": 0}])",
     "/inputs/measured/scale", " = 0 would erase the signal; scale must not be 0"},
    {"input_offset_count", R"([{"op": "add", "path": "/inputs/measured/offset", "value": [1, 2]}])",
     "/inputs/measured/offset", "has 2 numbers for 3 columns"},
    {"time_unit_unknown", R"([{"op": "add", "path": "/time", "value": {"unit": "min"}}])",
     "/time/unit", " = \"min\" is not one of s, ms, us, ns"},
    {"wire_without_dot", R"([{"op": "replace", "path": "/stages/1/inputs/signal", "value": "residual"}])",
     "/stages/1/inputs/signal", "violates the wire form"},
    {"unknown_input_port", R"([{"op": "add", "path": "/stages/1/inputs/sigal", "value": "input.measured"}])",
     "/stages/1/inputs/sigal", "plugin low_pass has no input 'sigal'; did you mean 'signal'?"},
    {"missing_input", R"([{"op": "remove", "path": "/stages/0/inputs/virtual"}])",
     "/stages/0/inputs/virtual", "missing input of plugin difference_residual"},
    {"dimension_mismatch",
     R"([{"op": "replace", "path": "/stages/0/inputs/measured", "value": ["input.measured", "input.reference"]}])",
     "/stages/0/inputs/virtual", "carries 3 values [input.reference (3)] but input 'virtual' of difference_residual takes 6"},
    {"unit_mismatch", R"([{"op": "replace", "path": "/inputs/reference/unit", "value": "m"}])",
     "/stages/0/inputs/virtual", "unit mismatch: input.reference is in 'm' but input.measured is in 'N'"},
    {"cycle", R"([{"op": "replace", "path": "/stages/0/inputs/virtual", "value": "detect.fault"}])",
     "/stages", "the stages form a cycle (residual -> smooth -> detect -> residual)"},
    {"independence_rule",
     R"([{"op": "add", "path": "/inputs/virtual_from_cells",
          "value": {"columns": ["a", "b", "c"], "unit": "N", "derived_from": ["measured"]}},
         {"op": "replace", "path": "/stages/0/inputs/virtual", "value": "input.virtual_from_cells"}])",
     "/stages/0/inputs/virtual", "independence rule: the virtual sensor 'virtual' of stage 'residual' is computed from input 'measured'"},
    {"duplicate_stage_name", R"([{"op": "replace", "path": "/stages/2/name", "value": "smooth"}])",
     "/stages/2/name", "duplicate stage name 'smooth' (also /stages/1)"},
    {"reserved_stage_name", R"([{"op": "replace", "path": "/stages/2/name", "value": "input"}])",
     "/stages/2/name", "violates identifier"},
    {"unknown_derived_from",
     R"([{"op": "add", "path": "/inputs/measured/derived_from", "value": ["refrence"]}])",
     "/inputs/measured/derived_from/0", "unknown input 'refrence'; did you mean 'reference'?"},
    {"empty_columns", R"([{"op": "replace", "path": "/inputs/measured/columns", "value": []}])",
     "/inputs/measured/columns", "is empty"},
    {"monitor_channel_count", R"([{"op": "remove", "path": "/monitor/channels/2"}])",
     "/monitor/measured", "carries 3 values but the monitor has 2 channels"},
    {"monitor_missing_field", R"([{"op": "remove", "path": "/monitor/fault_type"}])",
     "/monitor/fault_type", "missing required key"},
    {"params_not_object", R"([{"op": "replace", "path": "/stages/1/params", "value": [2.0]}])",
     "/stages/1/params", " = [2.0] has type array, expected object"},
    {"stage_not_object", R"([{"op": "replace", "path": "/stages/2", "value": "detect"}])",
     "/stages/2", "has type string, expected object"},
    // previous_tick: a signal read one tick late, declared with its size and unit.
    {"previous_tick_dim_not_the_signals",
     R"([{"op": "add", "path": "/previous_tick", "value": {"last": {"signal": "smooth.filtered", "dim": 2, "unit": "N"}}}])",
     "/previous_tick/last/dim", " = 2 but \"smooth.filtered\" carries 3 values; declare \"dim\": 3"},
    {"previous_tick_unit_not_the_signals",
     R"([{"op": "add", "path": "/previous_tick", "value": {"last": {"signal": "smooth.filtered", "dim": 3, "unit": "m"}}}])",
     "/previous_tick/last/unit", " = \"m\" but \"smooth.filtered\" is in 'N'; declare \"unit\": \"N\""},
    {"previous_tick_dim_not_whole",
     R"([{"op": "add", "path": "/previous_tick", "value": {"last": {"signal": "smooth.filtered", "dim": 2.5, "unit": "N"}}}])",
     "/previous_tick/last/dim", " = 2.5 violates whole number >= 1"},
    {"previous_tick_unknown_name",
     R"([{"op": "add", "path": "/previous_tick", "value": {"last": {"signal": "smooth.filtered", "dim": 3, "unit": "N"}}},
         {"op": "replace", "path": "/stages/0/inputs/virtual", "value": "previous_tick.lst"}])",
     "/stages/0/inputs/virtual", "no previous-tick signal named 'lst'; did you mean 'last'?"},
    {"previous_tick_undeclared", R"([{"op": "replace", "path": "/stages/0/inputs/virtual", "value": "previous_tick.last"}])",
     "/stages/0/inputs/virtual", "no previous-tick signal named 'last'; declare it under \"previous_tick\""},
    {"previous_tick_of_a_previous_tick",
     R"([{"op": "add", "path": "/previous_tick", "value": {
           "last": {"signal": "smooth.filtered", "dim": 3, "unit": "N"},
           "before": {"signal": "previous_tick.last", "dim": 3, "unit": "N"}}}])",
     "/previous_tick/before/signal", "reads a previous-tick signal; name the signal it delays itself"},
    {"previous_tick_missing_unit",
     R"([{"op": "add", "path": "/previous_tick", "value": {"last": {"signal": "smooth.filtered", "dim": 3}}}])",
     "/previous_tick/last/unit", "missing required key"},
    {"previous_tick_unknown_key",
     R"([{"op": "add", "path": "/previous_tick", "value": {"last": {"signal": "smooth.filtered", "dim": 3, "unit": "N", "inital": 1}}}])",
     "/previous_tick/last/inital", "unknown key in a previous-tick signal; did you mean 'initial'?"},
    {"previous_tick_unknown_stage",
     R"([{"op": "add", "path": "/previous_tick", "value": {"last": {"signal": "smoth.filtered", "dim": 3, "unit": "N"}}}])",
     "/previous_tick/last/signal", "no stage named 'smoth'"},
    {"stage_named_previous_tick", R"([{"op": "replace", "path": "/stages/2/name", "value": "previous_tick"}])",
     "/stages/2/name", "not 'input' or 'previous_tick'"},
    // A loop through previous_tick feeds the measured sensor into its own virtual sensor.
    {"previous_tick_loop_breaks_independence",
     R"([{"op": "add", "path": "/previous_tick", "value": {"last": {"signal": "smooth.filtered", "dim": 3, "unit": "N"}}},
         {"op": "replace", "path": "/stages/0/inputs/virtual", "value": "previous_tick.last"}])",
     "/stages/0/inputs/virtual", "independence rule: the virtual sensor 'virtual' of stage 'residual' is computed from input 'measured'"},
};

class BadConfig : public ::testing::TestWithParam<BadConfigCase> {};

TEST_P(BadConfig, IsRejectedWithPathAndRule) {
  const BadConfigCase& c = GetParam();
  const Json config = test::base_config().patch(Json::parse(c.patch));
  try {
    (void)Pipeline::build(config, reference_plugins::registry());
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    bool found = false;
    for (const auto& p : e.problems()) {
      found = found || (p.path == c.path && p.message.find(c.message_part) != std::string::npos);
    }
    EXPECT_TRUE(found) << "expected at " << c.path << ": " << c.message_part << "\ngot:\n" << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Table, BadConfig, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(BadConfig, EveryProblemIsReportedTogether) {
  const Json config = test::base_config().patch(Json::parse(R"([
      {"op": "replace", "path": "/stages/1/params/cutoff_hz", "value": -1},
      {"op": "replace", "path": "/stages/2/plugin", "value": "treshold_detector"},
      {"op": "add", "path": "/bogus", "value": 1}])"));
  try {
    (void)Pipeline::build(config, reference_plugins::registry());
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems().size(), 3u) << e.what();
    // One line per problem in what().
    const std::string text = e.what();
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2) << text;
  }
}

TEST(BadConfig, IndependenceViolationIsAWarningWhenExplicitlyAllowed) {
  const Json config = test::base_config().patch(Json::parse(R"([
      {"op": "add", "path": "/inputs/virtual_from_cells",
       "value": {"columns": ["a", "b", "c"], "unit": "N", "derived_from": ["measured"]}},
      {"op": "replace", "path": "/stages/0/inputs/virtual", "value": "input.virtual_from_cells"},
      {"op": "add", "path": "/allow_dependent_virtual_sensor", "value": true}])"));
  const Pipeline pipeline = Pipeline::build(config, reference_plugins::registry());
  ASSERT_EQ(pipeline.warnings().size(), 1u);
  EXPECT_EQ(pipeline.warnings()[0].path, "/stages/0/inputs/virtual");
  EXPECT_NE(pipeline.warnings()[0].message.find("accepted because"), std::string::npos);
}

TEST(BadConfig, TransitiveDependenceThroughStagesIsFound) {
  // The virtual sensor is a low-passed copy of the measured signal: still not independent.
  const Json config = test::base_config().patch(Json::parse(R"([
      {"op": "add", "path": "/stages/-",
       "value": {"name": "copy", "plugin": "low_pass", "inputs": {"signal": "input.measured"}}},
      {"op": "replace", "path": "/stages/0/inputs/virtual", "value": "copy.filtered"}])"));
  try {
    (void)Pipeline::build(config, reference_plugins::registry());
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems()[0].path, "/stages/0/inputs/virtual");
    EXPECT_NE(e.problems()[0].message.find("independence rule"), std::string::npos);
  }
}

// An integer parameter without bounds: only the integer type limits it.
struct IntegerParams {
  int count = 0;
  static void describe(ParamSchema<IntegerParams>& s) { s.add("count", &IntegerParams::count, "a count"); }
};

TEST(BadConfig, IntegerBeyondSixtyFourBitsIsNotWrapped) {
  // nlohmann keeps 2^64 - 1 as an unsigned integer; get<long long>() used to wrap it to -1.
  for (const char* text : {R"({"count": 18446744073709551615})", R"({"count": 9223372036854775808})"}) {
    Diagnostics diag;
    const IntegerParams p = load_params<IntegerParams>(Json::parse(text), "/params", "test", diag);
    ASSERT_EQ(diag.errors().size(), 1u) << text << " loaded as " << p.count;
    EXPECT_EQ(diag.errors()[0].path, "/params/count");
    EXPECT_NE(diag.errors()[0].message.find("violates the range of a 64-bit integer"), std::string::npos)
        << diag.errors()[0].message;
  }
  Diagnostics diag;
  EXPECT_EQ(load_params<IntegerParams>(Json::parse(R"({"count": -7})"), "/params", "test", diag).count, -7);
  EXPECT_FALSE(diag.has_errors());
}

struct BadTextCase {
  const char* name;
  const char* text;
  const char* path;
  const char* message_part;
};
std::ostream& operator<<(std::ostream& os, const BadTextCase& c) { return os << c.name; }

const BadTextCase kTextCases[] = {
    {"syntax_error", "{\n  \"sample_period_s\": 0.001,\n  \"inputs\": {,\n}", "c.json:3:14", "not valid JSON"},
    {"doubly_driven_input",
     R"({"stages": [{"name": "a", "inputs": {"signal": "x.y", "signal": "z.w"}}]})",
     "/stages/0/inputs/signal", "duplicate key 'signal'"},
    {"duplicate_top_level_key", R"({"stages": [], "stages": []})", "/stages", "duplicate key 'stages'"},
    {"empty_text", "", "c.json:1:1", "not valid JSON"},
    // Found by fuzz/fuzz_config: nlohmann throws out_of_range (not parse_error) for these.
    {"number_overflow", "{\"sample_period_s\": \"1e710\",\n \"x\": [1, 1e710]}", "c.json:2:11",
     "number overflow parsing '1e710'"},
    {"negative_number_overflow", "[-1e400]", "c.json:1:2", "number overflow parsing '-1e400'"},
};

class BadConfigText : public ::testing::TestWithParam<BadTextCase> {};

TEST_P(BadConfigText, IsRejectedWithPosition) {
  const BadTextCase& c = GetParam();
  try {
    (void)parse_json_text(c.text, "c.json");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    ASSERT_FALSE(e.problems().empty());
    EXPECT_EQ(e.problems()[0].path, c.path) << e.what();
    EXPECT_NE(e.problems()[0].message.find(c.message_part), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Table, BadConfigText, ::testing::ValuesIn(kTextCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(BadConfigText, NulByteIsRejected) {
  // nlohmann ends the text at a NUL byte: {"a": 1}\0garbage used to load as {"a": 1}.
  const std::string text("{\"a\": 1}\n\0garbage", 17);
  try {
    (void)parse_json_text(text, "c.json");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].path, "c.json:2:1") << e.what();
    EXPECT_NE(e.problems()[0].message.find("not valid JSON: a NUL byte"), std::string::npos) << e.what();
  }
}

TEST(BadConfigText, DeepNestingIsRejectedNotAStackOverflow) {
  // Found by fuzz/fuzz_config: 8000 nested arrays as a stage's params overflowed the stack when
  // the builder copied them. Strings may hold any number of brackets.
  const std::string deep = std::string(8000, '[') + std::string(8000, ']');
  const std::string text = R"({"description": "[[[[[[", "stages": [{"params": )" + deep + "}]}";
  try {
    (void)parse_json_text(text, "c.json");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].path, "c.json:1:" + std::to_string(48 + kMaxJsonDepth - 2)) << e.what();
    EXPECT_NE(e.problems()[0].message.find("nested deeper than 100"), std::string::npos) << e.what();
  }
  const std::string ok = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_TRUE(parse_json_text(ok, "c.json").is_array());
}

}  // namespace
}  // namespace ftsense
