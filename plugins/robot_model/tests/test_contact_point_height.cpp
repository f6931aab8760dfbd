// contact_point_height: the contract suite; exact heights of a tilted sole's points and of a ball
// foot; the ground from the lowest point; NaN poses; the ports a point foot needs.

#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/robot_model/contact_point_height.hpp"
#include "ftsense/robot_model/robot_model_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {

template <>
struct ContractSetup<robot_model::ContactPointHeight> {
  static Json params() { return {{"points", {{0.1, 0.05}, {-0.1, -0.05}}}}; }
  static std::size_t input_dim(std::string_view) { return 6; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "foot_pos") v[1] = 0.1, v[4] = -0.1, v[5] = 0.05;  // right foot 5 cm up
  }
  static double sample_period_s() { return 1e-3; }
};

INSTANTIATE_TYPED_TEST_SUITE_P(PointHeight, PluginContract, ::testing::Types<robot_model::ContactPointHeight>);

}  // namespace ftsense::testing

namespace ftsense::robot_model {
namespace {

struct Heights {
  ContactPointHeight plugin;
  std::vector<std::vector<double>> ins, outs;
  Heights(const ContactPointHeight::Params& p, std::size_t feet)
      : plugin(p, StageContext(1e-3, "pads", {{"foot_pos", 3 * feet}, {"foot_rpy", 3 * feet}})) {
    for (const auto& port : plugin.ports().inputs()) ins.emplace_back(port.dim, 0.0);
    for (const auto& port : plugin.ports().outputs()) outs.emplace_back(port.dim, 0.0);
  }
  void step() {
    std::vector<std::span<const double>> in(ins.begin(), ins.end());
    std::vector<std::span<double>> out(outs.begin(), outs.end());
    plugin.step(StepIO{0.0, in, out});
  }
};

// A sole pitched toe-up by 0.1 rad about its origin 2 cm above the plane z = 0.01: the toe point
// (0.12, 0) rises by 0.12 sin 0.1, the heel point (-0.12, 0) sinks by as much.
TEST(ContactPointHeight, ASolesPointsFollowItsTiltAboveThePlane) {
  ContactPointHeight::Params p;
  p.points = {{0.12, 0.0}, {-0.12, 0.0}};
  p.ground_height_m = 0.01;
  Heights run(p, 1);
  ASSERT_EQ(run.ins.size(), 2u);
  run.ins[0] = {0.3, 0.1, 0.02};
  run.ins[1] = {0.0, -0.1, 0.0};  // pitch -0.1 rad about y lifts +x (R = Ry(-0.1))
  run.step();
  const double rise = 0.12 * std::sin(0.1);
  EXPECT_NEAR(run.outs[ContactPointHeight::kPointHeight][0], 0.01 + rise, 1e-15);
  EXPECT_NEAR(run.outs[ContactPointHeight::kPointHeight][1], 0.01 - rise, 1e-15);
  EXPECT_NEAR(run.outs[ContactPointHeight::kFootHeight][0], 0.01 - rise, 1e-15);
}

// Four ball feet of radius 2 cm (a quadruped): no orientation port; the lowest point of each is
// r below its centre; with ground_reference lowest_point the lowest foot is at 0 and a foot whose
// centre is 4 cm higher is 4 cm up, whatever the world height of the base estimate.
TEST(ContactPointHeight, BallFeetNeedNoOrientationAndTheLowestPointIsTheGround) {
  ContactPointHeight::Params p;
  p.foot_radius_m = 0.02;
  p.ground_reference = ContactPointHeight::Params::GroundReference::lowest_point;
  Heights run(p, 4);
  ASSERT_EQ(run.plugin.ports().inputs().size(), 1u) << "a point foot's height needs no orientation";
  ASSERT_EQ(run.outs[ContactPointHeight::kPointHeight].size(), 4u);
  const double base_drift = 0.37;  // the feet's world height is off by this
  run.ins[0] = {0.2, 0.1, base_drift + 0.02, 0.2, -0.1, base_drift + 0.06, -0.2, 0.1, base_drift + 0.021,
                -0.2, -0.1, base_drift + 0.02};
  run.step();
  const std::vector<double> expected{0.0, 0.04, 0.001, 0.0};
  for (std::size_t f = 0; f < 4; ++f) {
    EXPECT_NEAR(run.outs[ContactPointHeight::kPointHeight][f], expected[f], 1e-12) << "foot " << f;
    EXPECT_NEAR(run.outs[ContactPointHeight::kFootHeight][f], expected[f], 1e-12) << "foot " << f;
  }
  // On the plane z = 0 instead, the ball resting on it is at 0: its centre is r up.
  p.ground_reference = ContactPointHeight::Params::GroundReference::plane;
  Heights plane(p, 1);
  plane.ins[0] = {0.0, 0.0, 0.02};
  plane.step();
  EXPECT_EQ(plane.outs[ContactPointHeight::kFootHeight][0], 0.0);
}

// A foot with no pose has no height; with the ground from the lowest point, no foot has one.
TEST(ContactPointHeight, AnUnknownPoseIsNoHeight) {
  ContactPointHeight::Params p;
  Heights plane(p, 2);
  plane.ins[0] = {0.0, 0.1, 0.03, 0.0, -0.1, std::numeric_limits<double>::quiet_NaN()};
  plane.step();
  EXPECT_EQ(plane.outs[ContactPointHeight::kFootHeight][0], 0.03);
  EXPECT_TRUE(std::isnan(plane.outs[ContactPointHeight::kFootHeight][1]));
  p.ground_reference = ContactPointHeight::Params::GroundReference::lowest_point;
  Heights lowest(p, 2);
  lowest.ins[0] = plane.ins[0];
  lowest.step();
  for (double h : lowest.outs[ContactPointHeight::kPointHeight]) EXPECT_TRUE(std::isnan(h));
}

TEST(ContactPointHeight, FootPosNotInThreesIsAConfigError) {
  try {
    const ContactPointHeight plugin(ContactPointHeight::Params{}, StageContext(1e-3, "pads", {{"foot_pos", 4}}));
    FAIL() << "4 values accepted as feet";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems()[0].path, "/inputs/foot_pos");
    EXPECT_NE(e.problems()[0].message.find("multiple of 3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ftsense::robot_model
