// Parameter descriptions: strict loading, defaults, round trips, rules in words.

#include <gtest/gtest.h>

#include "ftsense/params.hpp"

namespace ftsense {
namespace {

enum class Mode { fast, exact };

struct AllKinds {
  double gain = 2.0;
  int window = 10;
  bool enabled = true;
  std::string label = "x";
  Mode mode = Mode::exact;
  std::vector<double> weights{1.0};  // one weight for all points
  std::vector<std::array<double, 2>> points{{0.1, 0.2}, {0.3, 0.4}, {0.5, 0.6}};
  double mass_kg = 0.0;  // required

  static void describe(ParamSchema<AllKinds>& s) {
    s.add("gain", &AllKinds::gain, "a gain").at_least(0.0).at_most(10.0);
    s.add("window", &AllKinds::window, "window length").greater_than(0);
    s.add("enabled", &AllKinds::enabled, "switch");
    s.add("label", &AllKinds::label, "a label");
    s.add_choice("mode", &AllKinds::mode, "solver mode", {{"fast", Mode::fast}, {"exact", Mode::exact}});
    s.add("weights", &AllKinds::weights, "weights").greater_than(0.0).count_at_least(1).count_at_most(4);
    s.add("points", &AllKinds::points, "contact points").unit("m").count_at_least(3);
    s.add("mass_kg", &AllKinds::mass_kg, "total mass").unit("kg").greater_than(0.0).required();
  }

