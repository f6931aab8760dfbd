#pragma once
// The robot-model family (a robot described by a URDF) as one plugin set.

#include "ftsense/plugin_set.hpp"
#include "ftsense/robot_model/urdf_kinematics.hpp"

namespace ftsense::robot_model {

using robot_model_plugins = PluginSet<UrdfKinematics>;

}  // namespace ftsense::robot_model
