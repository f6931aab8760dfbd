// The quadruped: leg IK/FK, the model, the crawl plan, standing and crawling in MuJoCo, a fault's
// reach in the log, its scenario keys, and its URDF (golden file, same kinematics and masses).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "scenario_dir.hpp"
#include "csv_table.hpp"
#include "ftsense/robot_model/kinematic_tree.hpp"
#include "ftsense/sim/crawl_gait.hpp"
#include "ftsense/sim/mujoco_model.hpp"
#include "ftsense/sim/quadruped_leg_kinematics.hpp"
#include "ftsense/sim/quadruped_model.hpp"
#include "ftsense/sim/quadruped_urdf.hpp"
#include "ftsense/sim/simulator.hpp"

using namespace ftsense::sim;
using ftsense::sim::testing::CsvTable;
using nlohmann::json;

namespace {
namespace fs = std::filesystem;
using ftsense::sim::testing::kScenarioDir;
const fs::path kUrdf = kScenarioDir / ".." / "quadruped" / "quadruped.urdf";
constexpr std::uint64_t kQuadrupedSeed = 1;

std::string run(const Scenario& sc, SimulationSummary& sum, std::uint64_t seed = kQuadrupedSeed) {
  std::ostringstream os;
  sum = simulate(sc, seed, os);
  std::printf("%s: %s | cpu %.2f s for %.1f s | stance sum/mg %.5f | CoM err rms %.4f max %.4f m | tilt max %.4f rad\n",
              sc.name.c_str(), sum.message.c_str(), sum.cpu_s, sc.duration_s, sum.quiet_stance_force_ratio,
              sum.com_error_rms_m, sum.com_error_max_m, sum.max_torso_tilt_rad);
  return os.str();
}

Scenario clean(double duration_s) {
  Scenario sc = load_scenario(kScenarioDir / "quadruped_clean.json");
  sc.duration_s = duration_s;
  return sc;
}

std::string leg(std::size_t i) { return std::string(kQuadrupedLegs[i]); }

std::vector<std::string> problems_of(const json& doc) {
  try {
    (void)parse_scenario(doc);
  } catch (const ScenarioError& e) {
    return e.problems();
  }
  return {};
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

TEST(QuadrupedLegKinematics, InverseRoundTripsForward) {
  const QuadrupedLegGeometry g{0.20, 0.20};
  std::mt19937_64 rng(11);  // fixed seed
  std::uniform_real_distribution<double> abd(-0.7, 0.7), flex(-1.2, 2.0), knee(-2.6, -0.1);
  for (int i = 0; i < 2000; ++i) {
    const QuadrupedLegAngles q{abd(rng), flex(rng), knee(rng)};
    const Eigen::Vector3d p = quadruped_leg_forward(g, q);
    if (p.z() >= -1e-3) continue;  // the IK's leg points down (foot below the hip)
    const QuadrupedLegIk ik = quadruped_leg_inverse(g, p);
    ASSERT_TRUE(ik.reachable);
    for (std::size_t j = 0; j < 3; ++j) ASSERT_NEAR(ik.q[j], q[j], 1e-9) << "joint " << j << " sample " << i;
    ASSERT_LT((quadruped_leg_forward(g, ik.q) - p).norm(), 1e-12);
  }
  // Standing posture: foot 0.30 m below the hip, 2 cm outward: knee bent backward.
  const QuadrupedLegIk stand = quadruped_leg_inverse(g, Eigen::Vector3d(0.0, 0.02, -0.28));
  EXPECT_TRUE(stand.reachable);
  EXPECT_LT(stand.q[2], -1.0);
  EXPECT_GT(stand.q[1], 0.5);
  EXPECT_FALSE(quadruped_leg_inverse(g, Eigen::Vector3d(0.0, 0.0, -0.45)).reachable);
}

TEST(QuadrupedModel, LoadsWithThirteenKilogramsAndOneCollidingSpherePerFoot) {
  const QuadrupedParams qp;
  MjModelPtr m = load_mjcf_string(quadruped_mjcf(qp));
  double mass = 0.0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  EXPECT_NEAR(mass, 13.0, 1e-12);
  EXPECT_NEAR(qp.trunk_kg(), 9.0, 1e-12);
  EXPECT_EQ(m->njnt, 13);  // free joint + 12 hinges
  EXPECT_EQ(m->nu, 12);
  EXPECT_DOUBLE_EQ(m->opt.timestep, 0.001);
  int colliding = 0;
  for (int g = 0; g < m->ngeom; ++g)
    if (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0) ++colliding;
  EXPECT_EQ(colliding, 5);  // 4 feet + floor
  for (std::size_t i = 0; i < 4; ++i) {
    const int g = require_id(m.get(), mjOBJ_GEOM, (leg(i) + "_foot").c_str());
    EXPECT_EQ(m->geom_type[g], mjGEOM_SPHERE);
    EXPECT_DOUBLE_EQ(m->geom_size[3 * g], 0.02);
  }
  for (auto j : kQuadrupedJointNames) EXPECT_GE(require_id(m.get(), mjOBJ_ACTUATOR, std::string(j).c_str()), 0);
}

TEST(QuadrupedModel, LegForwardKinematicsMatchesMuJoCo) {
  const QuadrupedParams qp;
  MjModelPtr m = load_mjcf_string(quadruped_mjcf(qp));
  MjDataPtr d(mj_makeData(m.get()));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    std::array<double, 12> q{};
    for (double& x : q) x = u(rng);
    mju_zero(d->qpos, m->nq);
    d->qpos[3] = 1.0;  // trunk at the origin, level
    for (std::size_t j = 0; j < 12; ++j)
      d->qpos[m->jnt_qposadr[require_id(m.get(), mjOBJ_JOINT, std::string(kQuadrupedJointNames[j]).c_str())]] = q[j];
    mj_kinematics(m.get(), d.get());
    for (std::size_t i = 0; i < 4; ++i) {
      const auto h = quadruped_hip_point(qp, static_cast<int>(i));
      const Eigen::Vector3d p = quadruped_leg_forward({qp.thigh_m, qp.shank_m}, {q[3 * i], q[3 * i + 1], q[3 * i + 2]}) +
                                Eigen::Vector3d(h[0], h[1], h[2]);
      const int b = require_id(m.get(), mjOBJ_BODY, (leg(i) + "_foot").c_str());
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(d->xpos[3 * b + k], p[k], 1e-12) << leg(i);
    }
  }
}

TEST(CrawlPlan, OneFootSwingsAtATimeWithTheCoMInsideItsSupportTriangle) {
  const Scenario sc = clean(30.0);
  const CrawlPlan plan(sc.crawl, sc.quadruped.hip_x_m, sc.quadruped.foot_radius_m, sc.duration_s);
  EXPECT_EQ(plan.num_cycles(), 6);  // (30 - 1 - 1.5 - 0.5) / 4
  EXPECT_GE(plan.min_margin_m(), sc.crawl.stability_margin_m - 1e-12);
  std::array<int, 4> swings{};
  int prev = -1;
  double worst = 1.0;
  for (int k = 0; k <= 30000; ++k) {
    const CrawlSample s = plan.sample(0.001 * k);
    int up = 0;
    std::vector<Eigen::Vector2d> stance;
    for (std::size_t i = 0; i < 4; ++i) {
      if (s.contact[i]) {
        stance.push_back(s.foot[i].head<2>());
        ASSERT_DOUBLE_EQ(s.foot[i].z(), sc.quadruped.foot_radius_m);
      } else {
        ++up;
      }
    }
    ASSERT_LE(up, 1);
    worst = std::min(worst, support_margin_m(s.com, stance));
    if (s.swing_leg >= 0 && s.swing_leg != prev) ++swings[static_cast<std::size_t>(s.swing_leg)];
    prev = s.swing_leg;
  }
  EXPECT_GE(worst, sc.crawl.stability_margin_m - 1e-9);
  for (int n : swings) EXPECT_EQ(n, 6);
  // Forward by one stride per cycle; back to the centre of the four feet at the end.
  const CrawlSample end = plan.sample(30.0);
  EXPECT_NEAR(end.foot[0].x(), sc.quadruped.hip_x_m + 6 * sc.crawl.stride_m, 1e-12);
  EXPECT_NEAR(end.com.x(), 6 * sc.crawl.stride_m, 1e-12);
}

TEST(SupportMargin, SignedDistanceToTheHull) {
  const std::vector<Eigen::Vector2d> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  EXPECT_NEAR(support_margin_m({0.5, 0.5}, square), 0.5, 1e-15);
  EXPECT_NEAR(support_margin_m({0.9, 0.2}, square), 0.1, 1e-15);
  EXPECT_NEAR(support_margin_m({1.5, 0.5}, square), -0.5, 1e-15);
  EXPECT_NEAR(support_margin_m({0.5, 1.0}, {{0, 0}, {1, 0}}), -1.0, 1e-15);
}

TEST(QuadrupedStanding, FootForcesSumToWeightWithinOnePercent) {
  Scenario sc = clean(3.0);
  sc.name = "quadruped standing";
  sc.crawl.num_cycles = 0;
  SimulationSummary sum;
  const CsvTable t = CsvTable::parse(run(sc, sum));
  ASSERT_FALSE(sum.fell) << sum.message;
  ASSERT_EQ(t.rows(), 3000u);
  const double mg = sum.total_mass_kg * sum.gravity_m_s2;
  EXPECT_NEAR(sum.total_mass_kg, 13.0, 1e-12);
  for (std::size_t k = 0; k < t.rows(); ++k) {
    double s = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      const double f = t["truth/" + leg(i) + "_foot/force_N"][k];
      ASSERT_GT(f, 0.15 * mg) << leg(i);  // each foot carries a share
      s += f;
    }
    ASSERT_NEAR(s / mg, 1.0, 0.01) << "t = " << t["time_s"][k];
  }
  EXPECT_NEAR(sum.quiet_stance_force_ratio, 1.0, 0.01);
  // A level trunk, quaternion (1, 0, 0, 0) up to the servos' sag; IMU at rest reads g up.
  EXPECT_NEAR(t["base/quat_w"][1000], 1.0, 1e-4);
  double az = 0.0;
  for (double a : t["imu/acc_z_m_s2"]) az += a / static_cast<double>(t.rows());
  EXPECT_NEAR(az, sum.gravity_m_s2 + SensorParams{}.acc_bias_m_s2[2], 0.01);
}

