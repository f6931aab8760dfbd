// Robot-model plugins: the contract suite, forward kinematics against the analytic planar
// two-link arm, reversed walks, orientation round trips and the URDF configuration errors.

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "ftsense/biped/frames.hpp"
#include "ftsense/robot_model/robot_model_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace {

const std::string kFixtures = FTSENSE_ROBOT_MODEL_FIXTURES;

ftsense::Json arm_params() {
  return {{"urdf", kFixtures + "/planar_two_link.urdf"},
          {"joints", {"shoulder", "elbow"}},
          {"held_joints", {"wrist"}},
          {"base_link", "base"},
          {"imu_link", "imu"},
          {"foot_links", {"tip", "fore"}}};
}

}  // namespace

namespace ftsense::testing {

template <>
struct ContractSetup<robot_model::UrdfKinematics> {
  static Json params() { return arm_params(); }
  static std::size_t input_dim(std::string_view port) { return port == "joint_positions" ? 2 : 3; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "joint_positions") v[0] = 0.3, v[1] = -0.6;
    if (port == "base_pos") v[2] = 0.6;
  }
  static double sample_period_s() { return 0.01; }
};

using RobotModelPlugins = ::testing::Types<robot_model::UrdfKinematics>;
INSTANTIATE_TYPED_TEST_SUITE_P(UrdfModel, PluginContract, RobotModelPlugins);

}  // namespace ftsense::testing

