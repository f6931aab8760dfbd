#pragma once
// The directory of the simulator's scenario files (configs/scenarios), for the simulator's tests.
#include <filesystem>

namespace ftsense::sim::testing {

inline const std::filesystem::path kScenarioDir = FTSENSE_SIM_SCENARIO_DIR;

}  // namespace ftsense::sim::testing
