// The quadruped's static crawl in MuJoCo: the crawl plan (CoM and feet) -> multibody CoM
// correction of the trunk position -> analytic 3-DOF leg IK -> joint position servos; sensors,
// faults and the log as for the biped (sim/README.md, "Quadruped").
#include <algorithm>
#include <cmath>
#include <ctime>
#include <locale>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "ftsense/sim/free_body_accelerometer.hpp"
#include "ftsense/sim/mujoco_model.hpp"
#include "ftsense/sim/quadruped_leg_kinematics.hpp"
#include "ftsense/sim/simulator.hpp"
#include "simulation_log.hpp"

namespace ftsense::sim {

namespace {

constexpr std::size_t kLegs = kQuadrupedLegCount;
constexpr std::size_t kJoints = kQuadrupedJointNames.size();

/// Trunk position and joint references that put the whole-body CoM (x, y) at the planned CoM with
/// the feet at the plan, trunk level at body_height_m.
struct QuadrupedController {
  const mjModel* m;
  mjData* dk;  // scratch data for the kinematic CoM
  QuadrupedLegGeometry g;
  std::array<Eigen::Vector3d, kLegs> hips{};
  double body_height;
  std::array<int, kJoints> qadr{};
  int trunk = 0;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  // trunk - CoM (x, y), warm-started

  struct Refs {
    Eigen::Vector3d trunk;
    std::array<double, kJoints> q;
    bool reachable;
  };

  Refs ik(const Eigen::Vector3d& trunk_pos, const CrawlSample& s) const {
    Refs r{trunk_pos, {}, true};
    for (std::size_t leg = 0; leg < kLegs; ++leg) {
      const auto res = quadruped_leg_inverse(g, s.foot[leg] - trunk_pos - hips[leg]);  // trunk level
      r.reachable = r.reachable && res.reachable;
      for (std::size_t j = 0; j < 3; ++j) r.q[3 * leg + j] = res.q[j];
    }
    return r;
  }

  Eigen::Vector3d com_of(const Refs& r) const {
    mju_zero(dk->qpos, m->nq);
    for (int i = 0; i < 3; ++i) dk->qpos[i] = r.trunk[i];
    dk->qpos[3] = 1.0;
    for (std::size_t j = 0; j < kJoints; ++j) dk->qpos[qadr[j]] = r.q[j];
    mj_kinematics(m, dk);
    mj_comPos(m, dk);
    return {dk->subtree_com[3 * trunk], dk->subtree_com[3 * trunk + 1], dk->subtree_com[3 * trunk + 2]};
  }

  Refs solve(const CrawlSample& s) {
    for (int it = 0; it < 2; ++it) {
      const Refs r = ik(Eigen::Vector3d(s.com.x() + offset.x(), s.com.y() + offset.y(), body_height), s);
      offset += s.com - com_of(r).head<2>();
    }
    return ik(Eigen::Vector3d(s.com.x() + offset.x(), s.com.y() + offset.y(), body_height), s);
  }
};

}  // namespace

std::vector<std::string> quadruped_log_columns() {
  std::vector<std::string> c{"time_s"};
  for (auto ch : kQuadrupedForceChannels) c.push_back(std::string(ch) + "/force_N");
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("imu/acc_") + a + "_m_s2");
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("imu/gyro_") + a + "_rad_s");
  for (auto a : {"w", "x", "y", "z"}) c.push_back(std::string("base/quat_") + a);
  for (auto j : kQuadrupedJointNames) c.push_back("joint_pos/" + std::string(j) + "_rad");
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("base/pos_") + a + "_m");
  for (auto a : {"x", "y"}) c.push_back(std::string("plan/com_") + a + "_m");
  for (auto leg : kQuadrupedLegs) c.push_back("plan/contact_" + std::string(leg));
  for (auto ch : kQuadrupedForceChannels) c.push_back("truth/" + std::string(ch) + "/force_N");
  for (auto ch : kQuadrupedForceChannels) c.push_back("truth/" + std::string(ch) + "/contact");
  for (auto ch : kQuadrupedForceChannels)
    for (auto a : {"x", "y", "z"}) c.push_back("truth/" + std::string(ch) + "/pos_" + a + "_m");
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("truth/com_") + a + "_m");
  c.push_back("truth/torso_height_m");
  c.push_back("truth/torso_tilt_rad");
  for (auto ch : kQuadrupedForceChannels) c.push_back("truth/" + std::string(ch) + "/fault");
  return c;
}