TEST(QuadrupedCrawl, WalksTwelveSecondsOneFootInTheAirAtATime) {
  Scenario sc = clean(12.0);
  sc.name = "quadruped crawl";
  SimulationSummary sum;
  const CsvTable t = CsvTable::parse(run(sc, sum));
  ASSERT_FALSE(sum.fell) << sum.message;
  EXPECT_EQ(sum.ik_unreachable_ticks, 0);
  const auto& time = t["time_s"];
  for (std::size_t i = 0; i < 4; ++i) {
    std::printf("%s: %d lift-offs, %d touchdowns\n", leg(i).c_str(), sum.liftoffs[i], sum.touchdowns[i]);
    EXPECT_GE(sum.liftoffs[i], 2) << leg(i);
    EXPECT_EQ(sum.liftoffs[i], sum.touchdowns[i]) << leg(i);
  }
  double worst_margin = 1.0;
  int swing_ticks = 0;
  for (std::size_t k = 0; k < t.rows(); ++k) {
    int up = 0, planned_up = -1;
    std::vector<Eigen::Vector2d> feet;
    for (std::size_t i = 0; i < 4; ++i) {
      const std::string c = "truth/" + leg(i) + "_foot/";
      if (t[c + "contact"][k] > 0.5) {
        feet.emplace_back(t[c + "pos_x_m"][k], t[c + "pos_y_m"][k]);
      } else {
        ++up;
      }
      if (t["plan/contact_" + leg(i)][k] < 0.5) planned_up = static_cast<int>(i);
    }
    ASSERT_LE(up, 1) << "t = " << time[k];
    // Inside a planned swing (away from its ends: lift-off lags the plan by about 30 ms while
    // the leg unloads, touchdown leads it by about 15 ms as the trunk sags) exactly the planned
    // foot is off the ground.
    if (planned_up >= 0 && k >= 50 && t["plan/contact_" + leg(static_cast<std::size_t>(planned_up))][k - 50] < 0.5 &&
        k + 50 < t.rows() && t["plan/contact_" + leg(static_cast<std::size_t>(planned_up))][k + 50] < 0.5) {
      ++swing_ticks;
      ASSERT_EQ(up, 1) << "t = " << time[k];
      ASSERT_LT(t["truth/" + leg(static_cast<std::size_t>(planned_up)) + "_foot/contact"][k], 0.5) << "t = " << time[k];
    }
    worst_margin = std::min(worst_margin, support_margin_m({t["truth/com_x_m"][k], t["truth/com_y_m"][k]}, feet));
  }
  EXPECT_EQ(swing_ticks, 8 * 400);  // 2 cycles of 4 swings of 0.5 s, less the 0.1 s ends
  // The CoM's ground projection stays inside the polygon of the feet in contact: planned 3 cm,
  // true at least 2 cm (servo compliance and the swing leg's inertia).
  std::printf("true CoM margin in the support polygon: min %.4f m\n", worst_margin);
  EXPECT_GT(worst_margin, 0.02);
  EXPECT_LT(sum.com_error_max_m, 0.01);
  EXPECT_LT(sum.max_torso_tilt_rad, 0.05);
  // Forward: two cycles of 0.08 m, plus the sphere feet's rolling.
  EXPECT_NEAR(t["truth/com_x_m"].back() - t["truth/com_x_m"].front(), 2 * sc.crawl.stride_m, 0.02);
  std::printf("simulated %.1f s of crawling in %.2f s of CPU\n", sc.duration_s, sum.cpu_s);
}

