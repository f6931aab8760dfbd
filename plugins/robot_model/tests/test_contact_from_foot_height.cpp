// contact_from_foot_height: the contract suite, the hysteresis on a synthetic trace, NaN heights,
// any number of feet, and its configuration errors.

#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/pipeline.hpp"
#include "ftsense/robot_model/contact_from_foot_height.hpp"
#include "ftsense/robot_model/robot_model_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {

template <>
struct ContractSetup<robot_model::ContactFromFootHeight> {
  static Json params() { return {{"touchdown_height_m", 0.02}, {"liftoff_height_m", 0.05}}; }
  static std::size_t input_dim(std::string_view) { return 6; }
  static void nominal_input(std::string_view, std::span<double> v) {
    // Left foot on the ground, right foot 10 cm up.
    std::fill(v.begin(), v.end(), 0.0);
    v[1] = 0.1, v[4] = -0.1, v[5] = 0.1;
  }
  static double sample_period_s() { return 1e-3; }
};

INSTANTIATE_TYPED_TEST_SUITE_P(FootHeight, PluginContract, ::testing::Types<robot_model::ContactFromFootHeight>);

}  // namespace ftsense::testing

namespace ftsense::robot_model {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The plugin over `feet` feet at x = y = 0, fed one height per foot and tick.
class Trace {
 public:
  Trace(const Json& params, std::size_t feet) : foot_pos_(3 * feet, 0.0), contact_(feet, -1.0) {
    Diagnostics diag;
    const auto p = load_params<ContactFromFootHeight::Params>(params, "/params", ContactFromFootHeight::name, diag);
    EXPECT_FALSE(diag.has_errors());
    plugin_ = std::make_unique<ContactFromFootHeight>(p, StageContext(1e-3, "contact", {{"foot_pos", 3 * feet}}));
    plugin_->reset();
  }
  const std::vector<double>& step(const std::vector<double>& heights) {
    for (std::size_t i = 0; i < heights.size(); ++i) foot_pos_[3 * i + 2] = heights[i];
    const std::span<const double> ins[] = {foot_pos_};
    const std::span<double> outs[] = {contact_};
    plugin_->step(StepIO{0.0, ins, outs});
    return contact_;
  }
  ContactFromFootHeight& plugin() { return *plugin_; }

