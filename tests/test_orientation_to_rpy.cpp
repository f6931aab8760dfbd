// orientation_to_rpy: the contract suite, exact angles, round trips through the convention of
// frames.hpp (rotation_from_rpy) for every input layout, and inputs that are no orientation.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "ftsense/biped/frames.hpp"
#include "ftsense/generic/orientation_to_rpy.hpp"
#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {

template <>
struct ContractSetup<generic::OrientationToRpy> {
  static Json params() { return Json::object(); }  // quaternion_xyzw
  static std::size_t input_dim(std::string_view) { return 4; }
  static void nominal_input(std::string_view, std::span<double> v) {
    // 30 degrees about the axis (1, 2, 2) / 3.
    const double s = std::sin(std::numbers::pi / 12.0) / 3.0;
    v[0] = s, v[1] = 2.0 * s, v[2] = 2.0 * s, v[3] = std::cos(std::numbers::pi / 12.0);
  }
  static double sample_period_s() { return 1e-3; }
  // The quaternion walks by at most 0.01 per component and tick: its norm stays near 1.
  static double random_step() { return 0.01; }
  // A quaternion of norm 2e-300 is no orientation: NaN, not a made-up angle.
  static bool tiny_inputs_have_no_value() { return true; }
};

INSTANTIATE_TYPED_TEST_SUITE_P(Orientation, PluginContract, ::testing::Types<generic::OrientationToRpy>);

}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::OrientationToRpy;
using From = OrientationToRpy::From;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kHalfPi = std::numbers::pi / 2.0;

std::array<double, 3> rpy_of(From from, std::vector<double> orientation) {
  std::array<double, 3> rpy{};
  OrientationToRpy::to_rpy(from, orientation, rpy);
  return rpy;
}

// The layouts of R (and of its quaternion) the plugin reads.
std::vector<double> as_input(From from, const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  switch (from) {
    case From::quaternion_xyzw: return {q.x(), q.y(), q.z(), q.w()};
    case From::quaternion_wxyz: return {q.w(), q.x(), q.y(), q.z()};
    case From::rotation_matrix_row_major:
      return {r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)};
    case From::rotation_matrix_column_major:
      return {r(0, 0), r(1, 0), r(2, 0), r(0, 1), r(1, 1), r(2, 1), r(0, 2), r(1, 2), r(2, 2)};
  }
  return {};
}

constexpr std::array kAllLayouts = {From::quaternion_xyzw, From::quaternion_wxyz, From::rotation_matrix_row_major,
                                    From::rotation_matrix_column_major};

const char* layout_name(From from) {
  switch (from) {
    case From::quaternion_xyzw: return "quaternion_xyzw";
    case From::quaternion_wxyz: return "quaternion_wxyz";
    case From::rotation_matrix_row_major: return "rotation_matrix_row_major";
    case From::rotation_matrix_column_major: return "rotation_matrix_column_major";
  }
  return "";
}

void expect_rpy(const std::array<double, 3>& got, double roll, double pitch, double yaw, double tolerance) {
  EXPECT_NEAR(got[0], roll, tolerance);
  EXPECT_NEAR(got[1], pitch, tolerance);
  EXPECT_NEAR(got[2], yaw, tolerance);
}

TEST(OrientationToRpy, IdentityIsZeroInEveryLayout) {
  for (const From from : kAllLayouts) {
    SCOPED_TRACE(layout_name(from));
    const auto rpy = rpy_of(from, as_input(from, Eigen::Matrix3d::Identity()));
    EXPECT_EQ(rpy, (std::array<double, 3>{0.0, 0.0, 0.0}));
    for (const double angle : rpy) EXPECT_FALSE(std::signbit(angle)) << "a log would print -0";
  }
}