TEST(QuadrupedFaults, AFaultChangesOnlyItsChannelsMeasuredColumnAndTruthCode) {
  Scenario sc = clean(7.0);
  sc.crawl.num_cycles = 1;  // the fault (2 s to 5 s) while the feet step
  sc.name = "quadruped fault reach";
  SimulationSummary a_sum, b_sum;
  const CsvTable a = CsvTable::parse(run(sc, a_sum));
  FaultSpec f;
  f.channel = 1;  // rf_foot
  f.type = ftsense::FaultType::offset;
  f.start_s = 2.0;
  f.end_s = 5.0;
  f.offset_N = 25.0;
  sc.faults.push_back(f);
  const CsvTable b = CsvTable::parse(run(sc, b_sum));
  ASSERT_EQ(a_sum.num_steps, 4);
  ASSERT_FALSE(b_sum.fell);
  ASSERT_EQ(a.names, b.names);
  for (const auto& n : a.names) {
    if (n == "rf_foot/force_N" || n == "truth/rf_foot/fault") continue;
    EXPECT_EQ(a[n], b[n]) << n;
  }
  int faulty = 0;
  for (std::size_t k = 0; k < a.rows(); ++k) {
    const bool on = k >= 2000 && k < 5000;
    faulty += on;
    ASSERT_NEAR(b["rf_foot/force_N"][k] - a["rf_foot/force_N"][k], on ? 25.0 : 0.0, 1e-9) << k;
    ASSERT_EQ(b["truth/rf_foot/fault"][k], on ? ftsense::fault_code(ftsense::FaultType::offset) : 0.0) << k;
  }
  EXPECT_EQ(faulty, 3000);
}

