#pragma once
// The plugin set the `ftsense` program and the shipped configs use: every family in plugins/.
// Extend it with your own plugins without editing ftsense:
//
//   using my_plugins = ftsense::reference_plugins::with<MyVirtualSensor>;

#include "ftsense/biped/biped_plugins.hpp"
#include "ftsense/generic/generic_plugins.hpp"
#include "ftsense/robot_model/robot_model_plugins.hpp"

namespace ftsense {

using reference_plugins =
    merge_plugin_sets<merge_plugin_sets<generic::generic_plugins, biped::biped_plugins>,
                      robot_model::robot_model_plugins>;

}  // namespace ftsense