TEST(OrientationToRpy, RightAnglesAboutEachAxisFromMatrices) {
  // Exact matrices: the angles come out to the last bit. Ry(+-90 deg) is gimbal lock, where yaw
  // is 0 by convention and all of the rotation is in pitch.
  const std::array<double, 9> rx{1, 0, 0, 0, 0, -1, 0, 1, 0};
  const std::array<double, 9> ry{0, 0, 1, 0, 1, 0, -1, 0, 0};
  const std::array<double, 9> rz{0, -1, 0, 1, 0, 0, 0, 0, 1};
  const std::array<double, 9> ry_negative{0, 0, -1, 0, 1, 0, 1, 0, 0};
  auto row_major = [](const std::array<double, 9>& r) { return rpy_of(From::rotation_matrix_row_major, {r.begin(), r.end()}); };
  EXPECT_EQ(row_major(rx), (std::array<double, 3>{kHalfPi, 0.0, 0.0}));
  EXPECT_EQ(row_major(ry), (std::array<double, 3>{0.0, kHalfPi, 0.0}));
  EXPECT_EQ(row_major(rz), (std::array<double, 3>{0.0, 0.0, kHalfPi}));
  EXPECT_EQ(row_major(ry_negative), (std::array<double, 3>{0.0, -kHalfPi, 0.0}));
  // Column-major reads the transpose: the entries of Rx(90 deg) by rows, read by columns, are
  // Rx(-90 deg); Rx(90 deg) by columns is (1 0 0, 0 0 1, 0 -1 0).
  EXPECT_EQ(rpy_of(From::rotation_matrix_column_major, {rx.begin(), rx.end()}),
            (std::array<double, 3>{-kHalfPi, 0.0, 0.0}));
  EXPECT_EQ(rpy_of(From::rotation_matrix_column_major, {1, 0, 0, 0, 0, 1, 0, -1, 0}),
            (std::array<double, 3>{kHalfPi, 0.0, 0.0}));
}

TEST(OrientationToRpy, RightAnglesAboutEachAxisFromQuaternions) {
  // q = (sin 45 deg) axis + cos 45 deg; its entries are rounded, so the angles are within 1e-15.
  const double s = std::sqrt(0.5);
  expect_rpy(rpy_of(From::quaternion_xyzw, {s, 0, 0, s}), kHalfPi, 0.0, 0.0, 1e-15);
  expect_rpy(rpy_of(From::quaternion_xyzw, {0, s, 0, s}), 0.0, kHalfPi, 0.0, 1e-15);
  expect_rpy(rpy_of(From::quaternion_xyzw, {0, 0, s, s}), 0.0, 0.0, kHalfPi, 1e-15);
  expect_rpy(rpy_of(From::quaternion_wxyz, {s, s, 0, 0}), kHalfPi, 0.0, 0.0, 1e-15);
  expect_rpy(rpy_of(From::quaternion_wxyz, {s, 0, s, 0}), 0.0, kHalfPi, 0.0, 1e-15);
  expect_rpy(rpy_of(From::quaternion_wxyz, {s, 0, 0, s}), 0.0, 0.0, kHalfPi, 1e-15);
  // 180 degrees about z: q = k.
  expect_rpy(rpy_of(From::quaternion_xyzw, {0, 0, 1, 0}), 0.0, 0.0, std::numbers::pi, 1e-15);
}

TEST(OrientationToRpy, RandomRotationsRoundTripThroughEveryLayout) {
  constexpr std::uint64_t kSeed = 20260314;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> pitch_angle(-kHalfPi, kHalfPi);
  std::vector<std::array<double, 3>> cases;
  for (int k = 0; k < 2000; ++k) cases.push_back({angle(rng), pitch_angle(rng), angle(rng)});
  // At and next to gimbal lock, where roll and yaw are tied.
  for (const double pitch : {kHalfPi, -kHalfPi, kHalfPi - 1e-13, kHalfPi - 1e-9, -kHalfPi + 1e-7, kHalfPi - 1e-4}) {
    for (int k = 0; k < 20; ++k) cases.push_back({angle(rng), pitch, angle(rng)});
  }
  for (const From from : kAllLayouts) {
    SCOPED_TRACE(layout_name(from));
    for (const auto& original : cases) {
      const Eigen::Matrix3d r = biped::rotation_from_rpy(original[0], original[1], original[2]);
      const auto rpy = rpy_of(from, as_input(from, r));
      const Eigen::Matrix3d back = biped::rotation_from_rpy(rpy[0], rpy[1], rpy[2]);
      ASSERT_LE((back - r).cwiseAbs().maxCoeff(), 1e-12)
          << "rpy " << original[0] << " " << original[1] << " " << original[2];
      EXPECT_LE(std::abs(rpy[1]), kHalfPi);
      // Away from gimbal lock the angles themselves are unique.
      if (std::abs(original[1]) < kHalfPi - 1e-3) {
        ASSERT_NEAR(rpy[0], original[0], 1e-9);
        ASSERT_NEAR(rpy[1], original[1], 1e-9);
        ASSERT_NEAR(rpy[2], original[2], 1e-9);
      }
    }
  }
}

