#pragma once
// The plugin set of this example: ftsense's reference plugins plus the insole virtual sensor,
// added without editing ftsense.

// [snippet:plugin_set]
#include "ftsense/reference_plugins.hpp"
#include "insole/insole_virtual_sensor.hpp"

namespace insole {

using plugins = ftsense::reference_plugins::with<InsoleVirtualSensor>;

}  // namespace insole
// [end-snippet]
