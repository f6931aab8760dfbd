#pragma once
// The robot-model family (a robot described by a URDF; legged robots' feet) as one plugin set.

#include "ftsense/plugin_set.hpp"
#include "ftsense/robot_model/contact_from_foot_height.hpp"
#include "ftsense/robot_model/contact_point_height.hpp"
#include "ftsense/robot_model/urdf_kinematics.hpp"

namespace ftsense::robot_model {

using robot_model_plugins = PluginSet<UrdfKinematics, ContactFromFootHeight, ContactPointHeight>;

}  // namespace ftsense::robot_model
