// The generated MJCF: Table I geometry and mass, joints, pads, sensors.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "ftsense/sim/mujoco_model.hpp"
#include "ftsense/sim/robot_model.hpp"

using namespace ftsense::sim;

TEST(RobotModel, CompilesWithTableIMassAndTwelveJoints) {
  const RobotParams rp;
  MjModelPtr m = load_mjcf_string(suralp_mjcf(rp));
  double mass = 0.0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  EXPECT_NEAR(mass, 114.0, 1e-9);
  EXPECT_EQ(m->njnt, 13);  // free joint + 12 hinges
  EXPECT_EQ(m->nu, 12);
  EXPECT_DOUBLE_EQ(m->opt.timestep, 0.001);
  for (std::size_t j = 0; j < kJointNames.size(); ++j) {
    const std::string name(kJointNames[j]);
    const int id = require_id(m.get(), mjOBJ_JOINT, name.c_str());
    EXPECT_EQ(m->jnt_type[id], mjJNT_HINGE) << name;
    EXPECT_GE(require_id(m.get(), mjOBJ_ACTUATOR, name.c_str()), 0);
  }
  const double legs = 2.0 * (rp.hip_yaw_link_kg + rp.hip_roll_link_kg + rp.thigh_kg + rp.shank_kg +
                             rp.ankle_link_kg + rp.foot_kg + 4 * rp.pad_kg);
  EXPECT_NEAR(legs / 114.0, 0.28, 0.01);  // legs about 28 % of the mass
}

TEST(RobotModel, LegSegmentLengthsMatchTableI) {
  MjModelPtr m = load_mjcf_string(suralp_mjcf());
  const int shank = require_id(m.get(), mjOBJ_BODY, "l_shank");
  const int ankle = require_id(m.get(), mjOBJ_BODY, "l_ankle_link");
  const int sole = require_id(m.get(), mjOBJ_SITE, "l_sole");
  EXPECT_NEAR(m->body_pos[3 * shank + 2], -0.280, 1e-12);
  EXPECT_NEAR(m->body_pos[3 * ankle + 2], -0.270, 1e-12);
  EXPECT_NEAR(m->site_pos[3 * sole + 2], -0.124, 1e-12);
}

TEST(RobotModel, PadsSitOnSoleCornersAndOnlyTheyCollide) {
  const RobotParams rp;
  MjModelPtr m = load_mjcf_string(suralp_mjcf(rp));
  const double expect[4][2] = {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}};
  int colliding = 0;
  for (int g = 0; g < m->ngeom; ++g)
    if (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0) ++colliding;
  EXPECT_EQ(colliding, 9);  // 8 pads + floor
  for (const char* side : {"l", "r"}) {
    for (int p = 0; p < 4; ++p) {
      const std::string name = std::string(side) + "_pad" + std::to_string(p + 1);
      const int g = require_id(m.get(), mjOBJ_GEOM, name.c_str());
      EXPECT_EQ(m->geom_type[g], mjGEOM_SPHERE);
      EXPECT_NEAR(m->geom_pos[3 * g], expect[p][0], 1e-12) << name;
      EXPECT_NEAR(m->geom_pos[3 * g + 1], expect[p][1], 1e-12) << name;
      // lowest point on the sole plane
      EXPECT_NEAR(m->geom_pos[3 * g + 2] - m->geom_size[3 * g], -rp.sole_ankle_m, 1e-12) << name;
      const auto xy = pad_position(rp, p);
      EXPECT_DOUBLE_EQ(xy[0], expect[p][0]);
      EXPECT_DOUBLE_EQ(xy[1], expect[p][1]);
    }
  }
}

TEST(RobotModel, HasImuSensors) {
  MjModelPtr m = load_mjcf_string(suralp_mjcf());
  EXPECT_EQ(m->sensor_dim[require_id(m.get(), mjOBJ_SENSOR, "imu_acc")], 3);
  EXPECT_EQ(m->sensor_dim[require_id(m.get(), mjOBJ_SENSOR, "imu_gyro")], 3);
}

TEST(RobotModel, BadMjcfThrowsModelError) {
  EXPECT_THROW((void)load_mjcf_string("<mujoco><worldbody><body></mujoco>"), ModelError);
}

TEST(RobotModel, PadContactForceEqualsTouchSensorAndWeightWhenStanding) {
  // Straight legs, pads exactly on the floor, joints held at zero by the servos.
  const RobotParams rp;
  MjModelPtr m = load_mjcf_string(suralp_mjcf(rp));
  MjDataPtr d(mj_makeData(m.get()));
  d->qpos[2] = rp.upper_leg_m + rp.lower_leg_m + rp.sole_ankle_m;
  d->qpos[3] = 1.0;
  int pad_geom[8], touch_adr[8];
  for (int i = 0; i < 8; ++i) {
    const std::string name = std::string(i < 4 ? "l" : "r") + "_pad" + std::to_string(i % 4 + 1);
    pad_geom[i] = require_id(m.get(), mjOBJ_GEOM, name.c_str());
    touch_adr[i] = m->sensor_adr[require_id(m.get(), mjOBJ_SENSOR, (name + "_touch").c_str())];
  }
  double mass = 0.0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  const double mg = mass * rp.gravity_m_s2;
  double min_dist = 0.0;
  for (int k = 0; k < 1000; ++k) {
    for (int j = 0; j < m->nu; ++j)
      d->ctrl[j] = -rp.servo_kp_Nm_rad * d->qpos[m->jnt_qposadr[m->actuator_trnid[2 * j]]];
    mj_step(m.get(), d.get());
    if (k < 300) continue;  // settle
    double fn[8] = {};
    int per_pad[8] = {};
    for (int c = 0; c < d->ncon; ++c) {
      const mjContact& con = d->contact[c];
      for (int i = 0; i < 8; ++i)
        if (con.geom1 == pad_geom[i] || con.geom2 == pad_geom[i]) {
          mjtNum f6[6];
          mj_contactForce(m.get(), d.get(), c, f6);
          fn[i] += f6[0];
          ++per_pad[i];
          min_dist = std::min(min_dist, static_cast<double>(con.dist));
        }
    }
    double sum = 0.0;
    for (int i = 0; i < 8; ++i) {
      ASSERT_EQ(per_pad[i], 1) << "pad " << i << " tick " << k;  // exactly one contact per pad
      ASSERT_NEAR(fn[i], d->sensordata[touch_adr[i]], 1e-6 * mg);
      sum += fn[i];
    }
    ASSERT_NEAR(sum / mg, 1.0, 1e-3) << "tick " << k;
  }
  std::printf("pad penetration %.2f mm\n", -1e3 * min_dist);
  EXPECT_LT(-min_dist, 1e-3);  // stiff enough: under 1 mm for 114 kg
}
