// attitude_from_imu: the contract suite, the start from gravity, the gyro's exact integration,
// the tilt correction's time constant, and the accelerometer ignored through motion.

#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "ftsense/biped/frames.hpp"
#include "ftsense/generic/attitude_from_imu.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {

template <>
struct ContractSetup<generic::AttitudeFromImu> {
  static Json params() { return Json::object(); }
  static std::size_t input_dim(std::string_view) { return 3; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    std::fill(v.begin(), v.end(), 0.0);
    if (port == "imu_acc") v[0] = 1.0, v[2] = 9.75;  // at rest, tilted a little
    if (port == "gyro") v[2] = 0.2;
  }
  static double sample_period_s() { return 1e-3; }
  // A gyro that walks metres per second per tick has no physical meaning; 0.01 rad/s per tick.
  static double random_step() { return 0.01; }
  // An accelerometer reading 1e-300 m/s^2 is in free fall: it cannot tell the tilt to start from.
  static bool tiny_inputs_have_no_value() { return true; }
};

INSTANTIATE_TYPED_TEST_SUITE_P(Attitude, PluginContract, ::testing::Types<generic::AttitudeFromImu>);

}  // namespace ftsense::testing

namespace ftsense::generic {
namespace {

using testing::PluginHarness;
constexpr double kG = 9.806;

// The specific force an IMU at rest reads with attitude (roll, pitch, yaw): R^T (0, 0, g).
std::array<double, 3> at_rest(double roll, double pitch, double yaw) {
  const Eigen::Vector3d f = biped::rotation_from_rpy(std::array<double, 3>{roll, pitch, yaw}).transpose() *
                            Eigen::Vector3d(0.0, 0.0, kG);
  return {f.x(), f.y(), f.z()};
}

void feed(PluginHarness<AttitudeFromImu>& h, std::array<double, 3> gyro, std::array<double, 3> acc, double t) {
  h.inputs()[AttitudeFromImu::kGyro] = {gyro[0], gyro[1], gyro[2]};
  h.inputs()[AttitudeFromImu::kImuAcc] = {acc[0], acc[1], acc[2]};
  h.step(t);
}

TEST(AttitudeFromImu, StartsFromGravityAndHoldsAtRest) {
  PluginHarness<AttitudeFromImu> h;
  h.plugin().reset();
  // Not ready before a finite specific force that reads gravity alone (not a free fall).
  feed(h, {0.0, 0.0, 0.0}, {std::nan(""), 0.0, kG}, 0.0);
  EXPECT_TRUE(std::isnan(h.outputs()[0][0]));
  feed(h, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.5 * kG}, 0.0);
  EXPECT_TRUE(std::isnan(h.outputs()[0][0]));
  for (int k = 1; k <= 1000; ++k) feed(h, {0.0, 0.0, 0.0}, at_rest(0.2, -0.3, 0.7), k * 1e-3);
  // Roll and pitch from gravity at once; yaw is initial_yaw_rad (0): gravity does not tell it.
  EXPECT_NEAR(h.outputs()[0][0], 0.2, 1e-12);
  EXPECT_NEAR(h.outputs()[0][1], -0.3, 1e-12);
  EXPECT_NEAR(h.outputs()[0][2], 0.0, 1e-12);
}

TEST(AttitudeFromImu, IntegratesAHeldRateExactly) {
  // Level, turning at 0.5 rad/s about the vertical for 2 s: yaw = 1 rad, roll = pitch = 0.
  PluginHarness<AttitudeFromImu> h;
  h.plugin().reset();
  feed(h, {0.0, 0.0, 0.5}, at_rest(0.0, 0.0, 0.0), 0.0);  // the start tick does not integrate
  for (int k = 1; k <= 2000; ++k) feed(h, {0.0, 0.0, 0.5}, at_rest(0.0, 0.0, 0.0), k * 1e-3);
  EXPECT_NEAR(h.outputs()[0][2], 1.0, 1e-9);
  EXPECT_NEAR(h.outputs()[0][0], 0.0, 1e-12);
  EXPECT_NEAR(h.outputs()[0][1], 0.0, 1e-12);
}

TEST(AttitudeFromImu, ATiltErrorDecaysWithTheTimeConstant) {
  // Start level; the IMU is then at roll 0.1 rad with no rate measured (a gyro that missed the
  // tilt): the estimate follows gravity as 0.1 (1 - exp(-t / tau)), tau = 1 s.
  PluginHarness<AttitudeFromImu> h;
  h.plugin().reset();
  feed(h, {0.0, 0.0, 0.0}, at_rest(0.0, 0.0, 0.0), 0.0);
  for (int k = 1; k <= 1000; ++k) feed(h, {0.0, 0.0, 0.0}, at_rest(0.1, 0.0, 0.0), k * 1e-3);
  const double remaining = (0.1 - h.outputs()[0][0]) / 0.1;
  std::cout << "tilt error left after tau: " << remaining << " (exp(-1) = " << std::exp(-1.0) << ")\n";
  // sin(e) ~ e to 0.2 % at 0.1 rad, and one tick's Euler step is 0.05 % of tau.
  EXPECT_NEAR(remaining, std::exp(-1.0), 0.001);
  EXPECT_NEAR(h.outputs()[0][1], 0.0, 1e-12);
}

TEST(AttitudeFromImu, TheAccelerometerIsIgnoredThroughMotion) {
  // |f| = 2 g (a foot strike) and tilted: beyond accept_acc_fraction, so the level estimate stays.
  PluginHarness<AttitudeFromImu> h;
  h.plugin().reset();
  feed(h, {0.0, 0.0, 0.0}, at_rest(0.0, 0.0, 0.0), 0.0);
  const std::array<double, 3> strike{0.0, 2.0 * kG * std::sin(0.3), 2.0 * kG * std::cos(0.3)};
  for (int k = 1; k <= 500; ++k) feed(h, {0.0, 0.0, 0.0}, strike, k * 1e-3);
  EXPECT_EQ(h.outputs()[0][0], 0.0);
  EXPECT_EQ(h.outputs()[0][1], 0.0);
  // A non-finite gyro holds the attitude; a non-finite f leaves the gyro alone in charge.
  feed(h, {std::nan(""), 0.0, 0.0}, at_rest(0.0, 0.0, 0.0), 0.501);
  EXPECT_EQ(h.outputs()[0][2], 0.0);
  for (int k = 0; k < 1000; ++k) feed(h, {0.0, 0.0, 0.25}, {std::nan(""), 0.0, kG}, 0.502 + k * 1e-3);
  EXPECT_NEAR(h.outputs()[0][2], 0.25, 1e-9);
}

TEST(AttitudeFromImu, AnAbsurdRateDoesNotLatchANaN) {
  // 1e300 rad/s is finite but no gyro's (beyond half a turn per tick): the attitude holds.
  PluginHarness<AttitudeFromImu> h;
  h.plugin().reset();
  feed(h, {0.0, 0.0, 0.0}, at_rest(0.1, 0.0, 0.0), 0.0);
  feed(h, {1e300, 1e300, 0.0}, at_rest(0.1, 0.0, 0.0), 0.001);
  feed(h, {0.0, 0.0, 0.0}, at_rest(0.1, 0.0, 0.0), 0.002);
  EXPECT_NEAR(h.outputs()[0][0], 0.1, 1e-12);
  EXPECT_NEAR(h.outputs()[0][1], 0.0, 1e-12);
}

}  // namespace
}  // namespace ftsense::generic