  // Cross-field rule: as many weights as points, or one.
  void validate(Diagnostics& d, std::string_view path) const {
    if (weights.size() != 1 && weights.size() != points.size()) {
      d.error(std::string(path) + "/weights", "needs 1 or " + std::to_string(points.size()) + " entries");
    }
  }
};

TEST(Params, DefaultsComeFromMemberInitialisers) {
  Diagnostics d;
  const auto p = load_params<AllKinds>(Json{{"mass_kg", 114}}, "/params", "test", d);
  EXPECT_FALSE(d.has_errors());
  EXPECT_EQ(p.gain, 2.0);
  EXPECT_EQ(p.window, 10);
  EXPECT_EQ(p.mode, Mode::exact);
  EXPECT_EQ(p.mass_kg, 114.0);
  EXPECT_EQ(p.points.size(), 3u);
}

TEST(Params, EveryKindLoads) {
  Diagnostics d;
  const auto p = load_params<AllKinds>(Json::parse(R"({
      "gain": 10, "window": 3, "enabled": false, "label": "foot", "mode": "fast",
      "weights": [1, 2, 3], "points": [[0, 0], [1, 0], [0, 1]], "mass_kg": 1.5})"),
                                       "/p", "test", d);
  for (const auto& e : d.errors()) ADD_FAILURE() << e.text();
  EXPECT_EQ(p.gain, 10.0);  // inclusive upper bound
  EXPECT_EQ(p.window, 3);
  EXPECT_FALSE(p.enabled);
  EXPECT_EQ(p.label, "foot");
  EXPECT_EQ(p.mode, Mode::fast);
  EXPECT_EQ(p.weights, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(p.points[1][0], 1.0);
}

TEST(Params, AllProblemsAreCollectedWithPaths) {
  Diagnostics d;
  (void)load_params<AllKinds>(Json::parse(R"({
      "gain": 11, "window": 2.5, "enabled": 1, "mode": "quick", "weights": [], "points": [[0, 0], [1]],
      "extra": true})"),
                              "/stages/0/params", "test", d);
  std::vector<std::string> lines;
  for (const auto& e : d.errors()) lines.push_back(e.text());
  const std::vector<std::string> expected{
      "/stages/0/params/extra: unknown parameter of test; known: gain, window, enabled, label, mode, "
      "weights, points, mass_kg",
      "/stages/0/params/gain = 11 violates >= 0 and <= 10 (a gain)",
      "/stages/0/params/window = 2.5 has type number, expected integer (window length)",
      "/stages/0/params/enabled = 1 has type number, expected boolean (switch)",
      "/stages/0/params/mode = \"quick\" violates one of: fast, exact (solver mode); known: fast, exact",
      "/stages/0/params/weights = [] (0 entries) violates at least 1 entries (weights)",
      "/stages/0/params/points = [[0,0],[1]] (2 entries) violates at least 3 entries (contact points, m)",
      "/stages/0/params/points/1 = [1] has type array, expected [x, y] point (array of 2 numbers) "
      "(contact points, m)",
      "/stages/0/params/mass_kg: missing required parameter (total mass, kg); add it to the "
      "parameters of test",
  };
  EXPECT_EQ(lines, expected);
}

TEST(Params, CrossFieldValidationRunsOnlyWhenFieldsLoaded) {
  Diagnostics ok_fields;
  (void)load_params<AllKinds>(Json::parse(R"({"mass_kg": 1, "weights": [1, 2]})"), "/p", "test", ok_fields);
  ASSERT_EQ(ok_fields.errors().size(), 1u);
  EXPECT_EQ(ok_fields.errors()[0].text(), "/p/weights: needs 1 or 3 entries");

  Diagnostics bad_field;
  (void)load_params<AllKinds>(Json::parse(R"({"mass_kg": -1, "weights": [1, 2]})"), "/p", "test", bad_field);
  ASSERT_EQ(bad_field.errors().size(), 1u);
  EXPECT_EQ(bad_field.errors()[0].path, "/p/mass_kg");
}

TEST(Params, SaveLoadRoundTrip) {
  Diagnostics d;
  auto p = load_params<AllKinds>(Json{{"mass_kg", 80}}, "", "test", d);
  p.mode = Mode::fast;
  p.points = {{1, 2}, {3, 4}, {5, 6}};
  const Json saved = save_params(p);
  EXPECT_EQ(saved.at("mode"), "fast");
  const auto again = load_params<AllKinds>(saved, "", "test", d);
  EXPECT_FALSE(d.has_errors());
  EXPECT_EQ(save_params(again), saved);
}

TEST(Params, RulesInWords) {
  const auto infos = param_infos<AllKinds>();
  ASSERT_EQ(infos.size(), 8u);
  EXPECT_EQ(infos[0].rule(), ">= 0 and <= 10");
  EXPECT_EQ(infos[1].rule(), "> 0");
  EXPECT_EQ(infos[4].rule(), "one of: fast, exact");
  EXPECT_EQ(infos[5].rule(), "each > 0; at least 1 entries, at most 4 entries");
  EXPECT_EQ(infos[0].default_value, Json(2.0));
  EXPECT_TRUE(infos[7].required);
  EXPECT_TRUE(infos[7].default_value.is_null());
}

TEST(Params, IntegerOutOfRangeIsAnError) {
  Diagnostics d;
  (void)load_params<AllKinds>(Json::parse(R"({"mass_kg": 1, "window": 9000000000})"), "/p", "test", d);
  ASSERT_EQ(d.errors().size(), 1u);
  EXPECT_NE(d.errors()[0].message.find("32-bit integer"), std::string::npos);
}

// A plausible range: inside the bounds, outside the range is a warning, not an error.
struct Robot {
  double mass_kg = 50.0;
  int ticks = 20;
  std::vector<double> heights_m{0.5};
  std::vector<std::array<double, 2>> points{{0.1, 0.05}};

