// FreeBodyAccelerometer: the specific force of the motion MuJoCo integrates, checked against the
// second difference of the site's position, exact values for a body at rest, in free fall and
// spinning, and against MuJoCo's own accelerometer where the implicit joint damping makes them part.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ftsense/sim/free_body_accelerometer.hpp"
#include "ftsense/sim/mujoco_model.hpp"

using namespace ftsense::sim;

namespace {

// A 10 kg free box with a site 0.2 m above its origin, optionally a 2 kg arm on a hinge with the
// given damping (the implicit damping of the Euler step acts there). No contacts.
MjModelPtr body_model(double gravity, double hinge_damping, bool arm) {
  std::string xml = "<mujoco><option timestep='0.001' integrator='Euler' gravity='0 0 " + std::to_string(-gravity) +
                    "'/><worldbody><body name='trunk' pos='0 0 1'><freejoint/>"
                    "<geom type='box' size='0.1 0.1 0.1' mass='10' contype='0' conaffinity='0'/>"
                    "<site name='imu' pos='0 0 0.2'/>";
  if (arm)
    xml += "<body pos='0.1 0 0'><joint type='hinge' axis='0 1 0' damping='" + std::to_string(hinge_damping) +
           "'/><geom type='capsule' fromto='0 0 0 0.4 0 0' size='0.03' mass='2' contype='0' conaffinity='0'/>"
           "</body>";
  xml += "</body></worldbody><sensor><accelerometer name='acc' site='imu'/></sensor></mujoco>";
  return load_mjcf_string(xml);
}

struct Step {
  Eigen::Vector3d reading;           // FreeBodyAccelerometer, site frame
  Eigen::Vector3d mujoco_reading;    // MuJoCo's accelerometer sensor, site frame
  Eigen::Vector3d site_position;     // world, at the reading's time
  Eigen::Matrix3d site_orientation;  // world from site, at the reading's time
};

std::vector<Step> run(const mjModel* m, mjData* d, int ticks) {
  FreeBodyAccelerometer acc(m, require_id(m, mjOBJ_SITE, "imu"));
  const int sensor = m->sensor_adr[require_id(m, mjOBJ_SENSOR, "acc")];
  const int site = require_id(m, mjOBJ_SITE, "imu");
  std::vector<Step> steps;
  for (int k = 0; k < ticks; ++k) {
    acc.before_step(d);
    mj_step(m, d);  // derived quantities (site_xpos, sensordata) belong to the state before the step
    Step s;
    s.reading = acc.after_step(d);
    s.mujoco_reading = Eigen::Vector3d(d->sensordata[sensor], d->sensordata[sensor + 1], d->sensordata[sensor + 2]);
    s.site_position = Eigen::Vector3d(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s.site_orientation(i, j) = d->site_xmat[9 * site + 3 * i + j];
    steps.push_back(s);
  }
  return steps;
}

}  // namespace

TEST(FreeBodyAccelerometer, ReadsZeroInFreeFallWhateverItsOrientation) {
  MjModelPtr m = body_model(9.81, 0.0, false);
  MjDataPtr d(mj_makeData(m.get()));
  for (const Step& s : run(m.get(), d.get(), 50)) EXPECT_NEAR(s.reading.norm(), 0.0, 1e-9);

  // Tilted 90 degrees about x and falling: still nothing in any axis.
  MjDataPtr tilted(mj_makeData(m.get()));
  tilted->qpos[3] = std::sqrt(0.5);
  tilted->qpos[4] = std::sqrt(0.5);
  for (const Step& s : run(m.get(), tilted.get(), 50)) EXPECT_NEAR(s.reading.norm(), 0.0, 1e-9);
}

TEST(FreeBodyAccelerometer, ReadsTheCentripetalAccelerationOfASpinningBody) {
  // Zero gravity, spinning about the body's x axis at 3 rad/s: the site 0.2 m off the axis feels
  // omega^2 r = 1.8 m/s^2 towards the axis, -z in the body (site) frame, constant.
  MjModelPtr m = body_model(0.0, 0.0, false);
  MjDataPtr d(mj_makeData(m.get()));
  d->qvel[3] = 3.0;
  // The second difference of a point on a circle, omega T = 0.003 rad apart, is the centripetal
  // acceleration times sinc-like factors 1 + O((omega T)^2), here below 1e-5 relative.
  const std::vector<Step> steps = run(m.get(), d.get(), 200);
  for (std::size_t k = 1; k < steps.size(); ++k) {  // the first reading extrapolates its past
    EXPECT_NEAR(steps[k].reading.x(), 0.0, 1e-9);
    EXPECT_NEAR(steps[k].reading.y(), 0.0, 1.8 * 1e-5);
    EXPECT_NEAR(steps[k].reading.z(), -1.8, 1.8 * 1e-5);
  }
}

TEST(FreeBodyAccelerometer, EqualsTheSecondDifferenceOfTheSitePositionWhereMujocosSensorDoesNot) {
  // A swinging arm on a stiffly damped hinge (1000 N m s/rad, as the simulated robots' servos):
  // the Euler step treats the damping implicitly, so qacc (MuJoCo's accelerometer) is not the
  // motion that happens. The reading must be the site's true acceleration: the second difference
  // of its position, expressed in the site frame, minus gravity.
  const double g = 9.81;
  MjModelPtr m = body_model(g, 1000.0, true);
  MjDataPtr d(mj_makeData(m.get()));
  d->qvel[6] = 20.0;  // the arm swings, the trunk recoils
  const double T = m->opt.timestep;
  const std::vector<Step> steps = run(m.get(), d.get(), 60);
  double worst_ours = 0.0, worst_mujoco = 0.0;
  for (std::size_t k = 1; k + 1 < steps.size(); ++k) {
    const Eigen::Vector3d a =
        (steps[k + 1].site_position - 2.0 * steps[k].site_position + steps[k - 1].site_position) / (T * T);
    const Eigen::Vector3d expected = steps[k].site_orientation.transpose() * (a + Eigen::Vector3d(0.0, 0.0, g));
    worst_ours = std::max(worst_ours, (steps[k].reading - expected).norm());
    worst_mujoco = std::max(worst_mujoco, (steps[k].mujoco_reading - expected).norm());
  }
  std::printf("worst deviation from the site's second difference: %.3g m/s^2 (this model), %.3g m/s^2 "
              "(MuJoCo's accelerometer)\n", worst_ours, worst_mujoco);
  EXPECT_LT(worst_ours, 1e-6);
  EXPECT_GT(worst_mujoco, 1.0);  // the defect this model exists for
}

TEST(FreeBodyAccelerometer, RefusesASiteNotOnAFreeBody) {
  MjModelPtr m = load_mjcf_string(
      "<mujoco><worldbody><body><joint type='hinge'/><geom size='0.1'/><site name='imu'/></body></worldbody></mujoco>");
  EXPECT_THROW(FreeBodyAccelerometer(m.get(), require_id(m.get(), mjOBJ_SITE, "imu")), ModelError);
}
