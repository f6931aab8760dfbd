// Leg kinematics: IK/FK round trip and agreement of the analytic FK with MuJoCo's model.
#include <gtest/gtest.h>

#include <random>

#include "ftsense/sim/leg_kinematics.hpp"
#include "ftsense/sim/mujoco_model.hpp"
#include "ftsense/sim/robot_model.hpp"

using namespace ftsense::sim;

namespace {
constexpr std::uint64_t kKinematicsSeed = 20240611;

LegAngles random_angles(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Within the reachable, non-singular set: knee bent 0.2..1.8 rad, other joints moderate.
  return {0.4 * u(rng), 0.3 * u(rng), 0.8 * u(rng), 1.0 + 0.8 * u(rng), 0.6 * u(rng), 0.3 * u(rng)};
}
}  // namespace

TEST(LegKinematics, RpyRoundTrip) {
  const Eigen::Matrix3d R = rpy_to_matrix(0.1, -0.2, 0.3);
  const Eigen::Vector3d rpy = matrix_to_rpy(R);
  EXPECT_NEAR(rpy[0], 0.1, 1e-12);
  EXPECT_NEAR(rpy[1], -0.2, 1e-12);
  EXPECT_NEAR(rpy[2], 0.3, 1e-12);
}

TEST(LegKinematics, InverseOfForwardRecoversAnglesAndPose) {
  std::printf("seed %llu\n", static_cast<unsigned long long>(kKinematicsSeed));
  std::mt19937_64 rng(kKinematicsSeed);
  const LegGeometry g;
  for (int i = 0; i < 2000; ++i) {
    Pose hip;
    hip.p = Eigen::Vector3d(0.1, -0.2, 0.6);
    hip.R = rpy_to_matrix(0.05, -0.03, 0.2);
    const LegAngles q = random_angles(rng);
    const Pose sole = leg_forward(g, hip, q);
    const LegIkResult ik = leg_inverse(g, hip, sole);
    ASSERT_TRUE(ik.reachable);
    for (std::size_t j = 0; j < 6; ++j) ASSERT_NEAR(ik.q[j], q[j], 1e-9) << "joint " << j << " case " << i;
    const Pose back = leg_forward(g, hip, ik.q);
    ASSERT_LT((back.p - sole.p).norm(), 1e-12);
    ASSERT_LT((back.R - sole.R).norm(), 1e-12);
  }
}

TEST(LegKinematics, UnreachableTargetIsFlaggedAndClamped) {
  const LegGeometry g;
  Pose hip;
  hip.p = Eigen::Vector3d(0, 0, 1.0);
  Pose sole;  // 1 m below the hip: beyond A + B + h_s
  const LegIkResult ik = leg_inverse(g, hip, sole);
  EXPECT_FALSE(ik.reachable);
  EXPECT_NEAR(ik.q[3], 0.0, 1e-3);  // straight knee
}

TEST(LegKinematics, ForwardMatchesMujocoModel) {
  const RobotParams rp;
  MjModelPtr m = load_mjcf_string(suralp_mjcf(rp));
  MjDataPtr d(mj_makeData(m.get()));
  const LegGeometry g{rp.upper_leg_m, rp.lower_leg_m, rp.sole_ankle_m};
  std::mt19937_64 rng(kKinematicsSeed + 1);
  const char* joints[2][6] = {
      {"l_hip_yaw", "l_hip_roll", "l_hip_pitch", "l_knee", "l_ankle_pitch", "l_ankle_roll"},
      {"r_hip_yaw", "r_hip_roll", "r_hip_pitch", "r_knee", "r_ankle_pitch", "r_ankle_roll"}};
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d base(0.3, 0.1, 0.7);
    const Eigen::Quaterniond qb(rpy_to_matrix(0.02 * i / 50.0, -0.05, 0.3));
    d->qpos[0] = base.x();
    d->qpos[1] = base.y();
    d->qpos[2] = base.z();
    d->qpos[3] = qb.w();
    d->qpos[4] = qb.x();
    d->qpos[5] = qb.y();
    d->qpos[6] = qb.z();
    std::array<LegAngles, 2> q{random_angles(rng), random_angles(rng)};
    for (int leg = 0; leg < 2; ++leg)
      for (int j = 0; j < 6; ++j)
        d->qpos[m->jnt_qposadr[require_id(m.get(), mjOBJ_JOINT, joints[leg][j])]] = q[leg][j];
    mj_kinematics(m.get(), d.get());
    for (int leg = 0; leg < 2; ++leg) {
      Pose hip;
      hip.R = qb.toRotationMatrix();
      hip.p = base + hip.R * Eigen::Vector3d(0, leg == 0 ? rp.hip_half_width_m : -rp.hip_half_width_m, 0);
      const Pose sole = leg_forward(g, hip, q[leg]);
      const int site = require_id(m.get(), mjOBJ_SITE, leg == 0 ? "l_sole" : "r_sole");
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(sole.p[k], d->site_xpos[3 * site + k], 1e-12);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sole.R(r, c), d->site_xmat[9 * site + 3 * r + c], 1e-12);
    }
  }
}