  static void describe(ParamSchema<Robot>& s) {
    s.add("mass_kg", &Robot::mass_kg, "robot mass").unit("kg").greater_than(0.0).plausible(1.0, 1000.0, "robot mass");
    s.add("ticks", &Robot::ticks, "ticks").at_least(1).plausible(2, 100, "a few ticks");
    s.add("heights_m", &Robot::heights_m, "heights").unit("m").greater_than(0.0).plausible(0.01, 3.0, "heights");
    s.add("points", &Robot::points, "foot points").unit("m").plausible(-1.0, 1.0, "feet");
  }
};

TEST(Params, ImplausibleValueIsAWarningWithItsPath) {
  Diagnostics d;
  const auto p = load_params<Robot>(Json{{"mass_kg", 0.001}}, "/stages/3/params", "test", d);
  EXPECT_FALSE(d.has_errors());
  ASSERT_EQ(d.warnings().size(), 1u);
  EXPECT_EQ(d.warnings()[0].path, "/stages/3/params/mass_kg");
  EXPECT_EQ(d.warnings()[0].text(),
            "/stages/3/params/mass_kg = 0.001 is outside the plausible range 1 .. 1000 kg (robot mass); "
            "check the unit or the value");
  EXPECT_EQ(p.mass_kg, 0.001);  // a warning keeps the value: the user may mean it
}

TEST(Params, PlausibleRangeIsInclusiveAndQuietInside) {
  for (const double mass : {1.0, 114.0, 1000.0}) {
    Diagnostics d;
    Json params = Json::parse(R"({"ticks": 2, "heights_m": [0.01, 3.0], "points": [[-1.0, 1.0]]})");
    params["mass_kg"] = mass;
    (void)load_params<Robot>(params, "/p", "test", d);
    EXPECT_FALSE(d.has_errors()) << mass;
    EXPECT_TRUE(d.warnings().empty()) << mass << ": " << d.warnings()[0].text();
  }
  Diagnostics defaults;
  (void)load_params<Robot>(Json::object(), "/p", "test", defaults);
  EXPECT_TRUE(defaults.warnings().empty());
}

TEST(Params, ImplausibleIntegersListEntriesAndPointCoordinatesWarnEach) {
  Diagnostics d;
  (void)load_params<Robot>(Json::parse(R"({"mass_kg": 1e300, "ticks": 1000000, "heights_m": [0.5, 1e-300, 7],
                                           "points": [[0.1, 0.05], [120, -0.05]]})"),
                           "/p", "test", d);
  EXPECT_FALSE(d.has_errors());
  std::vector<std::string> lines;
  for (const auto& w : d.warnings()) lines.push_back(w.text());
  const std::vector<std::string> expected{
      "/p/mass_kg = 1e+300 is outside the plausible range 1 .. 1000 kg (robot mass); check the unit or the value",
      "/p/ticks = 1000000 is outside the plausible range 2 .. 100 (a few ticks); check the unit or the value",
      "/p/heights_m/1 = 1e-300 is outside the plausible range 0.01 .. 3 m (heights); check the unit or the value",
      "/p/heights_m/2 = 7 is outside the plausible range 0.01 .. 3 m (heights); check the unit or the value",
      "/p/points/1/0 = 120 is outside the plausible range -1 .. 1 m (feet); check the unit or the value",
  };
  EXPECT_EQ(lines, expected);
}

TEST(Params, HardBoundsStayErrorsWithoutAPlausibilityWarning) {
  Diagnostics d;
  (void)load_params<Robot>(Json::parse(R"({"mass_kg": -5, "ticks": 0})"), "/p", "test", d);
  ASSERT_EQ(d.errors().size(), 2u);
  EXPECT_EQ(d.errors()[0].text(), "/p/mass_kg = -5 violates > 0 (robot mass, kg)");
  EXPECT_EQ(d.errors()[1].text(), "/p/ticks = 0 violates >= 1 (ticks)");
  EXPECT_TRUE(d.warnings().empty());
}

TEST(Params, PlausibleRangeInWords) {
  const auto infos = param_infos<Robot>();
  ASSERT_TRUE(infos[0].plausible.has_value());
  EXPECT_EQ(infos[0].plausible->text(infos[0].unit), "1 .. 1000 kg (robot mass)");
  EXPECT_EQ(infos[0].rule(), "> 0");  // the rule stays the hard bound
  EXPECT_FALSE(param_infos<AllKinds>()[0].plausible.has_value());
}

TEST(JsonPointer, TokensAreEscaped) {
  EXPECT_EQ(json_pointer_append("/inputs", "r_foot/p1~x"), "/inputs/r_foot~1p1~0x");
  EXPECT_EQ(json_pointer_append("/stages", 3), "/stages/3");
}

TEST(Suggest, ClosestNameOrNothing) {
  EXPECT_EQ(closest_match("low_pas", {"low_pass", "threshold_detector"}), "low_pass");
  EXPECT_EQ(closest_match("kalman", {"low_pass", "threshold_detector"}), "");
  EXPECT_EQ(suggest("x", {}), "known: (none)");
}

}  // namespace
}  // namespace ftsense
