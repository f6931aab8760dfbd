#pragma once
// A robot's kinematic tree read from a URDF, and its forward kinematics from a chosen base link.
//
// Frames and units: SI (m, kg, rad). A pose T = (R, p) maps coordinates in a child frame to its
// parent frame: x_parent = R x_child + p. A URDF joint j between parent link P and child link C
// with origin T_PJ and axis a (unit, joint frame) gives
//
//   T_PC(q) = T_PJ * M_j(q),   M_j(q) = (Rot(a, q), 0)   revolute, continuous [q in rad]
//                              M_j(q) = (I, a q)          prismatic             [q in m]
//                              M_j    = identity          fixed
//
// The tree is walked from the base link B outwards (against a joint's direction where the base
// is not the URDF root: T_CP = T_PC^-1 = (R^T, -R^T p), no matrix inverse), so for every link L
//
//   T_WL = T_WB * prod over the joints on the path B -> L of T_PC(q_j)^(+-1)
//
// and the centre of mass of the whole robot, with m_L and c_L the link's mass and CoM offset
// (URDF <inertial>, link frame), is
//
//   M = sum_L m_L,   c_W = (1 / M) sum_L m_L (R_WL c_L + p_WL)                       [kg, m]
//
// Floating and planar joints are not supported (they are reported when they lie on a path the
// kinematics needs); mimic relations are ignored (list such joints as read or held).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace ftsense::robot_model {

// A rigid transform child -> parent.
struct RigidPose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  [[nodiscard]] RigidPose operator*(const RigidPose& child) const noexcept {
    return {rotation * child.rotation, rotation * child.translation + translation};
  }
  [[nodiscard]] RigidPose inverse() const noexcept {
    return {rotation.transpose(), -(rotation.transpose() * translation)};
  }
};

enum class JointType { fixed, revolute, continuous, prismatic, floating, planar };

// A URDF that cannot be read or is not a tree ftsense can use; what() says why.
class UrdfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class KinematicTree {
 public:
  struct Link {
    std::string name;
    double mass_kg = 0.0;
    Eigen::Vector3d com_in_link_m = Eigen::Vector3d::Zero();
    std::optional<std::size_t> parent_joint;  // none for the URDF root
  };
  struct Joint {
    std::string name;
    JointType type = JointType::fixed;
    std::size_t parent_link = 0;
    std::size_t child_link = 0;
    RigidPose origin;                          // T_PJ
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    [[nodiscard]] bool movable() const noexcept {
      return type == JointType::revolute || type == JointType::continuous || type == JointType::prismatic;
    }
    // T_PC(q) = T_PJ * M_j(q).
    [[nodiscard]] RigidPose transform(double q) const noexcept;
  };

  // Throws UrdfError naming the file and urdfdom's first complaint. While parsing, urdfdom's
  // console_bridge output handler (process-global) is replaced to capture that complaint: do not
  // parse URDFs on two threads at once.
  [[nodiscard]] static KinematicTree from_urdf_file(const std::filesystem::path& path);
  [[nodiscard]] static KinematicTree from_urdf_text(const std::string& xml, std::string_view source_name);

  [[nodiscard]] const std::vector<Link>& links() const noexcept { return links_; }
  [[nodiscard]] const std::vector<Joint>& joints() const noexcept { return joints_; }
  [[nodiscard]] std::optional<std::size_t> find_link(std::string_view name) const noexcept;
  [[nodiscard]] std::optional<std::size_t> find_joint(std::string_view name) const noexcept;
  [[nodiscard]] std::vector<std::string> link_names() const;
  [[nodiscard]] std::vector<std::string> joint_names() const;
  [[nodiscard]] std::vector<std::string> movable_joint_names() const;
  [[nodiscard]] double total_mass_kg() const noexcept;
  // The joints on the tree path between two links, in walking order from `from`.
  [[nodiscard]] std::vector<std::size_t> path_joints(std::size_t from, std::size_t to) const;

 private:
  std::vector<Link> links_;
  std::vector<Joint> joints_;
};

// Forward kinematics of a tree from a base link whose world pose is given, for the links with
// mass (the CoM) and a list of wanted frames. Built once (allocates); compute() does not.
class ForwardKinematics {
 public:
  // Where each joint's position comes from: an index into the q vector given to compute(), or
  // nothing (held at q = 0). Precondition (checked, std::invalid_argument): one entry per joint,
  // and no floating or planar joint on a needed path. Callers decide which joints may be held.
  ForwardKinematics(const KinematicTree& tree, std::size_t base_link,
                    std::vector<std::optional<std::size_t>> joint_sources,
                    std::vector<std::size_t> wanted_frames);

  // Joints a ForwardKinematics from `base_link` to the massive links and `wanted_frames` moves
  // through, in tree order (to validate a configuration before constructing).
  [[nodiscard]] static std::vector<std::size_t> needed_joints(const KinematicTree& tree, std::size_t base_link,
                                                              std::span<const std::size_t> wanted_frames);

  // T_WB and the read joint positions q (as many as the largest source index + 1).
  void compute(const RigidPose& world_base, std::span<const double> q) noexcept;

  // Results of the last compute().
  [[nodiscard]] const RigidPose& frame_pose(std::size_t wanted_index) const noexcept {
    return poses_[wanted_frames_[wanted_index]];
  }
  [[nodiscard]] const Eigen::Vector3d& com_world() const noexcept { return com_world_; }
  [[nodiscard]] double total_mass_kg() const noexcept { return total_mass_kg_; }
  [[nodiscard]] std::size_t q_size() const noexcept { return q_size_; }

 private:
  struct Step {
    std::size_t from_link = 0;
    std::size_t to_link = 0;
    std::size_t joint = 0;
    bool along_joint = true;  // parent -> child
  };
  std::vector<KinematicTree::Joint> joints_;
  std::vector<std::optional<std::size_t>> joint_sources_;
  std::vector<Step> steps_;
  std::size_t base_link_ = 0;
  std::vector<std::size_t> wanted_frames_;
  std::vector<std::size_t> massive_links_;
  std::vector<double> link_mass_kg_;
  std::vector<Eigen::Vector3d> link_com_m_;
  std::vector<RigidPose> poses_;
  Eigen::Vector3d com_world_ = Eigen::Vector3d::Zero();
  double total_mass_kg_ = 0.0;
  std::size_t q_size_ = 0;
};

}  // namespace ftsense::robot_model
