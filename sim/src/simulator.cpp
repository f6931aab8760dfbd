#include "ftsense/sim/simulator.hpp"

#include <charconv>
#include <cmath>
#include <ctime>
#include <locale>
#include <sstream>

#include "ftsense/sim/leg_kinematics.hpp"
#include "ftsense/sim/free_body_accelerometer.hpp"
#include "ftsense/sim/mujoco_model.hpp"
#include "ftsense/sim/preview_control.hpp"
#include "simulation_log.hpp"

namespace ftsense::sim {

namespace {

constexpr std::array<const char*, 2> kSide = {"l", "r"};
using detail::CsvRow;

struct Controller {
  const mjModel* m;
  mjData* dk;  // scratch data for kinematic CoM
  LegGeometry g;
  double hip_w;
  double pelvis_z;
  std::array<int, 12> qadr{};
  int trunk = 0;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  // pelvis - CoM (xy), warm-started

  struct Refs {
    Eigen::Vector3d pelvis;
    std::array<double, 12> q;
    bool reachable;
  };

  Refs ik(const Eigen::Vector3d& pelvis, const GaitSample& s) const {
    Refs r{pelvis, {}, true};
    for (int leg = 0; leg < 2; ++leg) {
      Pose hip;
      hip.p = pelvis + Eigen::Vector3d(0.0, leg == 0 ? hip_w : -hip_w, 0.0);
      Pose sole;
      sole.p = s.sole[static_cast<std::size_t>(leg)];
      const auto res = leg_inverse(g, hip, sole);
      r.reachable = r.reachable && res.reachable;
      for (int j = 0; j < 6; ++j) r.q[static_cast<std::size_t>(6 * leg + j)] = res.q[static_cast<std::size_t>(j)];
    }
    return r;
  }

  Eigen::Vector3d com_of(const Refs& r) const {
    mju_zero(dk->qpos, m->nq);
    for (int i = 0; i < 3; ++i) dk->qpos[i] = r.pelvis[i];
    dk->qpos[3] = 1.0;
    for (std::size_t j = 0; j < 12; ++j) dk->qpos[qadr[j]] = r.q[j];
    mj_kinematics(m, dk);
    mj_comPos(m, dk);
    return {dk->subtree_com[3 * trunk], dk->subtree_com[3 * trunk + 1], dk->subtree_com[3 * trunk + 2]};
  }

  /// Joint references putting the multibody CoM (xy) at com_xy with the feet at the plan.
  Refs solve(const Eigen::Vector2d& com_xy, const GaitSample& s, const Eigen::Vector2d& fb = Eigen::Vector2d::Zero()) {
    Refs r{};
    for (int it = 0; it < 2; ++it) {
      r = ik(Eigen::Vector3d(com_xy.x() + offset.x(), com_xy.y() + offset.y(), pelvis_z), s);
      const Eigen::Vector3d c = com_of(r);
      offset += com_xy - c.head<2>();
    }
    return ik(Eigen::Vector3d(com_xy.x() + offset.x() + fb.x(), com_xy.y() + offset.y() + fb.y(), pelvis_z), s);
  }

