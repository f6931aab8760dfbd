#pragma once
// Simulation scenario: duration, gait, sensor noise and injected force-sensor faults.
// Loading is strict: unknown keys, missing required keys, wrong types and out-of-range values are
// all collected and thrown together as one ScenarioError, each message starting with the JSON
// Pointer of the offending value. The keys are documented in sim/README.md.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "ftsense/sim/gait_plan.hpp"
#include "ftsense/sim/robot_model.hpp"
#include "ftsense/sim/sensor_models.hpp"

namespace ftsense::sim {

struct Scenario {
  std::string name;
  std::string description;
  double duration_s = 30.0;
  std::uint64_t seed = 1;  ///< default seed; a command-line --seed overrides it
  GaitParams gait;
  SensorParams sensors;
  std::vector<FaultSpec> faults;
  RobotParams robot;  ///< not read from JSON: the paper's robot
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
/// Parses JSON text; syntax errors are reported as a ScenarioError too.
[[nodiscard]] Scenario parse_scenario_text(const std::string& text);
[[nodiscard]] Scenario load_scenario(const std::filesystem::path& path);

}  // namespace ftsense::sim
