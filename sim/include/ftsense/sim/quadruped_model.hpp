#pragma once
// A 13 kg, 12-DOF quadruped: parameters, link inertias and the MJCF text generated from them.
//
// Trunk: a box (length x width x height) whose centre is the trunk frame origin, x forward,
// y left, z up. Legs, in this order: lf (left front), rf, lh (left hind), rh. Hip point of leg i
// at (+-hip_x_m, +-hip_y_m, 0) in the trunk frame (front +, left +). Each leg:
//   hip abduction (x) at the hip point -> hip link
//   hip flexion (y), same point      -> thigh, thigh_m long down its -z axis
//   knee (y) at the thigh's end      -> shank, shank_m long down its -z axis
//   foot: a sphere of foot_radius_m centred at the shank's end (welded, no joint).
// All angles zero: legs straight down. Positive angles follow the right-hand rule about the
// trunk's axes; the knees bend backward (knee angle < 0, like most electric quadrupeds), see
// quadruped_leg_kinematics.hpp.
// One sphere-plane pair gives exactly one contact, so each foot is one force channel; its true
// normal force is the contact-frame normal component of mj_contactForce.
// Units: m, kg, kg m^2, N m/rad, N m s/rad, s.
#include <array>
#include <string>
#include <string_view>

namespace ftsense::sim {

/// Physical and servo parameters of the quadruped.
struct QuadrupedParams {
  double trunk_length_m = 0.45;
  double trunk_width_m = 0.20;
  double trunk_height_m = 0.10;
  double hip_x_m = 0.19;  ///< hip points at x = +-hip_x_m (front +)
  double hip_y_m = 0.10;  ///< hip points at y = +-hip_y_m (left +): the trunk's side faces
  double thigh_m = 0.20;  ///< hip to knee
  double shank_m = 0.20;  ///< knee to the foot sphere's centre
  double foot_radius_m = 0.02;
  double total_mass_kg = 13.0;
  // Mass per leg link (kg); the trunk gets the rest of total_mass_kg (9 kg with these).
  double hip_link_kg = 0.35;  ///< abduction drive and bracket
  double thigh_kg = 0.45;     ///< flexion and knee drives sit here
  double shank_kg = 0.15;
  double foot_kg = 0.05;
  // Shapes for the inertias (and MuJoCo's drawing): the hip link a sphere, the thigh and shank
  // solid cylinders along their axes.
  double hip_link_radius_m = 0.04;
  double thigh_radius_m = 0.025;
  double shank_radius_m = 0.012;
  double imu_height_m = 0.03;  ///< IMU site above the trunk centre (trunk frame)
  // Contact: MuJoCo solref (time constant, damping ratio) and friction.
  double contact_timeconst_s = 0.005;
  double contact_dampratio = 2.0;  // overdamped: the foot does not bounce at touchdown
  double friction = 1.0;
  // Joint position servos on motor (torque) actuators at 1 kHz:
  //   torque = clamp(kp (q_ref - q), +-max_torque) - damping qdot
  // The damping is MuJoCo joint damping (implicit in the Euler integrator); the reflected rotor
  // inertia of the geared drives is the joint armature.
  double servo_kp_Nm_rad = 1000.0;
  double joint_damping_Nms_rad = 20.0;
  double joint_armature_kgm2 = 0.02;
  double max_torque_Nm = 40.0;
  double max_velocity_rad_s = 20.0;  ///< written to the URDF's limits; not enforced in simulation
  // Joint ranges (rad), the same in MuJoCo and the URDF.
  std::array<double, 2> abd_range_rad = {-0.8, 0.8};
  std::array<double, 2> flex_range_rad = {-1.5, 2.5};
  std::array<double, 2> knee_range_rad = {-2.7, -0.1};
  double timestep_s = 0.001;
  double gravity_m_s2 = 9.806;

  /// Mass of the trunk so that the whole robot weighs total_mass_kg.
  [[nodiscard]] double trunk_kg() const;
};

inline constexpr int kQuadrupedLegCount = 4;
/// Legs in log/actuator order.
inline constexpr std::array<std::string_view, 4> kQuadrupedLegs = {"lf", "rf", "lh", "rh"};
/// The 12 joints in log/actuator order: per leg (kQuadrupedLegs order) abduction, flexion, knee.
inline constexpr std::array<std::string_view, 12> kQuadrupedJointNames = {
    "lf_hip_abd", "lf_hip_flex", "lf_knee", "rf_hip_abd", "rf_hip_flex", "rf_knee",
    "lh_hip_abd", "lh_hip_flex", "lh_knee", "rh_hip_abd", "rh_hip_flex", "rh_knee"};

/// Hip point of leg 0..3 (kQuadrupedLegs order) in the trunk frame.
[[nodiscard]] std::array<double, 3> quadruped_hip_point(const QuadrupedParams& p, int leg);

/// Mass, centre of mass and principal moments (about the CoM, along the link frame's axes) of
/// one link; the link frame is the frame of the joint that moves it (the foot: the sphere's
/// centre). Used by both the MJCF and the URDF, so the two describe the same bodies.
struct LinkInertial {
  double mass_kg = 0.0;
  std::array<double, 3> com_m{};
  std::array<double, 3> inertia_kgm2{};  ///< Ixx, Iyy, Izz; products are zero
};
struct QuadrupedInertials {
  LinkInertial trunk, hip, thigh, shank, foot;
};
[[nodiscard]] QuadrupedInertials quadruped_inertials(const QuadrupedParams& p);

/// MJCF text of the quadruped on a flat floor, standing with straight legs (feet on the floor).
/// Bodies "trunk" (free joint "root"), "<leg>_hip", "<leg>_thigh", "<leg>_shank", "<leg>_foot";
/// foot geoms "<leg>_foot" (the only geoms that collide, with the floor); site "imu"; sensors
/// "imu_acc", "imu_gyro"; one motor actuator per joint, named like the joint.
[[nodiscard]] std::string quadruped_mjcf(const QuadrupedParams& p = {});

}  // namespace ftsense::sim
