#pragma once
// The walking simulation: MuJoCo physics of the SURALP-like model, the open-loop walking
// controller (ZMP preview control -> multibody CoM correction -> analytic leg IK -> joint position
// servos), sensor models and fault injection, written as a CSV log (see sim/README.md). A scenario
// with "robot": "quadruped" runs the quadruped's static crawl instead (simulate_quadruped).
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "ftsense/sim/scenario.hpp"

namespace ftsense::sim {

struct SimulationOptions {
  /// Called about every progress_interval_s of simulated time with (t, duration).
  std::function<void(double, double)> progress;
  double progress_interval_s = 1.0;
  /// Fall detection: the run stops when the pelvis height or the trunk tilt leaves these limits.
  double min_torso_height_m = 0.35;
  double max_torso_tilt_rad = 0.6;
  /// The quadruped's height limit (trunk centre; it stands at 0.30 m), with max_torso_tilt_rad.
  double min_quadruped_torso_height_m = 0.15;
  /// Standing time simulated (not logged) before t = 0 so the log starts settled on the pads.
  double settle_s = 0.5;
  /// A foot is in (true) contact when its pads carry more than this total normal force.
  double contact_threshold_N = 1.0;
};

struct SimulationSummary {
  bool fell = false;
  double fall_time_s = std::numeric_limits<double>::quiet_NaN();
  std::string message;            ///< human-readable outcome
  std::int64_t ticks = 0;         ///< rows written
  double simulated_s = 0.0;
  double cpu_s = 0.0;             ///< process CPU time spent in simulate()
  double total_mass_kg = 0.0;
  double gravity_m_s2 = 0.0;
  double lipm_com_height_m = 0.0; ///< z_c used by the preview controller
  int num_steps = 0;
  /// Mean of (sum of true pad forces) / (m g) over the initial standing phase.
  double quiet_stance_force_ratio = std::numeric_limits<double>::quiet_NaN();
  double zmp_error_rms_m = 0.0, zmp_error_max_m = 0.0;  ///< true ZMP vs planned ZMP
  double zmp_error_ss_rms_m = 0.0, zmp_error_ss_max_m = 0.0;  ///< the same, single support only
  double com_error_rms_m = 0.0, com_error_max_m = 0.0;  ///< true CoM (xy) vs planned CoM
  double min_torso_height_m = std::numeric_limits<double>::infinity();
  double max_torso_tilt_rad = 0.0;
  std::vector<std::string> foot_names;  ///< biped: l_foot, r_foot; quadruped: kQuadrupedForceChannels
  std::vector<int> liftoffs;    ///< per foot (foot_names order), from the true contact state
  std::vector<int> touchdowns;
  int ik_unreachable_ticks = 0;
  /// Quadruped: smallest planned distance of the CoM from the support triangle's edges in swing.
  double planned_stability_margin_m = std::numeric_limits<double>::quiet_NaN();
};

/// The names of the CSV columns, in order (first is time_s).
[[nodiscard]] std::vector<std::string> log_columns();
/// The same for the quadruped's log (sim/README.md, "Quadruped").
[[nodiscard]] std::vector<std::string> quadruped_log_columns();

/// Runs the scenario with the given seed and writes the CSV log to `csv`.
/// Throws ModelError on an internal model problem; a fall is reported in the summary
/// (fell = true, the log ends at the fall).
SimulationSummary simulate(const Scenario& scenario, std::uint64_t seed, std::ostream& csv,
                           const SimulationOptions& options = {});

/// The quadruped crawling (static crawl, joint position servos); simulate() calls it for
/// robot_kind quadruped.
SimulationSummary simulate_quadruped(const Scenario& scenario, std::uint64_t seed, std::ostream& csv,
                                     const SimulationOptions& options = {});

}  // namespace ftsense::sim
