#include "ftsense/robot_model/urdf_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ftsense/biped/frames.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::robot_model {
namespace {

std::string did_you_mean(std::string_view name, const std::vector<std::string>& known, std::string_view what) {
  // A URDF has hundreds of links: name the closest, not all of them.
  const std::string closest = closest_match(name, known);
  return (closest.empty() ? std::string() : "did you mean '" + closest + "'? ") + "the URDF has " +
         std::to_string(known.size()) + " " + std::string(what);
}

}  // namespace

void UrdfKinematics::Params::describe(ParamSchema<Params>& schema) {
  schema.add("urdf", &Params::urdf, "URDF file of the robot; a relative path is relative to the config file's directory")
      .required();
  schema.add("joints", &Params::joints, "joints read from input joint_positions, in its order (URDF names)")
      .required();
  schema.add("held_joints", &Params::held_joints,
             "movable joints not read (no encoder in the log), held at q = 0");
  schema.add("base_link", &Params::base_link, "link whose world pose inputs base_pos and base_rpy give").required();
  schema.add("imu_link", &Params::imu_link, "link (frame) of the IMU whose specific force is used").required();
  schema.add("left_sole_link", &Params::left_sole_link, "link (frame) of the left sole, on the sole plane").required();
  schema.add("right_sole_link", &Params::right_sole_link, "link (frame) of the right sole, on the sole plane")
      .required();
  schema.add("left_sole_points_m", &Params::left_sole_points_m,
             "sole outline points (x, y) in the left sole frame, for the contact test; empty: the frame origin")
      .unit("m").plausible(plausible::foot_point_m());
  schema.add("right_sole_points_m", &Params::right_sole_points_m,
             "sole outline points (x, y) in the right sole frame, for the contact test; empty: the frame origin")
      .unit("m").plausible(plausible::foot_point_m());
  schema.add_choice("ground_reference", &Params::ground_reference,
                    "the ground the sole heights are measured from: the plane z = ground_height_m, or the "
                    "lower foot's lowest sole point",
                    {{"plane", Params::GroundReference::plane}, {"lowest_sole", Params::GroundReference::lowest_sole}});
  schema.add("ground_height_m", &Params::ground_height_m, "height of the ground plane, world frame (ground_reference = plane)")
      .unit("m").plausible(plausible::ground_height_m());
  schema.add("contact_height_m", &Params::contact_height_m,
             "a foot is in contact when its lowest sole point is below this height above the ground")
      .unit("m").greater_than(0.0).plausible(plausible::foot_height_m());
}

Ports UrdfKinematics::declare_ports(const Params& params) {
  Ports ports;
  ports.add_input(PortSpec{"base_pos", 3, "m", "position p_WB of base_link"}.in_frame("world"));
  ports.add_input(PortSpec{"base_rpy", 3, "rad", "orientation of base_link: roll, pitch, yaw of R_WB"}
                      .in_frame("base in world"));
  ports.add_input(PortSpec{"joint_positions", params.joints.size(), "rad", "positions q of the joints listed in `joints`"}
                      .sized_by("len(params.joints)"));
  ports.add_output(PortSpec{"com", 3, "m", "centre of mass c_W of the whole robot"}.in_frame("world"));
  ports.add_output(PortSpec{"l_sole_pos", 3, "m", "left sole frame origin"}.in_frame("world"));
  ports.add_output(PortSpec{"l_sole_rpy", 3, "rad", "left sole orientation: roll, pitch, yaw"}
                       .in_frame("sole in world"));
  ports.add_output(PortSpec{"r_sole_pos", 3, "m", "right sole frame origin"}.in_frame("world"));
  ports.add_output(PortSpec{"r_sole_rpy", 3, "rad", "right sole orientation: roll, pitch, yaw"}
                       .in_frame("sole in world"));
  ports.add_output(PortSpec{"imu_rpy", 3, "rad", "IMU frame orientation R_WB R_B,IMU: roll, pitch, yaw"}
                       .in_frame("imu in world"));
  ports.add_output({"sole_height", 2, "m", "lowest sole point above the ground (left, right)"});
  ports.add_output({"contact", 2, "1", "kinematic contact state (left, right): sole_height < contact_height_m"});
  ports.add_output({"mass", 1, "kg", "total mass M of the URDF's links"});
  return ports;
}