 private:
  std::unique_ptr<ContactFromFootHeight> plugin_;
  std::vector<double> foot_pos_;
  std::vector<double> contact_;
};

// One foot's output after each height of `heights` (NaN compared as NaN).
void expect_trace(Trace& trace, const std::vector<double>& heights, const std::vector<double>& expected) {
  ASSERT_EQ(heights.size(), expected.size());
  for (std::size_t k = 0; k < heights.size(); ++k) {
    const double got = trace.step({heights[k]})[0];
    if (std::isnan(expected[k])) {
      EXPECT_TRUE(std::isnan(got)) << "tick " << k << ", height " << heights[k] << ": got " << got;
    } else {
      EXPECT_EQ(got, expected[k]) << "tick " << k << ", height " << heights[k];
    }
  }
}

TEST(ContactFromFootHeight, HysteresisKeepsTheStateBetweenTouchdownAndLiftoff) {
  // Ground at z = 0.1: heights are z - 0.1. Touchdown below 0.02, liftoff above 0.05.
  Trace trace({{"ground_height_m", 0.1}, {"touchdown_height_m", 0.02}, {"liftoff_height_m", 0.05}}, 1);
  // Heights 0.2 (swing), 0.03 (band), 0.01 (touchdown), 0.03, 0.04 (band), 0.06 (liftoff), 0.04,
  // 0.03 (band), 0.01 (touchdown), 0.02, 0.05 (not above liftoff), 0.051 (liftoff).
  const std::vector<double> z{0.3, 0.13, 0.11, 0.13, 0.14, 0.16, 0.14, 0.13, 0.11, 0.12, 0.15, 0.151};
  const std::vector<double> c{0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0};
  expect_trace(trace, z, c);
}

TEST(ContactFromFootHeight, TheFirstFiniteHeightDecidesWithTheTouchdownHeight) {
  const Json params = {{"touchdown_height_m", 0.02}, {"liftoff_height_m", 0.05}};
  {
    Trace trace(params, 1);
    expect_trace(trace, {kNaN, 0.01, 0.04}, {kNaN, 1.0, 1.0});  // starts in contact, stays in the band
  }
  {
    Trace trace(params, 1);
    expect_trace(trace, {0.03, 0.04, 0.01}, {0.0, 0.0, 1.0});  // starts in swing from inside the band
  }
  {
    Trace trace(params, 1);
    expect_trace(trace, {0.01, 0.1}, {1.0, 0.0});
    trace.plugin().reset();  // undecided again
    expect_trace(trace, {0.03}, {0.0});
  }
}

TEST(ContactFromFootHeight, NaNGivesNaNAndDoesNotLatch) {
  Trace trace({{"touchdown_height_m", 0.02}, {"liftoff_height_m", 0.05}}, 1);
  const double inf = std::numeric_limits<double>::infinity();
  // In contact; NaN and Inf are unknown; the state holds, so 0.04 (in the band) is still contact.
  expect_trace(trace, {0.0, kNaN, inf, 0.04, 0.06, kNaN, 0.03, -inf, 0.01},
               {1.0, kNaN, kNaN, 1.0, 0.0, kNaN, 0.0, kNaN, 1.0});
}

TEST(ContactFromFootHeight, LiftoffZeroIsTheTouchdownHeight) {
  Trace trace({{"touchdown_height_m", 0.02}}, 1);
  // At exactly 0.02 neither rule fires (contact below, swing above): the state holds.
  expect_trace(trace, {0.1, 0.02, 0.019, 0.02, 0.021, 0.02}, {0.0, 0.0, 1.0, 1.0, 0.0, 0.0});
}

TEST(ContactFromFootHeight, EachOfFourFeetHasItsOwnState) {
  Trace trace({{"touchdown_height_m", 0.02}, {"liftoff_height_m", 0.05}}, 4);
  EXPECT_EQ(trace.plugin().foot_count(), 4u);
  EXPECT_EQ(trace.step({0.0, 0.1, 0.03, kNaN})[0], 1.0);
  const auto c1 = trace.step({0.04, 0.04, 0.01, 0.03});
  EXPECT_EQ(c1[0], 1.0);  // in the band: still contact
  EXPECT_EQ(c1[1], 0.0);  // in the band: still swing
  EXPECT_EQ(c1[2], 1.0);  // touched down
  EXPECT_EQ(c1[3], 0.0);  // first finite height, above touchdown: swing
  const auto c2 = trace.step({0.06, 0.01, kNaN, 0.0});
  EXPECT_EQ(c2[0], 0.0);
  EXPECT_EQ(c2[1], 1.0);
  EXPECT_TRUE(std::isnan(c2[2]));
  EXPECT_EQ(c2[3], 1.0);
}

TEST(ContactFromFootHeight, FootPosNotAMultipleOfThreeIsAConfigError) {
  ContactFromFootHeight::Params params;
  params.touchdown_height_m = 0.02;
  for (const std::size_t dim : {1u, 4u, 8u}) {
    try {
      (void)ContactFromFootHeight(params, StageContext(1e-3, "contact", {{"foot_pos", dim}}));
      ADD_FAILURE() << dim << " values were accepted";
    } catch (const ConfigError& e) {
      ASSERT_EQ(e.problems().size(), 1u);
      EXPECT_EQ(e.problems()[0].path, "/inputs/foot_pos");
      EXPECT_NE(e.problems()[0].message.find("carries " + std::to_string(dim) + " values"), std::string::npos)
          << e.what();
      EXPECT_NE(e.problems()[0].message.find("a multiple of 3"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(ContactFromFootHeight(params, StageContext(1e-3, "contact", {{"foot_pos", 12}})).foot_count(), 4u);
}

Json two_feet_config(const Json& foot_pos_wire) {
  return {{"sample_period_s", 0.001},
          {"inputs",
           {{"l_foot_pos", {{"columns", {"l/x", "l/y", "l/z"}}, {"unit", "m"}}},
            {"r_foot_pos", {{"columns", {"r/x", "r/y", "r/z"}}, {"unit", "m"}}}}},
          {"stages",
           {{{"name", "contact"},
             {"plugin", "contact_from_foot_height"},
             {"params", {{"touchdown_height_m", 0.02}}},
             {"inputs", {{"foot_pos", foot_pos_wire}}}}}}};
}

TEST(ContactFromFootHeight, AListWireStacksTheFeetInItsOrder) {
  Pipeline pipeline = Pipeline::build(two_feet_config(Json::array({"input.l_foot_pos", "input.r_foot_pos"})),
                                      robot_model_plugins::registry());
  const SignalRef contact = pipeline.signal("contact.contact");
  ASSERT_EQ(contact.dim, 2u);
  std::size_t left = 0, right = 0;
  for (std::size_t i = 0; i < pipeline.inputs().size(); ++i) {
    (pipeline.inputs()[i].name == "l_foot_pos" ? left : right) = i;
  }
  pipeline.reset();
  const auto l = pipeline.input_values(left);
  const auto r = pipeline.input_values(right);
  l[0] = 0.1, l[1] = 0.1, l[2] = 0.005;
  r[0] = -0.1, r[1] = -0.1, r[2] = 0.12;
  pipeline.step(0.0);
  EXPECT_EQ(pipeline.values(contact)[0], 1.0);
  EXPECT_EQ(pipeline.values(contact)[1], 0.0);
}

TEST(ContactFromFootHeight, AWireOfFourValuesIsAConfigErrorAtTheWire) {
  Json config = two_feet_config(Json::array({"input.l_foot_pos", "input.r_foot_pos"}));
  config["inputs"]["r_foot_pos"]["columns"].push_back("r/w");
  try {
    (void)Pipeline::build(config, robot_model_plugins::registry());
    ADD_FAILURE() << "7 values were accepted";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems()[0].path, "/stages/0/inputs/foot_pos");
    EXPECT_NE(e.problems()[0].message.find("carries 7 values"), std::string::npos) << e.what();
  }
}

TEST(ContactFromFootHeight, ParameterErrorsNameTheRule) {
  auto errors = [](const Json& raw) {
    Diagnostics diag;
    (void)load_params<ContactFromFootHeight::Params>(raw, "/stages/2/params", ContactFromFootHeight::name, diag);
    return diag.errors();
  };
  const auto below = errors({{"touchdown_height_m", 0.05}, {"liftoff_height_m", 0.02}});
  ASSERT_EQ(below.size(), 1u);
  EXPECT_EQ(below[0].path, "/stages/2/params/liftoff_height_m");
  EXPECT_EQ(below[0].message,
            " = 0.02 is below touchdown_height_m = 0.05; a foot lifts off at or above the height it touches down "
            "(0: the same height)");
  const auto missing = errors(Json::object());
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0].path, "/stages/2/params/touchdown_height_m");
  const auto zero = errors({{"touchdown_height_m", 0.0}});
  ASSERT_EQ(zero.size(), 1u);
  EXPECT_EQ(zero[0].path, "/stages/2/params/touchdown_height_m");
  EXPECT_TRUE(errors({{"touchdown_height_m", 0.05}, {"liftoff_height_m", 0.05}}).empty());
  EXPECT_TRUE(errors({{"touchdown_height_m", 0.05}, {"liftoff_height_m", 0.0}}).empty());
}

}  // namespace
}  // namespace ftsense::robot_model