SimulationSummary simulate_quadruped(const Scenario& sc, std::uint64_t seed, std::ostream& csv,
                                     const SimulationOptions& opt) {
  const std::clock_t cpu0 = std::clock();
  SimulationSummary sum;
  sum.foot_names.assign(kQuadrupedForceChannels.begin(), kQuadrupedForceChannels.end());
  sum.liftoffs.assign(kLegs, 0);
  sum.touchdowns.assign(kLegs, 0);
  const QuadrupedParams& qp = sc.quadruped;
  MjModelPtr model = load_mjcf_string(quadruped_mjcf(qp));
  const mjModel* m = model.get();
  MjDataPtr data(mj_makeData(m));
  MjDataPtr scratch(mj_makeData(m));
  mjData* d = data.get();
  const double dt = m->opt.timestep;
  const std::int64_t log_every = detail::log_every_ticks(sc, dt);

  const int trunk = require_id(m, mjOBJ_BODY, "trunk");
  FreeBodyAccelerometer accelerometer(m, require_id(m, mjOBJ_SITE, "imu"));
  const int gyro_adr = m->sensor_adr[require_id(m, mjOBJ_SENSOR, "imu_gyro")];
  std::array<int, kJoints> qadr{}, act{};
  for (std::size_t j = 0; j < kJoints; ++j) {
    const std::string name(kQuadrupedJointNames[j]);
    qadr[j] = m->jnt_qposadr[require_id(m, mjOBJ_JOINT, name.c_str())];
    act[j] = require_id(m, mjOBJ_ACTUATOR, name.c_str());
  }
  std::vector<int> geom_channel(static_cast<std::size_t>(m->ngeom), -1);
  std::array<int, kLegs> foot_body{};
  for (std::size_t leg = 0; leg < kLegs; ++leg) {
    const std::string name = std::string(kQuadrupedLegs[leg]) + "_foot";
    geom_channel[static_cast<std::size_t>(require_id(m, mjOBJ_GEOM, name.c_str()))] = static_cast<int>(leg);
    foot_body[leg] = require_id(m, mjOBJ_BODY, name.c_str());
  }
  double mass = 0.0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  const double grav = -m->opt.gravity[2];
  sum.total_mass_kg = mass;
  sum.gravity_m_s2 = grav;

  std::optional<CrawlPlan> plan_storage;
  try {
    plan_storage.emplace(sc.crawl, qp.hip_x_m, qp.foot_radius_m, sc.duration_s);
  } catch (const std::invalid_argument& ex) {
    std::ostringstream msg;
    msg.imbue(std::locale::classic());
    msg << "/gait/stability_margin_m = " << sc.crawl.stability_margin_m << ": " << ex.what();
    throw ScenarioError({msg.str()});
  }
  const CrawlPlan& plan = *plan_storage;
  sum.num_steps = 4 * plan.num_cycles();
  sum.planned_stability_margin_m = plan.min_margin_m();
  const auto n_ticks = static_cast<std::int64_t>(std::llround(sc.duration_s / dt));

  QuadrupedController ctl{m, scratch.get(), QuadrupedLegGeometry{qp.thigh_m, qp.shank_m}, {}, sc.crawl.body_height_m,
                          qadr, trunk, Eigen::Vector2d::Zero()};
  for (std::size_t leg = 0; leg < kLegs; ++leg) {
    const auto h = quadruped_hip_point(qp, static_cast<int>(leg));
    ctl.hips[leg] = Eigen::Vector3d(h[0], h[1], h[2]);
  }
  const CrawlSample s0 = plan.sample(0.0);
  (void)ctl.solve(s0);
  const QuadrupedController::Refs r0 = ctl.solve(s0);

  // Initial state: the planned posture at t = 0, feet touching the floor.
  for (int i = 0; i < 3; ++i) d->qpos[i] = r0.trunk[i];
  d->qpos[3] = 1.0;
  for (std::size_t j = 0; j < kJoints; ++j) d->qpos[qadr[j]] = r0.q[j];

  mj_forward(m, d);

  std::array<double, kJoints> qpre{};
  // Rolling drift: a sphere foot rolls as its shank turns in stance, so its centre creeps forward
  // (about 5 mm per cycle). The plan is re-anchored to where the feet are: the CoM and every foot
  // target are shifted by the mean (x, y) drift of the planned stance feet from their footholds,
  // low-passed (time constant kDriftFilter_s) so that the switch of the stance set at lift-off
  // does not jump the references.
  constexpr double kDriftFilter_s = 0.5;
  Eigen::Vector2d drift = Eigen::Vector2d::Zero();
  auto anchored = [&](CrawlSample s) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    int n = 0;
    for (std::size_t leg = 0; leg < kLegs; ++leg) {
      if (!s.contact[leg]) continue;
      const mjtNum* x = d->xpos + 3 * foot_body[leg];
      mean += Eigen::Vector2d(x[0], x[1]) - s.foot[leg].head<2>();
      ++n;
    }
    if (n > 0) drift += (dt / kDriftFilter_s) * (mean / n - drift);
    s.com += drift;
    for (auto& f : s.foot) f.head<2>() += drift;
    return s;
  };
  // One controller tick: joint references from the (re-anchored) plan, then the servo torques
  // (MuJoCo clamps them to the actuators' ctrlrange). Reads the state before mj_step.
  auto control = [&](const CrawlSample& s) {
    const QuadrupedController::Refs ref = ctl.solve(s);
    for (std::size_t j = 0; j < kJoints; ++j) {
      qpre[j] = d->qpos[qadr[j]];
      d->ctrl[act[j]] = qp.servo_kp_Nm_rad * (ref.q[j] - qpre[j]);
    }
    return ref.reachable;
  };

  // Settle onto the feet before logging, as for the biped: the log's t = 0 is the settled robot.
  {
    const auto settle_ticks = static_cast<int>(std::lround(opt.settle_s / dt));
    for (int i = 0; i < settle_ticks; ++i) {
      (void)control(anchored(s0));
      mj_step(m, d);
    }
    d->time = 0.0;
    mj_forward(m, d);
  }

  std::vector<ForceChannelModel> force;
  for (std::size_t c = 0; c < kLegs; ++c) {
    std::vector<FaultSpec> fs;
    for (const auto& f : sc.faults)
      if (f.channel == static_cast<int>(c)) fs.push_back(f);
    force.emplace_back(static_cast<int>(c), sc.sensors.force_noise_std_N, std::move(fs), dt, seed,
                       static_cast<double>(log_every) * dt, sc.sensors.force_resolution_N,
                       sc.sensors.force_zero_below_N);
  }
  Rng imu_rng(seed, 1), enc_rng(seed, 2), base_rng(seed, 3);
  const SensorParams& sp = sc.sensors;

  const auto cols = quadruped_log_columns();
  for (std::size_t i = 0; i < cols.size(); ++i) csv << (i ? "," : "") << cols[i];
  csv << '\n';
  detail::CsvRow row;

  std::array<bool, kLegs> prev_contact{true, true, true, true};
  double com_se = 0.0, stance_ratio_sum = 0.0;
  std::int64_t com_n = 0, stance_n = 0;
  double next_progress = 0.0;
  const double ticks_per_s = static_cast<double>(std::llround(1.0 / dt));
  for (std::int64_t k = 0; k < n_ticks; ++k) {
    const double t = static_cast<double>(k) / ticks_per_s;
    const CrawlSample s = anchored(plan.sample(t));
    if (!control(s)) ++sum.ik_unreachable_ticks;
    accelerometer.before_step(d);
    mj_step(m, d);  // derived quantities (contacts, xpos, sensors) now belong to time t
    const Eigen::Vector3d specific_force = accelerometer.after_step(d);

    std::array<double, kLegs> fn{};
    double fsum = 0.0;
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& con = d->contact[i];
      int ch = geom_channel[static_cast<std::size_t>(con.geom1)];
      if (ch < 0) ch = geom_channel[static_cast<std::size_t>(con.geom2)];
      if (ch < 0) continue;
      mjtNum f6[6];
      mj_contactForce(m, d, i, f6);
      fn[static_cast<std::size_t>(ch)] += f6[0];
      fsum += f6[0];
    }
    std::array<bool, kLegs> contact{};
    for (std::size_t f = 0; f < kLegs; ++f) {
      contact[f] = fn[f] > opt.contact_threshold_N;
      if (prev_contact[f] && !contact[f]) ++sum.liftoffs[f];
      if (!prev_contact[f] && contact[f]) ++sum.touchdowns[f];
      prev_contact[f] = contact[f];
    }
    const mjtNum* bx = d->xpos + 3 * trunk;
    const mjtNum* bm = d->xmat + 9 * trunk;
    const double height = bx[2];
    const double tilt = std::acos(std::clamp(static_cast<double>(bm[8]), -1.0, 1.0));
    const double* tc = d->subtree_com + 3 * trunk;
    sum.min_torso_height_m = std::min(sum.min_torso_height_m, height);
    sum.max_torso_tilt_rad = std::max(sum.max_torso_tilt_rad, tilt);
    {
      const double e2 = std::pow(tc[0] - s.com.x(), 2) + std::pow(tc[1] - s.com.y(), 2);
      com_se += e2;
      ++com_n;
      sum.com_error_max_m = std::max(sum.com_error_max_m, std::sqrt(e2));
    }
    if (t < sc.crawl.initial_stand_s - 0.05) {
      stance_ratio_sum += fsum / (mass * grav);
      ++stance_n;
    }

    if (k % log_every == 0) {
      row.first(t);
      std::array<FaultType, kLegs> codes{};
      for (std::size_t c = 0; c < kLegs; ++c) {
        const auto out = force[c].step(k, fn[c]);
        codes[c] = out.fault;
        row.num(out.value);
      }
      const bool acc_fault = sp.acc_fault_start_s && t >= *sp.acc_fault_start_s &&
                             (!sp.acc_fault_end_s || t < *sp.acc_fault_end_s);
      for (std::size_t i = 0; i < 3; ++i)
        row.num(specific_force[static_cast<Eigen::Index>(i)] + sp.acc_bias_m_s2[i] +
                sp.acc_noise_std_m_s2 * imu_rng.normal() + (acc_fault ? sp.acc_fault_offset_m_s2[i] : 0.0));
      for (std::size_t i = 0; i < 3; ++i)
        row.num(d->sensordata[gyro_adr + static_cast<int>(i)] + sp.gyro_bias_rad_s[i] +
                sp.gyro_noise_std_rad_s * imu_rng.normal());
      // Trunk orientation as a unit quaternion (w, x, y, z), w >= 0; the orientation noise
      // (base.rpy_noise_std_rad) is a small rotation about the trunk's axes.
      const mjtNum* xq = d->xquat + 4 * trunk;
      Eigen::Quaterniond q(xq[0], xq[1], xq[2], xq[3]);
      if (sp.base_rpy_noise_std_rad > 0.0) {
        Eigen::Vector3d v;
        for (int i = 0; i < 3; ++i) v[i] = sp.base_rpy_noise_std_rad * base_rng.normal();
        if (v.norm() > 0.0) q = q * Eigen::Quaterniond(Eigen::AngleAxisd(v.norm(), v.normalized()));
      }
      q.normalize();
      if (q.w() < 0.0) q.coeffs() = -q.coeffs();
      row.num(q.w());
      row.num(q.x());
      row.num(q.y());
      row.num(q.z());
      for (std::size_t j = 0; j < kJoints; ++j)
        row.num(qpre[j] + (sp.encoder_noise_std_rad > 0.0 ? sp.encoder_noise_std_rad * enc_rng.normal() : 0.0));
      for (int i = 0; i < 3; ++i) row.num(bx[i]);
      row.num(s.com.x());
      row.num(s.com.y());
      for (bool c : s.contact) row.num(c ? 1.0 : 0.0);
      for (double f : fn) row.num(f);
      for (bool c : contact) row.num(c ? 1.0 : 0.0);
      for (std::size_t leg = 0; leg < kLegs; ++leg)
        for (int i = 0; i < 3; ++i) row.num(d->xpos[3 * foot_body[leg] + i]);
      for (int i = 0; i < 3; ++i) row.num(tc[i]);
      row.num(height);
      row.num(tilt);
      for (FaultType c : codes) row.num(fault_code(c));
      row.flush(csv);
      ++sum.ticks;
    }
    sum.simulated_s = t;

    if (opt.progress && t >= next_progress) {
      opt.progress(t, sc.duration_s);
      next_progress += opt.progress_interval_s;
    }
    if (detail::record_fall(t, height, tilt, opt.min_quadruped_torso_height_m, opt.max_torso_tilt_rad, sum)) break;
  }
  csv.flush();
  if (com_n > 0) sum.com_error_rms_m = std::sqrt(com_se / static_cast<double>(com_n));
  if (stance_n > 0) sum.quiet_stance_force_ratio = stance_ratio_sum / static_cast<double>(stance_n);
  if (!sum.fell) {
    std::ostringstream msg;
    msg.imbue(std::locale::classic());
    msg << "crawled " << plan.num_cycles() << " cycles (" << sum.num_steps << " steps) in " << sc.duration_s
        << " s without falling";
    sum.message = msg.str();
  }
  sum.cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  return sum;
}

}  // namespace ftsense::sim
