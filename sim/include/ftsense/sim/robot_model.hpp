#pragma once
// SURALP-like 12-DOF biped: parameters and the MJCF text generated from them.
//
// Geometry (paper Table I): upper leg A = 0.280 m, lower leg B = 0.270 m, ankle above sole
// h_s = 0.124 m, foot 0.240 m x 0.150 m, total mass 114 kg. Each leg: hip yaw (z), hip roll (x),
// hip pitch (y) with intersecting axes at the hip point; knee pitch (y); ankle pitch (y) and
// ankle roll (x) intersecting at the ankle point. All joint angles are zero with the leg straight
// and the foot flat; positive angles follow the right-hand rule about the body axes.
//
// Foot frame: origin on the sole plane directly under the ankle, x forward, y left. The sole is
// centred under the ankle. The foot touches the ground only through four small sphere pads whose
// lowest points lie on the sole plane at the sole corners:
//   p1 = (+0.12, +0.075), p2 = (+0.12, -0.075), p3 = (-0.12, +0.075), p4 = (-0.12, -0.075).
// One sphere-plane pair gives exactly one contact, so each pad is one force channel.
#include <array>
#include <string>
#include <string_view>

namespace ftsense::sim {

/// Physical and servo parameters of the model. Defaults reproduce Table I of the paper.
struct RobotParams {
  double upper_leg_m = 0.280;   ///< hip to knee, A
  double lower_leg_m = 0.270;   ///< knee to ankle, B
  double sole_ankle_m = 0.124;  ///< ankle point above the sole plane, h_s
  double foot_length_m = 0.240;
  double foot_width_m = 0.150;
  double hip_half_width_m = 0.100;  ///< lateral offset of each hip point from the pelvis origin
  double total_mass_kg = 114.0;
  // Mass per leg segment (kg); the trunk gets the rest of total_mass_kg.
  double hip_yaw_link_kg = 1.0;
  double hip_roll_link_kg = 1.0;
  double thigh_kg = 6.5;
  double shank_kg = 4.0;
  double ankle_link_kg = 0.5;
  double foot_kg = 2.8;  ///< foot plate, without pads
  double pad_kg = 0.05;  ///< each of the 4 pads
  double trunk_com_height_m = 0.25;  ///< trunk CoM above the pelvis origin
  double imu_height_m = 0.15;        ///< IMU site above the pelvis origin (trunk frame)
  double pad_radius_m = 0.01;
  // Contact: MuJoCo solref (time constant, damping ratio) and friction.
  double contact_timeconst_s = 0.005;
  double contact_dampratio = 2.0;  // overdamped: no pad rattle after touchdown
  double friction = 1.0;
  // Joint position servos, run by the simulator at 1 kHz on motor (torque) actuators:
  //   torque = kp (q_ref - q) - damping qdot
  // The damping is MuJoCo joint damping (integrated implicitly by the Euler integrator); the
  // reflected rotor inertia of the geared drives is the joint armature.
  double servo_kp_Nm_rad = 50000.0;
  double ankle_kp_scale = 1.0;  ///< ankle servos use ankle_kp_scale * servo_kp_Nm_rad
  double joint_damping_Nms_rad = 1000.0;
  double joint_armature_kgm2 = 0.5;  // reflected rotor inertia of geared drives
  double timestep_s = 0.001;
  double gravity_m_s2 = 9.806;

  /// Mass of the trunk body so that the whole robot weighs total_mass_kg.
  [[nodiscard]] double trunk_kg() const;
};

/// The 12 joints in log/actuator order, left leg first.
inline constexpr std::array<std::string_view, 12> kJointNames = {
    "l_hip_yaw", "l_hip_roll", "l_hip_pitch", "l_knee", "l_ankle_pitch", "l_ankle_roll",
    "r_hip_yaw", "r_hip_roll", "r_hip_pitch", "r_knee", "r_ankle_pitch", "r_ankle_roll"};

/// Pad (x, y) in the foot frame for pad index 0..3 (p1..p4), per the numbering above.
[[nodiscard]] std::array<double, 2> pad_position(const RobotParams& p, int pad);

/// MJCF text of the robot on a flat floor. Body names: "trunk" (free joint), "l_foot"/"r_foot"
/// (ankle-roll bodies); sites "imu", "l_sole", "r_sole"; pad geoms "l_pad1".."r_pad4";
/// sensors "imu_acc", "imu_gyro", touch sensors "l_pad1_touch".."r_pad4_touch" (on sites named
/// like the pads, an independent check of the pad forces); one motor (torque) actuator per
/// joint, named like the joint.
[[nodiscard]] std::string suralp_mjcf(const RobotParams& p = {});

}  // namespace ftsense::sim