TEST(QuadrupedLog, ColumnsInOrder) {
  const auto c = quadruped_log_columns();
  EXPECT_EQ(c.size(), 1u + 4 + 6 + 4 + 12 + 3 + 2 + 4 + 4 + 4 + 12 + 3 + 2 + 4);
  EXPECT_EQ(c[1], "lf_foot/force_N");
  EXPECT_EQ(c[4], "rh_foot/force_N");
  EXPECT_EQ(c[11], "base/quat_w");
  EXPECT_EQ(c[14], "base/quat_z");
  EXPECT_EQ(c[15], "joint_pos/lf_hip_abd_rad");
  EXPECT_EQ(c[17], "joint_pos/lf_knee_rad");
  EXPECT_NE(std::find(c.begin(), c.end(), "truth/lh_foot/contact"), c.end());
  EXPECT_NE(std::find(c.begin(), c.end(), "plan/contact_rf"), c.end());
  EXPECT_EQ(c.back(), "truth/rh_foot/fault");
}

TEST(QuadrupedScenario, DefaultsAndShippedFiles) {
  const Scenario s = parse_scenario(json::parse(R"({"robot": "quadruped", "duration_s": 10, "faults": []})"));
  EXPECT_EQ(s.robot_kind, RobotKind::quadruped);
  EXPECT_EQ(s.crawl.stride_m, CrawlParams{}.stride_m);
  EXPECT_EQ(s.sensors.force_noise_std_N, kQuadrupedForceNoiseStdN);
  EXPECT_EQ(parse_scenario(json::parse(R"({"duration_s": 10, "gait": {"step_length_m": 0.15, "step_time_s": 1.0,
      "double_support_ratio": 0.2}, "faults": []})")).robot_kind, RobotKind::suralp);
  const Scenario c = load_scenario(kScenarioDir / "quadruped_clean.json");
  EXPECT_TRUE(c.faults.empty());
  EXPECT_GE(c.duration_s, 30.0);
  const Scenario f = load_scenario(kScenarioDir / "quadruped_faults.json");
  EXPECT_GE(f.duration_s, 30.0);
  const CrawlPlan plan(f.crawl, f.quadruped.hip_x_m, f.quadruped.foot_radius_m, f.duration_s);
  std::set<ftsense::FaultType> types;
  for (std::size_t i = 0; i < f.faults.size(); ++i) {
    const FaultSpec& a = f.faults[i];
    types.insert(a.type);
    EXPECT_GT(a.start_s, f.crawl.initial_stand_s) << i;  // onsets while the walk is under way
    EXPECT_LT(a.start_s, plan.walk_end_s()) << i;
    for (std::size_t j = 0; j < i; ++j) {  // distinct channels, or apart in time
      if (f.faults[j].channel == a.channel) {
        EXPECT_TRUE(f.faults[j].end_s && *f.faults[j].end_s < a.start_s) << i << " " << j;
      }
    }
    if (a.type == ftsense::FaultType::offset) {
      EXPECT_NEAR(a.offset_N / (13.0 * 9.806), 0.2, 0.02);
    }
    if (a.type == ftsense::FaultType::gain) {
      EXPECT_EQ(a.gain, 1.5);
      EXPECT_TRUE(a.end_s.has_value());
    }
  }
  using ftsense::FaultType;
  EXPECT_EQ(types, (std::set<FaultType>{FaultType::offset, FaultType::drift, FaultType::frozen, FaultType::gain,
                                        FaultType::noise}));
}

