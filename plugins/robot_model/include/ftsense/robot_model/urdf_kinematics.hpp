#pragma once
// Forward kinematics of a robot described by a URDF: CoM, foot frames, IMU orientation and a
// kinematic contact state, from the base pose and the joint encoders. Any number of feet (a
// biped's two soles, a quadruped's four point feet, a hexapod's six).
//
// Inputs: the world pose of `base_link` (p_WB [m], roll-pitch-yaw of R_WB [rad] with
// R = Rz(yaw) Ry(pitch) Rx(roll)) and the positions q of the joints listed in `joints`, in that
// order [rad; m for prismatic joints]. Joints listed in `held_joints` are held at q = 0.
// The maths of the tree is in kinematic_tree.hpp:
//
//   T_WL = T_WB * prod_{joints B -> L} T_PC(q)^(+-1),    c_W = sum_L m_L (R_WL c_L + p_WL) / M
//
// Outputs, world frame (z up), n = len(foot_links) feet in the order of `foot_links`:
//   com          c_W [m], from the URDF's link masses (M = sum m_L, output `mass` [kg])
//   foot_pos     p_W of each foot link [m], stacked (x, y, z) foot after foot (3 n values);
//   foot_rpy     its roll, pitch, yaw [rad], stacked alike
//   imu_rpy      roll, pitch, yaw of R_W,IMU = R_WB R_B,IMU [rad]: the IMU frame is not the base
//                frame, and a virtual force sensor rotating the IMU's specific force needs this one
//   foot_height  h_i = min_l (p_W,i + R_W,i [x_l, y_l, 0])_z - g over the contact points
//                (x_l, y_l) of `foot_points_m` (foot frame, every foot alike: a sole outline,
//                which a URDF with mesh-only feet lacks), or of the foot origin when none (point
//                feet) [m]. The ground g is `ground_height_m` (ground_reference = plane) or the
//                lowest point of all feet (ground_reference = lowest_foot: walking on flat
//                ground, a foot is always down; immune to a drifting world height of the base
//                estimate)
//   contact      per foot, 1 when h_i < contact_height_m, else 0: a contact state from
//                kinematics, independent of the force sensors
//
// The URDF path is resolved against the config file's directory (StageContext::resolve_path).
// A missing or unparsable URDF, an unknown link or joint name, or a movable joint the kinematics
// needs that is neither read nor held is a ConfigError with the parameter's JSON Pointer.
// Parsing and the tree walk's plan happen in the constructor; step() does not allocate.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"
#include "ftsense/robot_model/kinematic_tree.hpp"

namespace ftsense::robot_model {

class UrdfKinematics {
 public:
  static constexpr std::string_view name = "urdf_kinematics";
  static constexpr std::string_view summary =
      "URDF forward kinematics: CoM, foot poses, IMU orientation and kinematic contact from base pose and joints";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"({"urdf": "model.urdf", "joints": ["l_hip_pitch", "l_knee", "l_ankle_pitch", "r_hip_pitch", "r_knee", "r_ankle_pitch"],
       "base_link": "root_link", "imu_link": "root_link_imu_frame", "foot_links": ["l_sole", "r_sole"]})";

  struct Params {
    std::string urdf;
    std::vector<std::string> joints;
    std::vector<std::string> held_joints;
    std::string base_link;
    std::string imu_link;
    std::vector<std::string> foot_links;
    std::vector<std::array<double, 2>> foot_points_m;
    enum class GroundReference { plane, lowest_foot };
    GroundReference ground_reference = GroundReference::plane;
    double ground_height_m = 0.0;
    double contact_height_m = 0.01;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kBasePos, kBaseRpy, kJointPositions };
  enum Output : std::size_t {
    kCom, kFootPos, kFootRpy, kImuRpy, kFootHeight, kContact, kMass
  };

  UrdfKinematics(const Params& params, const StageContext& context);
  // The ports, without reading the URDF (the config reference lists them without one).
  [[nodiscard]] static Ports declare_ports(const Params& params);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  static constexpr std::size_t kImuFrame = 0;  // then the feet, frame 1 + i for foot i
  Ports ports_;
  Params params_;
  std::optional<ForwardKinematics> kinematics_;
};

}  // namespace ftsense::robot_model