  /// Swing-foot levelling. The position servos let the trunk sag and tilt a little, so a swing
  /// foot following the nominal IK would land on one heel corner. While a foot swings (and in
  /// the double support after its landing) its leg's IK is re-solved from the actual trunk
  /// orientation R_act and the pelvis height implied by the other leg's joint angles q_act,
  /// keeping the planned pelvis x, y; the result is blended in with s.swing_weight.
  void level_swing_feet(Refs& r, const GaitSample& s, const Eigen::Matrix3d& R_act,
                        const std::array<double, 12>& q_act) const {
    for (std::size_t f = 0; f < 2; ++f) {
      const double w = s.swing_weight[f];
      if (w <= 0.0) continue;
      const std::size_t a = 1 - f;
      const double ya = a == 0 ? hip_w : -hip_w, yf = f == 0 ? hip_w : -hip_w;
      Pose hip_a;
      hip_a.R = R_act;
      hip_a.p = R_act * Eigen::Vector3d(0.0, ya, 0.0);
      LegAngles qa{};
      for (std::size_t j = 0; j < 6; ++j) qa[j] = q_act[6 * a + j];
      Eigen::Vector3d pelvis = s.sole[a] - leg_forward(g, hip_a, qa).p;
      pelvis.head<2>() = r.pelvis.head<2>();
      Pose hip_f;
      hip_f.R = R_act;
      hip_f.p = pelvis + R_act * Eigen::Vector3d(0.0, yf, 0.0);
      Pose sole;
      sole.p = s.sole[f];
      const auto res = leg_inverse(g, hip_f, sole);
      for (std::size_t j = 0; j < 6; ++j) r.q[6 * f + j] += w * (res.q[j] - r.q[6 * f + j]);
    }
  }
};

}  // namespace

namespace detail {
std::int64_t log_every_ticks(const Scenario& sc, double dt) {
  if (!sc.log_period_s) return 1;
  const std::int64_t every = std::llround(*sc.log_period_s / dt);
  if (every < 1 || std::abs(static_cast<double>(every) * dt - *sc.log_period_s) > 1e-9) {
    throw ScenarioError({"/log_period_s = " + std::to_string(*sc.log_period_s) +
                         " s is not a whole multiple of the simulation tick " + std::to_string(dt) +
                         " s; give a multiple such as 0.002 or 0.005"});
  }
  return every;
}
}  // namespace detail

std::vector<std::string> log_columns() {
  std::vector<std::string> c{"time_s"};
  for (auto s : kSide)
    for (int p = 1; p <= 4; ++p) c.push_back(std::string(s) + "_foot/p" + std::to_string(p) + "/force_N");
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("imu/acc_") + a + "_m_s2");
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("imu/gyro_") + a + "_rad_s");
  for (auto a : {"roll", "pitch", "yaw"}) c.push_back(std::string("base/rpy_") + a + "_rad");
  for (auto j : kJointNames) c.push_back("joint_pos/" + std::string(j) + "_rad");
  for (auto s : kSide) {
    for (auto a : {"x", "y", "z"}) c.push_back(std::string(s) + "_foot/pos_" + a + "_m");
    for (auto a : {"roll", "pitch", "yaw"}) c.push_back(std::string(s) + "_foot/rpy_" + a + "_rad");
  }
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("base/pos_") + a + "_m");
  for (auto a : {"x", "y"}) c.push_back(std::string("plan/zmp_") + a + "_m");
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("plan/com_") + a + "_m");
  c.push_back("plan/contact_l");
  c.push_back("plan/contact_r");
  for (auto s : kSide)
    for (int p = 1; p <= 4; ++p) c.push_back(std::string("truth/") + s + "_foot/p" + std::to_string(p) + "/force_N");
  for (auto a : {"x", "y", "z"}) c.push_back(std::string("truth/com_") + a + "_m");
  for (auto a : {"x", "y"}) c.push_back(std::string("truth/zmp_") + a + "_m");
  c.push_back("truth/l_foot/contact");
  c.push_back("truth/r_foot/contact");
  c.push_back("truth/torso_height_m");
  c.push_back("truth/torso_tilt_rad");
  for (auto s : kSide)
    for (int p = 1; p <= 4; ++p) c.push_back(std::string("truth/") + s + "_foot/p" + std::to_string(p) + "/fault");
  return c;
}

