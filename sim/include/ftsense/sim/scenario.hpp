#pragma once
// Simulation scenario: duration, gait, sensor noise and injected force-sensor faults.
// Loading is strict: unknown keys, missing required keys, wrong types and out-of-range values are
// all collected and thrown together as one ScenarioError, each message starting with the JSON
// Pointer of the offending value. The keys are documented in sim/README.md.
#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "ftsense/sim/crawl_gait.hpp"
#include "ftsense/sim/gait_plan.hpp"
#include "ftsense/sim/quadruped_model.hpp"
#include "ftsense/sim/robot_model.hpp"
#include "ftsense/sim/sensor_models.hpp"

namespace ftsense::sim {

/// The simulated robots; the scenario key "robot" names one (kRobotKindNames, by enumerator value).
enum class RobotKind { suralp = 0, quadruped = 1 };
inline constexpr std::array<std::string_view, 2> kRobotKindNames = {"suralp", "quadruped"};

struct Scenario {
  std::string name;
  std::string description;
  double duration_s = 30.0;
  /// Period of the logged rows (the sensors' sample period): a multiple of the simulation tick;
  /// absent: every tick.
  std::optional<double> log_period_s;
  std::uint64_t seed = 1;  ///< default seed; a command-line --seed overrides it
  RobotKind robot_kind = RobotKind::suralp;  ///< "robot"; decides how "gait" and the channels read
  GaitParams gait;    ///< "gait" of the biped
  CrawlParams crawl;  ///< "gait" of the quadruped
  SensorParams sensors;
  std::vector<FaultSpec> faults;
  RobotParams robot;  ///< "body" of the biped: its size and mass; absent: the paper's robot
  QuadrupedParams quadruped;  ///< not read from JSON
};

/// Every problem found in a scenario; what() joins them with newlines.
class ScenarioError : public std::runtime_error {
 public:
  explicit ScenarioError(std::vector<std::string> problems);
  [[nodiscard]] const std::vector<std::string>& problems() const noexcept { return problems_; }

 private:
  std::vector<std::string> problems_;
};

[[nodiscard]] Scenario parse_scenario(const nlohmann::json& doc);
/// Reads a scenario-style "faults" array (the keys of sim/README.md) whose "channel" names one of
/// `channels` (FaultSpec::channel is its index there), with start and end times in [0, duration_s].
/// Problems, faults overlapping in time on one channel included, are appended to `errors`, each
/// starting with its JSON Pointer under `path`.
[[nodiscard]] std::vector<FaultSpec> parse_faults(const nlohmann::json& faults, const std::string& path,
                                                  const std::vector<std::string_view>& channels,
                                                  double duration_s, std::vector<std::string>& errors);
/// Parses JSON text; syntax errors are reported as a ScenarioError too.
[[nodiscard]] Scenario parse_scenario_text(const std::string& text);
[[nodiscard]] Scenario load_scenario(const std::filesystem::path& path);

}  // namespace ftsense::sim