UrdfKinematics::UrdfKinematics(const Params& params, const StageContext& context) : params_(params) {
  KinematicTree tree;
  try {
    tree = KinematicTree::from_urdf_file(context.resolve_path(params.urdf));
  } catch (const UrdfError& e) {
    throw ConfigError("/params/urdf", std::string(e.what()) +
                                          (context.config_directory().empty()
                                               ? std::string()
                                               : " (relative paths start at the config file's directory)"));
  }
  Diagnostics diag;
  const std::vector<std::string> links = tree.link_names();
  const auto link = [&](const std::string& key, const std::string& link_name) -> std::size_t {
    if (const auto index = tree.find_link(link_name)) return *index;
    diag.error("/params/" + key, "link '" + link_name + "' is not in the URDF; " + did_you_mean(link_name, links, "links"));
    return 0;
  };
  const std::size_t base = link("base_link", params.base_link);
  const std::vector<std::size_t> frames{link("imu_link", params.imu_link), link("left_sole_link", params.left_sole_link),
                                        link("right_sole_link", params.right_sole_link)};
  std::vector<std::optional<std::size_t>> sources(tree.joints().size());
  std::vector<bool> listed(tree.joints().size(), false);
  const std::vector<std::string> movable = tree.movable_joint_names();
  const auto joint = [&](const std::string& key, std::size_t i, const std::string& joint_name) -> std::optional<std::size_t> {
    const std::string path = json_pointer_append("/params/" + key, i);
    const auto index = tree.find_joint(joint_name);
    if (!index || !tree.joints()[*index].movable()) {
      diag.error(path, (index ? "joint '" + joint_name + "' is fixed, nothing to read or hold; "
                              : "joint '" + joint_name + "' is not in the URDF; ") +
                           did_you_mean(joint_name, movable, "movable joints"));
      return std::nullopt;
    }
    if (listed[*index]) {
      diag.error(path, "joint '" + joint_name + "' is listed twice (in joints or held_joints)");
      return std::nullopt;
    }
    listed[*index] = true;
    return index;
  };
  for (std::size_t i = 0; i < params.joints.size(); ++i) {
    if (const auto j = joint("joints", i, params.joints[i])) sources[*j] = i;
  }
  for (std::size_t i = 0; i < params.held_joints.size(); ++i) (void)joint("held_joints", i, params.held_joints[i]);
  diag.throw_if_errors();

  std::vector<std::string> unlisted;
  for (std::size_t j : ForwardKinematics::needed_joints(tree, base, frames)) {
    const auto& jt = tree.joints()[j];
    if (jt.type == JointType::floating || jt.type == JointType::planar) {
      diag.error("/params/base_link", "joint '" + jt.name + "' is floating or planar; urdf_kinematics needs a tree of "
                                      "fixed, revolute, continuous and prismatic joints from the base link");
    } else if (jt.movable() && !listed[j]) {
      unlisted.push_back(jt.name);
    }
  }
  if (!unlisted.empty()) {
    std::string names;
    for (const auto& n : unlisted) names += (names.empty() ? "" : ", ") + n;
    diag.error("/params/joints", "the movable joints " + names +
                                     " carry mass or frames the kinematics needs; read them (joints) or hold "
                                     "them at 0 (held_joints)");
  }
  diag.throw_if_errors();
  kinematics_.emplace(tree, base, std::move(sources), frames);

  ports_ = declare_ports(params);
}

void UrdfKinematics::step(const StepIO& io) noexcept {
  const auto base_pos = io.in(kBasePos);
  const auto base_rpy = io.in(kBaseRpy);
  const auto q = io.in(kJointPositions);
  io.out(kMass)[0] = kinematics_->total_mass_kg();
  if (!biped::all_finite(base_pos) || !biped::all_finite(base_rpy) || !biped::all_finite(q)) {
    // An unknown pose is not a pose: NaN tells the stages downstream the kinematics is not ready.
    for (std::size_t o = kCom; o <= kContact; ++o) {
      for (double& v : io.out(o)) v = std::numeric_limits<double>::quiet_NaN();
    }
    return;
  }
  kinematics_->compute({biped::rotation_from_rpy(base_rpy), biped::vector3(base_pos)}, q);
  const auto write = [](std::span<double> out, const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) out[static_cast<std::size_t>(i)] = v[i];
  };
  write(io.out(kCom), kinematics_->com_world());
  const RigidPose& left = kinematics_->frame_pose(kLeftSoleFrame);
  const RigidPose& right = kinematics_->frame_pose(kRightSoleFrame);
  write(io.out(kLeftSolePos), left.translation);
  write(io.out(kLeftSoleRpy), biped::rpy_from_rotation(left.rotation));
  write(io.out(kRightSolePos), right.translation);
  write(io.out(kRightSoleRpy), biped::rpy_from_rotation(right.rotation));
  write(io.out(kImuRpy), biped::rpy_from_rotation(kinematics_->frame_pose(kImuFrame).rotation));
  const auto lowest = [&](const RigidPose& sole, const std::vector<std::array<double, 2>>& points) {
    if (points.empty()) return sole.translation.z();
    double z = std::numeric_limits<double>::infinity();
    for (const auto& p : points) z = std::min(z, sole.rotation.row(2).head<2>().dot(Eigen::Vector2d(p[0], p[1])));
    return sole.translation.z() + z;
  };
  double heights[2] = {lowest(left, params_.left_sole_points_m), lowest(right, params_.right_sole_points_m)};
  const double ground = params_.ground_reference == Params::GroundReference::plane ? params_.ground_height_m
                                                                                   : std::min(heights[0], heights[1]);
  for (double& h : heights) h -= ground;
  for (std::size_t i = 0; i < 2; ++i) {
    io.out(kSoleHeight)[i] = heights[i];
    io.out(kContact)[i] = heights[i] < params_.contact_height_m ? 1.0 : 0.0;
  }
}

}  // namespace ftsense::robot_model
