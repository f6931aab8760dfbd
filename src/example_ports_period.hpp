#pragma once
// Private to the generated references (config_reference.cpp, config_schema.cpp).

namespace ftsense {

// The tick period [s] the generated references build example stages with to list their ports
// (PluginInfo::example_ports); ports rarely depend on it.
inline constexpr double kExamplePortsSamplePeriodS = 0.001;

}  // namespace ftsense