TEST(OrientationToRpy, QuaternionAndItsNegativeGiveTheSameAngles) {
  constexpr std::uint64_t kSeed = 77;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> component;
  for (int k = 0; k < 200; ++k) {
    std::vector<double> q{component(rng), component(rng), component(rng), component(rng)};
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& c : q) c /= norm;
    const std::vector<double> minus_q{-q[0], -q[1], -q[2], -q[3]};
    EXPECT_EQ(rpy_of(From::quaternion_xyzw, q), rpy_of(From::quaternion_xyzw, minus_q));
    EXPECT_EQ(rpy_of(From::quaternion_wxyz, q), rpy_of(From::quaternion_wxyz, minus_q));
  }
}

TEST(OrientationToRpy, QuaternionsAreNormalisedWithinHalfToTwice) {
  const double s = std::sqrt(0.5);
  for (const double scale : {0.5, 0.6, 1.9, 2.0}) {
    SCOPED_TRACE(scale);
    expect_rpy(rpy_of(From::quaternion_xyzw, {scale * s, 0, 0, scale * s}), kHalfPi, 0.0, 0.0, 1e-15);
  }
}

void expect_no_value(const std::array<double, 3>& rpy) {
  EXPECT_TRUE(std::isnan(rpy[0]) && std::isnan(rpy[1]) && std::isnan(rpy[2]))
      << rpy[0] << " " << rpy[1] << " " << rpy[2];
}

TEST(OrientationToRpy, InputsThatAreNoOrientationGiveNaN) {
  const double s = std::sqrt(0.5);
  const double inf = std::numeric_limits<double>::infinity();
  // Quaternions: norm outside [0.5, 2] (a wrong column), not finite, all zero.
  expect_no_value(rpy_of(From::quaternion_xyzw, {0.49 * s, 0, 0, 0.49 * s}));
  expect_no_value(rpy_of(From::quaternion_xyzw, {2.01 * s, 0, 0, 2.01 * s}));
  expect_no_value(rpy_of(From::quaternion_xyzw, {0, 0, 0, 0}));
  expect_no_value(rpy_of(From::quaternion_xyzw, {0, 0, kNaN, 1}));
  expect_no_value(rpy_of(From::quaternion_wxyz, {inf, 0, 0, 0}));
  // Matrices: scaled by 1.01 (R^T R = 1.0201 I), a reflection (det -1), a NaN entry, a shear.
  expect_no_value(rpy_of(From::rotation_matrix_row_major, {1.01, 0, 0, 0, 1.01, 0, 0, 0, 1.01}));
  expect_no_value(rpy_of(From::rotation_matrix_row_major, {1, 0, 0, 0, 1, 0, 0, 0, -1}));
  expect_no_value(rpy_of(From::rotation_matrix_column_major, {1, 0, 0, 0, kNaN, 0, 0, 0, 1}));
  expect_no_value(rpy_of(From::rotation_matrix_column_major, {1, 0, 0, 0.01, 1, 0, 0, 0, 1}));
  // Within the tolerance (max |R^T R - I| = 4e-4 <= 1e-3) a matrix is read as it is.
  const auto nearly = rpy_of(From::rotation_matrix_row_major, {1, 0, 0, 0, 1, 0, 0, 0, 1.0002});
  EXPECT_EQ(nearly, (std::array<double, 3>{0.0, 0.0, 0.0}));
}

TEST(OrientationToRpy, PortsFollowTheLayout) {
  for (const From from : kAllLayouts) {
    const OrientationToRpy plugin({from}, StageContext(1e-3, "o"));
    const bool quaternion = from == From::quaternion_xyzw || from == From::quaternion_wxyz;
    EXPECT_EQ(plugin.ports().inputs().at(0).dim, quaternion ? 4u : 9u) << layout_name(from);
    EXPECT_EQ(plugin.ports().outputs().at(0).unit, "rad");
  }
}

TEST(OrientationToRpy, ARotationMatrixWiredToAQuaternionLayoutIsAConfigError) {
  const Json config = Json::parse(R"({
    "sample_period_s": 0.001,
    "inputs": {"base_rotation": {"columns": ["r00", "r01", "r02", "r10", "r11", "r12", "r20", "r21", "r22"], "unit": "1"}},
    "stages": [{"name": "base", "plugin": "orientation_to_rpy", "params": {"from": "quaternion_xyzw"},
                "inputs": {"orientation": "input.base_rotation"}}]
  })");
  try {
    (void)Pipeline::build(config, reference_plugins::registry());
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/stages/0/inputs/orientation"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("takes 4"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ftsense
