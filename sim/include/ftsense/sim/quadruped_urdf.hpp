#pragma once
// The quadruped as a URDF for ftsense's robot-model stages, generated from the same
// QuadrupedParams (and the same link inertias, quadruped_inertials) as the simulated MJCF.
//
// Links: trunk (the URDF root; its origin is the trunk box centre, the free joint's frame in
// MuJoCo), imu (fixed, at the IMU site), per leg <leg>_hip, <leg>_thigh, <leg>_shank (moved by
// <leg>_hip_abd, <leg>_hip_flex, <leg>_knee, axes and limits as in MuJoCo) and <leg>_foot (fixed
// at the shank's end: the foot sphere's CENTRE, not its lowest point, so the foot frame's height
// above the ground is radius + clearance whatever the shank's angle; it carries the sphere as
// its collision geometry). Joint limits: the MuJoCo ranges, effort max_torque_Nm, velocity
// max_velocity_rad_s; dynamics damping joint_damping_Nms_rad (URDF has no armature).
// Numbers are written shortest round-trip, so the text is a function of the parameters only.
#include <string>

#include "ftsense/sim/quadruped_model.hpp"

namespace ftsense::sim {

/// URDF text of the quadruped; the command writing it is named in its header comment.
[[nodiscard]] std::string quadruped_urdf(const QuadrupedParams& p = {});

}  // namespace ftsense::sim