namespace ftsense::robot_model {
namespace {

constexpr double kL1 = 0.5, kL2 = 0.3, kM0 = 2.0, kM1 = 1.0, kM2 = 0.5;

struct ArmOracle {
  Eigen::Vector3d tip, com;
};
// The planar arm in its base frame (base at the origin, joints about z).
ArmOracle oracle(double q1, double q2) {
  const Eigen::Vector3d elbow(kL1 * std::cos(q1), kL1 * std::sin(q1), 0.0);
  const Eigen::Vector3d along(std::cos(q1 + q2), std::sin(q1 + q2), 0.0);
  const Eigen::Vector3d c1 = 0.5 * elbow;
  const Eigen::Vector3d c2 = elbow + 0.5 * kL2 * along;
  return {elbow + kL2 * along, (kM1 * c1 + kM2 * c2) / (kM0 + kM1 + kM2)};
}

KinematicTree arm_tree() { return KinematicTree::from_urdf_file(kFixtures + "/planar_two_link.urdf"); }

TEST(KinematicTree, ReadsMassesJointsAndLinks) {
  const KinematicTree tree = arm_tree();
  EXPECT_DOUBLE_EQ(tree.total_mass_kg(), kM0 + kM1 + kM2);
  EXPECT_EQ(tree.links().size(), 6u);
  EXPECT_EQ(tree.movable_joint_names(), (std::vector<std::string>{"elbow", "shoulder", "wrist"}));
  const auto path = tree.path_joints(*tree.find_link("tip"), *tree.find_link("base"));
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(tree.joints()[path.front()].name, "tip_fixed");
  EXPECT_EQ(tree.joints()[path.back()].name, "shoulder");
}

TEST(ForwardKinematics, MatchesThePlanarArmOracleUnderARandomBasePose) {
  const KinematicTree tree = arm_tree();
  std::vector<std::optional<std::size_t>> sources(tree.joints().size());
  sources[*tree.find_joint("shoulder")] = 0;
  sources[*tree.find_joint("elbow")] = 1;
  sources[*tree.find_joint("wrist")] = std::nullopt;
  ForwardKinematics fk(tree, *tree.find_link("base"), sources, {*tree.find_link("tip")});
  std::mt19937 rng(7);  // fixed seed
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  for (int trial = 0; trial < 200; ++trial) {
    const double q[2] = {angle(rng), angle(rng)};
    const RigidPose world_base{biped::rotation_from_rpy(angle(rng), 0.4 * angle(rng), angle(rng)),
                               Eigen::Vector3d(angle(rng), angle(rng), angle(rng))};
    fk.compute(world_base, q);
    const ArmOracle expected = oracle(q[0], q[1]);
    const Eigen::Vector3d tip = world_base.rotation * expected.tip + world_base.translation;
    const Eigen::Vector3d com = world_base.rotation * expected.com + world_base.translation;
    EXPECT_LT((fk.frame_pose(0).translation - tip).norm(), 1e-12) << "trial " << trial;
    EXPECT_LT((fk.com_world() - com).norm(), 1e-12) << "trial " << trial;
  }
}

TEST(ForwardKinematics, WalksAgainstJointsFromABaseThatIsNotTheRoot) {
  // Put the tip where the forward walk said it is; walking back must find the base at identity.
  const KinematicTree tree = arm_tree();
  std::vector<std::optional<std::size_t>> sources(tree.joints().size());
  sources[*tree.find_joint("shoulder")] = 0;
  sources[*tree.find_joint("elbow")] = 1;
  sources[*tree.find_joint("wrist")] = std::nullopt;
  const double q[2] = {0.7, -1.1};
  ForwardKinematics forward(tree, *tree.find_link("base"), sources, {*tree.find_link("tip")});
  forward.compute({}, q);
  ForwardKinematics backward(tree, *tree.find_link("tip"), sources, {*tree.find_link("base")});
  backward.compute(forward.frame_pose(0), q);
  EXPECT_LT(backward.frame_pose(0).translation.norm(), 1e-12);
  EXPECT_LT((backward.frame_pose(0).rotation - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_LT((backward.com_world() - oracle(q[0], q[1]).com).norm(), 1e-12);
}

TEST(Frames, RpyRoundTripsEveryRotationIncludingGimbalLock) {
  std::mt19937 rng(11);  // fixed seed
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  for (int trial = 0; trial < 500; ++trial) {
    const double pitch = trial % 50 == 0 ? std::numbers::pi / 2 * (trial % 100 == 0 ? 1 : -1) : 0.5 * angle(rng);
    const Eigen::Matrix3d r = biped::rotation_from_rpy(angle(rng), pitch, angle(rng));
    const Eigen::Vector3d rpy = biped::rpy_from_rotation(r);
    EXPECT_LT((biped::rotation_from_rpy(rpy[0], rpy[1], rpy[2]) - r).norm(), 1e-9) << "trial " << trial;
  }
}

// The plugin on the arm: world outputs, the IMU orientation R_WB R_B,IMU, the sole points'
// height and contact state, the URDF mass.
TEST(UrdfKinematics, OutputsTheArmsFramesComAndContact) {
  Json params = arm_params();
  params["foot_points_m"] = {{0.0, 0.0}, {0.1, 0.0}};
  params["contact_height_m"] = 0.05;
  Diagnostics diag;
  const auto p = load_params<UrdfKinematics::Params>(params, "/params", UrdfKinematics::name, diag);
  ASSERT_FALSE(diag.has_errors());
  UrdfKinematics plugin(p, StageContext(0.01, "fk", {{"joint_positions", 2}}));
  std::vector<std::vector<double>> in{{0.0, 0.0, 0.04}, {0.0, 0.0, 0.0}, {0.0, 0.0}};
  std::vector<std::vector<double>> out;
  for (const auto& o : plugin.ports().outputs()) out.emplace_back(o.dim, 0.0);
  std::vector<std::span<const double>> in_spans(in.begin(), in.end());
  std::vector<std::span<double>> out_spans(out.begin(), out.end());
  StepIO io{0.0, in_spans, out_spans};
  // Base turned -90 deg about x (roll): the arm's plane is the world x-z plane, z_base = y_world.
  in[1][0] = -std::numbers::pi / 2;
  // Shoulder +90 deg: upper along +y_base = -z_world (down); elbow -90 deg: fore along +x.
  const double q[2] = {std::numbers::pi / 2, -std::numbers::pi / 2};
  in[2] = {q[0], q[1]};
  plugin.step(io);
  const double tip_z = 0.04 - kL1;
  EXPECT_NEAR(out[UrdfKinematics::kFootPos][0], kL2, 1e-12);          // fore horizontal, +x
  EXPECT_NEAR(out[UrdfKinematics::kFootPos][2], tip_z, 1e-12);
  // The second foot, the fore link's origin at the elbow: kL1 below the base, x = 0.
  EXPECT_NEAR(out[UrdfKinematics::kFootPos][3], 0.0, 1e-12);
  EXPECT_NEAR(out[UrdfKinematics::kFootPos][5], tip_z, 1e-12);
  // The point (0.1, 0) of the tip frame is 0.1 m further along +x, same height.
  EXPECT_NEAR(out[UrdfKinematics::kFootHeight][0], tip_z, 1e-12);
  EXPECT_EQ(out[UrdfKinematics::kContact][0], 1.0);                       // below 0.05 m
  EXPECT_NEAR(out[UrdfKinematics::kMass][0], kM0 + kM1 + kM2, 1e-12);
  const Eigen::Vector3d com =
      biped::rotation_from_rpy(-std::numbers::pi / 2, 0, 0) * oracle(q[0], q[1]).com + Eigen::Vector3d(0, 0, 0.04);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(out[UrdfKinematics::kCom][static_cast<std::size_t>(i)], com[i], 1e-12);
  const Eigen::Matrix3d r_imu = biped::rotation_from_rpy(-std::numbers::pi / 2, 0, 0) *
                                biped::rotation_from_rpy(std::numbers::pi / 2, 0, std::numbers::pi / 2);
  const Eigen::Vector3d rpy(out[UrdfKinematics::kImuRpy][0], out[UrdfKinematics::kImuRpy][1],
                            out[UrdfKinematics::kImuRpy][2]);
  EXPECT_LT((biped::rotation_from_rpy(rpy[0], rpy[1], rpy[2]) - r_imu).norm(), 1e-12);
  // Lift the base: the tip leaves the ground.
  in[0][2] = 1.0;
  plugin.step(io);
  EXPECT_EQ(out[UrdfKinematics::kContact][0], 0.0);
  // An unknown joint reading is not a pose.
  in[2][1] = std::numeric_limits<double>::quiet_NaN();
  plugin.step(io);
  EXPECT_TRUE(std::isnan(out[UrdfKinematics::kCom][0]));
}

TEST(UrdfKinematics, ResolvesARelativeUrdfAgainstTheConfigDirectory) {
  Json params = arm_params();
  params["urdf"] = "planar_two_link.urdf";
  Diagnostics diag;
  const auto p = load_params<UrdfKinematics::Params>(params, "/params", UrdfKinematics::name, diag);
  EXPECT_NO_THROW(UrdfKinematics(p, StageContext(0.01, "fk", {}, kFixtures)));
  EXPECT_THROW(UrdfKinematics(p, StageContext(0.01, "fk", {}, "/nonexistent")), ConfigError);
}

// Each bad configuration gives one ConfigError whose path and message say what and where.
struct BadUrdfCase {
  const char* what;
  const char* key;
  Json value;
  const char* path;
  const char* message;
};

TEST(UrdfKinematics, ReportsBadUrdfsAndNamesWithPathAndSuggestion) {
  const std::vector<BadUrdfCase> cases{
      {"missing file", "urdf", kFixtures + "/nope.urdf", "/params/urdf", "no such file"},
      {"unparsable", "urdf", kFixtures + "/broken.urdf", "/params/urdf", "not a valid URDF"},
      {"not xml", "urdf", kFixtures + "/../test_robot_model.cpp", "/params/urdf", "not a valid URDF"},
      {"unknown link", "imu_link", "imu_", "/params/imu_link", "did you mean 'imu'?"},
      {"unknown joint", "joints", {"shoulder", "elbw"}, "/params/joints/1", "did you mean 'elbow'?"},
      {"fixed joint", "held_joints", {"tip_fixed", "wrist"}, "/params/held_joints/0", "is fixed"},
      {"twice", "held_joints", {"wrist", "elbow"}, "/params/held_joints/1", "listed twice"},
      {"unlisted", "joints", {"shoulder"}, "/params/joints", "elbow"},
  };
  for (const auto& c : cases) {
    Json params = arm_params();
    params[c.key] = c.value;
    Diagnostics diag;
    const auto p = load_params<UrdfKinematics::Params>(params, "/params", UrdfKinematics::name, diag);
    ASSERT_FALSE(diag.has_errors()) << c.what;
    try {
      UrdfKinematics plugin(p, StageContext(0.01, "fk"));
      ADD_FAILURE() << c.what << ": no error";
    } catch (const ConfigError& e) {
      ASSERT_EQ(e.problems().size(), 1u) << c.what << ": " << e.what();
      EXPECT_EQ(e.problems()[0].path, c.path) << c.what;
      EXPECT_NE(e.problems()[0].message.find(c.message), std::string::npos) << c.what << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace ftsense::robot_model