TEST(QuadrupedScenario, ProblemsNameTheirJsonPointer) {
  const auto p = problems_of(json::parse(R"({"robot": "quadruped", "duration_s": 10,
      "gait": {"stride_m": 0.5, "step_length_m": 0.15, "cycle_s": "x"},
      "faults": [{"channel": "l_foot/p1", "type": "offset", "start_s": 1, "offset_N": 5}]})"));
  const auto has = [&](const std::string& m) { return std::find(p.begin(), p.end(), m) != p.end(); };
  EXPECT_TRUE(has("/gait/stride_m = 0.5 is out of range, expected >= 0 and <= 0.15")) << ScenarioError(p).what();
  EXPECT_TRUE(has("/gait/cycle_s = \"x\" has type string, expected number")) << ScenarioError(p).what();
  EXPECT_TRUE(has("/faults/0/channel = \"l_foot/p1\" is not one of: lf_foot, rf_foot, lh_foot, rh_foot"))
      << ScenarioError(p).what();
  bool unknown = false;
  for (const auto& m : p) unknown = unknown || m.rfind("/gait/step_length_m = 0.15 is not a known key", 0) == 0;
  EXPECT_TRUE(unknown) << ScenarioError(p).what();
  EXPECT_EQ(p.size(), 4u) << ScenarioError(p).what();
  const auto r = problems_of(json::parse(R"({"robot": "hexapod", "duration_s": 10, "faults": []})"));
  ASSERT_EQ(r.size(), 1u) << ScenarioError(r).what();
  EXPECT_EQ(r[0], "/robot = \"hexapod\" is not one of: suralp, quadruped");
  // The biped keeps its channels: a quadruped channel is an error there.
  const auto b = problems_of(json::parse(R"({"duration_s": 10, "gait": {"step_length_m": 0.15, "step_time_s": 1.0,
      "double_support_ratio": 0.2}, "faults": [{"channel": "lf_foot", "type": "invalid", "start_s": 1}]})"));
  ASSERT_EQ(b.size(), 1u) << ScenarioError(b).what();
  EXPECT_EQ(b[0].rfind("/faults/0/channel = \"lf_foot\" is not one of: l_foot/p1", 0), 0u) << b[0];
}