SimulationSummary simulate(const Scenario& sc, std::uint64_t seed, std::ostream& csv,
                           const SimulationOptions& opt) {
  if (sc.robot_kind == RobotKind::quadruped) return simulate_quadruped(sc, seed, csv, opt);
  const std::clock_t cpu0 = std::clock();
  SimulationSummary sum;
  sum.foot_names = {"l_foot", "r_foot"};
  sum.liftoffs.assign(2, 0);
  sum.touchdowns.assign(2, 0);
  const RobotParams& rp = sc.robot;
  MjModelPtr model = load_mjcf_string(suralp_mjcf(rp));
  const mjModel* m = model.get();
  MjDataPtr data(mj_makeData(m));
  MjDataPtr scratch(mj_makeData(m));
  mjData* d = data.get();
  const double dt = m->opt.timestep;
  // The sensors sample every log_every ticks (the scenario's log period).
  const std::int64_t log_every = detail::log_every_ticks(sc, dt);

  const int trunk = require_id(m, mjOBJ_BODY, "trunk");
  FreeBodyAccelerometer accelerometer(m, require_id(m, mjOBJ_SITE, "imu"));
  const int gyro_adr = m->sensor_adr[require_id(m, mjOBJ_SENSOR, "imu_gyro")];
  std::array<int, 12> qadr{}, act{};
  for (std::size_t j = 0; j < 12; ++j) {
    const std::string name(kJointNames[j]);
    qadr[j] = m->jnt_qposadr[require_id(m, mjOBJ_JOINT, name.c_str())];
    act[j] = require_id(m, mjOBJ_ACTUATOR, name.c_str());
  }
  std::vector<int> geom_channel(static_cast<std::size_t>(m->ngeom), -1);
  for (int s = 0; s < 2; ++s)
    for (int p = 0; p < 4; ++p) {
      const std::string name = std::string(kSide[static_cast<std::size_t>(s)]) + "_pad" + std::to_string(p + 1);
      geom_channel[static_cast<std::size_t>(require_id(m, mjOBJ_GEOM, name.c_str()))] = 4 * s + p;
    }
  double mass = 0.0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  const double grav = -m->opt.gravity[2];
  sum.total_mass_kg = mass;
  sum.gravity_m_s2 = grav;

  // Plan: footsteps and ZMP reference, then the CoM by preview control.
  const GaitPlan plan(sc.gait, sc.duration_s);
  sum.num_steps = plan.num_steps();
  const auto n_ticks = static_cast<std::int64_t>(std::llround(sc.duration_s / dt));
  Controller ctl{m, scratch.get(), LegGeometry{rp.upper_leg_m, rp.lower_leg_m, rp.sole_ankle_m},
                 rp.hip_half_width_m, sc.gait.pelvis_height_m, qadr, trunk, Eigen::Vector2d::Zero()};
  const GaitSample s0 = plan.sample(0.0);
  ctl.solve(s0.zmp, s0);
  const Controller::Refs r0 = ctl.solve(s0.zmp, s0);
  const double zc = ctl.com_of(r0).z();
  sum.lipm_com_height_m = zc;

  std::vector<double> zx(static_cast<std::size_t>(n_ticks) + 1), zy(zx.size());
  for (std::size_t k = 0; k < zx.size(); ++k) {
    const GaitSample s = plan.sample(static_cast<double>(k) * dt);
    zx[k] = s.zmp.x();
    zy[k] = s.zmp.y();
  }
  const ZmpPreviewController preview(dt, zc, grav, sc.gait.preview_s);
  const auto cx = preview.track(zx, Eigen::Vector3d(zx[0], 0, 0));
  const auto cy = preview.track(zy, Eigen::Vector3d(zy[0], 0, 0));

  // Initial state: the planned posture at t = 0, pads touching the floor.
  for (int i = 0; i < 3; ++i) d->qpos[i] = r0.pelvis[i];
  d->qpos[3] = 1.0;
  for (std::size_t j = 0; j < 12; ++j) {
    d->qpos[qadr[j]] = r0.q[j];
  }
  std::array<double, 12> kp{};
  for (std::size_t j = 0; j < 12; ++j)
    kp[j] = rp.servo_kp_Nm_rad * ((j % 6 >= 4) ? rp.ankle_kp_scale : 1.0);
  std::array<double, 12> qpre{};
  Eigen::Vector2d com_err_int = Eigen::Vector2d::Zero();
  // One controller tick: joint references from the plan (CoM feedback, IK, swing-foot
  // levelling), then the joint servo torques. Reads the state before mj_step.
  auto control = [&](const GaitSample& s, const Eigen::Vector2d& com_plan) {
    const Eigen::Vector2d com_true(d->subtree_com[3 * trunk], d->subtree_com[3 * trunk + 1]);
    const Eigen::Vector2d com_err = com_plan - com_true;
    com_err_int += com_err * dt;
    Controller::Refs ref = ctl.solve(com_plan, s, sc.gait.com_feedback_gain * com_err +
                                                      sc.gait.com_feedback_integral_gain_1_s * com_err_int);
    for (std::size_t j = 0; j < 12; ++j) qpre[j] = d->qpos[qadr[j]];
    const mjtNum* qb = d->qpos + 3;  // trunk quaternion (w, x, y, z)
    const Eigen::Matrix3d R_act =
        Eigen::Quaterniond(qb[0], qb[1], qb[2], qb[3]).normalized().toRotationMatrix();
    ctl.level_swing_feet(ref, s, R_act, qpre);
    for (std::size_t j = 0; j < 12; ++j) d->ctrl[act[j]] = kp[j] * (ref.q[j] - qpre[j]);
    return ref.reachable;
  };

  // Settle onto the contacts before logging (the pads start exactly touching; the 0.5 mm
  // equilibrium penetration and the CoM feedback take a few tenths of a second): run the t = 0
  // controller, then restart the clock. The log's t = 0 is the settled robot.
  {
    const Eigen::Vector2d com0(cx[0].x(), cy[0].x());
    const auto settle_ticks = static_cast<int>(std::lround(opt.settle_s / dt));
    for (int i = 0; i < settle_ticks; ++i) {
      (void)control(s0, com0);
      mj_step(m, d);
    }
    d->time = 0.0;
    mj_forward(m, d);
  }

  // Sensors.
  std::vector<ForceChannelModel> force;
  for (int c = 0; c < 8; ++c) {
    std::vector<FaultSpec> fs;
    for (const auto& f : sc.faults)
      if (f.channel == c) fs.push_back(f);
    force.emplace_back(c, sc.sensors.force_noise_std_N, std::move(fs), dt, seed, log_every * dt,
                       sc.sensors.force_resolution_N, sc.sensors.force_zero_below_N);
  }
  Rng imu_rng(seed, 1), enc_rng(seed, 2), base_rng(seed, 3);
  const SensorParams& sp = sc.sensors;

  const auto cols = log_columns();
  for (std::size_t i = 0; i < cols.size(); ++i) csv << (i ? "," : "") << cols[i];
  csv << '\n';
  CsvRow row;

  std::array<bool, 2> prev_contact{true, true};
  double zmp_se = 0.0, com_se = 0.0, stance_ratio_sum = 0.0;
  std::int64_t zmp_n = 0, com_n = 0, stance_n = 0, zmp_ss_n = 0;
  double zmp_ss_se = 0.0;
  double next_progress = 0.0;
  const LegGeometry& lg = ctl.g;

  // t = k / (ticks per second): the double nearest to the decimal time, printed as such.
  const double ticks_per_s = static_cast<double>(std::llround(1.0 / dt));
  for (std::int64_t k = 0; k < n_ticks; ++k) {
    const double t = static_cast<double>(k) / ticks_per_s;
    const auto ku = static_cast<std::size_t>(k);
    const GaitSample s = plan.sample(t);
    const Eigen::Vector2d com_plan(cx[ku].x(), cy[ku].x());
    if (!control(s, com_plan)) ++sum.ik_unreachable_ticks;
    // After mj_step every derived quantity (xpos, contacts, sensors) belongs to time t; only
    // qpos/qvel have advanced, hence the joint positions saved above.
    accelerometer.before_step(d);
    mj_step(m, d);
    const Eigen::Vector3d specific_force = accelerometer.after_step(d);

    // Truth.
    std::array<double, 8> fn{};
    double fsum = 0.0, mx = 0.0, my = 0.0;
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& con = d->contact[i];
      int ch = geom_channel[static_cast<std::size_t>(con.geom1)];
      if (ch < 0) ch = geom_channel[static_cast<std::size_t>(con.geom2)];
      if (ch < 0) continue;
      mjtNum f6[6];
      mj_contactForce(m, d, i, f6);
      fn[static_cast<std::size_t>(ch)] += f6[0];
      fsum += f6[0];
      mx += f6[0] * con.pos[0];
      my += f6[0] * con.pos[1];
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double tzx = fsum > opt.contact_threshold_N ? mx / fsum : nan;
    const double tzy = fsum > opt.contact_threshold_N ? my / fsum : nan;
    std::array<bool, 2> contact{};
    for (std::size_t f = 0; f < 2; ++f) {
      const double ff = fn[4 * f] + fn[4 * f + 1] + fn[4 * f + 2] + fn[4 * f + 3];
      contact[f] = ff > opt.contact_threshold_N;
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
    if (!std::isnan(tzx)) {
      const double e2 = std::pow(tzx - s.zmp.x(), 2) + std::pow(tzy - s.zmp.y(), 2);
      zmp_se += e2;
      ++zmp_n;
      sum.zmp_error_max_m = std::max(sum.zmp_error_max_m, std::sqrt(e2));
      if (s.contact[0] != s.contact[1]) {
        zmp_ss_se += e2;
        ++zmp_ss_n;
        sum.zmp_error_ss_max_m = std::max(sum.zmp_error_ss_max_m, std::sqrt(e2));
      }
    }
    {
      const double e2 = std::pow(tc[0] - com_plan.x(), 2) + std::pow(tc[1] - com_plan.y(), 2);
      com_se += e2;
      ++com_n;
      sum.com_error_max_m = std::max(sum.com_error_max_m, std::sqrt(e2));
    }
    if (t < sc.gait.initial_stand_s - 0.05) {
      stance_ratio_sum += fsum / (mass * grav);
      ++stance_n;
    }

    // Measurements, on the logged ticks only (the sensors sample at the log's rate).
    if (k % log_every == 0) {
      row.first(t);
      std::array<FaultType, 8> codes{};
      for (std::size_t c = 0; c < 8; ++c) {
        const auto out = force[c].step(k, fn[c]);
        codes[c] = out.fault;
        row.num(out.value);
      }
      const bool acc_fault = sp.acc_fault_start_s && t >= *sp.acc_fault_start_s &&
                             (!sp.acc_fault_end_s || t < *sp.acc_fault_end_s);
      for (int i = 0; i < 3; ++i)
        row.num(specific_force[i] + sp.acc_bias_m_s2[static_cast<std::size_t>(i)] +
                sp.acc_noise_std_m_s2 * imu_rng.normal() +
                (acc_fault ? sp.acc_fault_offset_m_s2[static_cast<std::size_t>(i)] : 0.0));
      for (int i = 0; i < 3; ++i)
        row.num(d->sensordata[gyro_adr + i] + sp.gyro_bias_rad_s[static_cast<std::size_t>(i)] +
                sp.gyro_noise_std_rad_s * imu_rng.normal());
      Eigen::Matrix3d Rb;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Rb(i, j) = bm[3 * i + j];
      Eigen::Vector3d rpy = matrix_to_rpy(Rb);
      if (sp.base_rpy_noise_std_rad > 0.0)
        for (int i = 0; i < 3; ++i) rpy[i] += sp.base_rpy_noise_std_rad * base_rng.normal();
      for (int i = 0; i < 3; ++i) row.num(rpy[i]);
      std::array<double, 12> qm{};
      for (std::size_t j = 0; j < 12; ++j) {
        qm[j] = qpre[j] + (sp.encoder_noise_std_rad > 0.0 ? sp.encoder_noise_std_rad * enc_rng.normal() : 0.0);
        row.num(qm[j]);
      }
      // Foot frames as the robot's kinematics sees them: measured base pose and encoders.
      const Eigen::Matrix3d Rm = rpy_to_matrix(rpy[0], rpy[1], rpy[2]);
      const Eigen::Vector3d base(bx[0], bx[1], bx[2]);
      for (int leg = 0; leg < 2; ++leg) {
        Pose hip;
        hip.R = Rm;
        hip.p = base + Rm * Eigen::Vector3d(0.0, leg == 0 ? rp.hip_half_width_m : -rp.hip_half_width_m, 0.0);
        LegAngles q{};
        for (std::size_t j = 0; j < 6; ++j) q[j] = qm[6 * static_cast<std::size_t>(leg) + j];
        const Pose sole = leg_forward(lg, hip, q);
        for (int i = 0; i < 3; ++i) row.num(sole.p[i]);
        const Eigen::Vector3d frpy = matrix_to_rpy(sole.R);
        for (int i = 0; i < 3; ++i) row.num(frpy[i]);
      }
      for (int i = 0; i < 3; ++i) row.num(bx[i]);
      row.num(s.zmp.x());
      row.num(s.zmp.y());
      row.num(com_plan.x());
      row.num(com_plan.y());
      row.num(zc);
      row.num(s.contact[0] ? 1.0 : 0.0);
      row.num(s.contact[1] ? 1.0 : 0.0);
      for (double f : fn) row.num(f);
      for (int i = 0; i < 3; ++i) row.num(tc[i]);
      row.num(tzx);
      row.num(tzy);
      row.num(contact[0] ? 1.0 : 0.0);
      row.num(contact[1] ? 1.0 : 0.0);
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
    if (detail::record_fall(t, height, tilt, opt.min_torso_height_m, opt.max_torso_tilt_rad, sum)) break;
  }
  csv.flush();
  if (zmp_n > 0) sum.zmp_error_rms_m = std::sqrt(zmp_se / static_cast<double>(zmp_n));
  if (zmp_ss_n > 0) sum.zmp_error_ss_rms_m = std::sqrt(zmp_ss_se / static_cast<double>(zmp_ss_n));
  if (com_n > 0) sum.com_error_rms_m = std::sqrt(com_se / static_cast<double>(com_n));
  if (stance_n > 0) sum.quiet_stance_force_ratio = stance_ratio_sum / static_cast<double>(stance_n);
  if (!sum.fell) {
    std::ostringstream msg;
    msg.imbue(std::locale::classic());
    msg << "walked " << plan.num_steps() << " steps in " << sc.duration_s << " s without falling";
    sum.message = msg.str();
  }
  sum.cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  return sum;
}

}  // namespace ftsense::sim