// Golden data: configs/quadruped/quadruped.urdf was written by
//   ftsense-sim --write-urdf configs/quadruped/quadruped.urdf --robot quadruped
TEST(QuadrupedUrdf, CommittedFileIsTheGeneratedOne) {
  const std::string committed = read(kUrdf);
  ASSERT_FALSE(committed.empty()) << kUrdf;
  EXPECT_EQ(quadruped_urdf(), committed);
  const fs::path out = fs::temp_directory_path() / ("ftsense_sim_" + std::to_string(::getpid()) + "_quadruped.urdf");
  const std::string cmd = std::string("\"") + FTSENSE_SIM_CLI + "\" --write-urdf \"" + out.string() + "\" --robot quadruped";
  const int raw = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << cmd;
  EXPECT_EQ(read(out), committed);
  fs::remove(out);
  const std::string bad = std::string("\"") + FTSENSE_SIM_CLI + "\" --write-urdf x.urdf --robot suralp 2> /dev/null";
  const int raw_bad = std::system(bad.c_str());
  EXPECT_TRUE(WIFEXITED(raw_bad) && WEXITSTATUS(raw_bad) == 2);
}

TEST(QuadrupedUrdf, SameKinematicsAndMassesAsTheSimulatedModel) {
  namespace rm = ftsense::robot_model;
  const QuadrupedParams qp;
  const rm::KinematicTree tree = rm::KinematicTree::from_urdf_file(kUrdf);
  EXPECT_NEAR(tree.total_mass_kg(), 13.0, 1e-12);
  const auto trunk = tree.find_link("trunk");
  ASSERT_TRUE(trunk.has_value());
  std::vector<std::optional<std::size_t>> sources(tree.joints().size());
  for (std::size_t j = 0; j < 12; ++j) {
    const auto id = tree.find_joint(kQuadrupedJointNames[j]);
    ASSERT_TRUE(id.has_value()) << kQuadrupedJointNames[j];
    sources[*id] = j;
  }
  std::vector<std::size_t> frames;
  for (std::size_t i = 0; i < 4; ++i) frames.push_back(*tree.find_link(leg(i) + "_foot"));
  frames.push_back(*tree.find_link("imu"));
  rm::ForwardKinematics fk(tree, *trunk, sources, frames);

  MjModelPtr m = load_mjcf_string(quadruped_mjcf(qp));
  MjDataPtr d(mj_makeData(m.get()));
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::array<double, 12> q{};
    for (double& x : q) x = u(rng);
    mju_zero(d->qpos, m->nq);
    d->qpos[2] = 0.3;
    d->qpos[3] = 1.0;
    for (std::size_t j = 0; j < 12; ++j)
      d->qpos[m->jnt_qposadr[require_id(m.get(), mjOBJ_JOINT, std::string(kQuadrupedJointNames[j]).c_str())]] = q[j];
    mj_kinematics(m.get(), d.get());
    mj_comPos(m.get(), d.get());
    rm::RigidPose base;
    base.translation = Eigen::Vector3d(0.0, 0.0, 0.3);
    fk.compute(base, q);
    for (std::size_t i = 0; i < 4; ++i) {
      const int b = require_id(m.get(), mjOBJ_BODY, (leg(i) + "_foot").c_str());
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(fk.frame_pose(i).translation[k], d->xpos[3 * b + k], 1e-12) << leg(i);
    }
    const int imu = require_id(m.get(), mjOBJ_SITE, "imu");
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(fk.frame_pose(4).translation[k], d->site_xpos[3 * imu + k], 1e-12);
    const int tb = require_id(m.get(), mjOBJ_BODY, "trunk");
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(fk.com_world()[k], d->subtree_com[3 * tb + k], 1e-12);
  }
}
