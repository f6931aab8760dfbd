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
  schema.add("foot_links", &Params::foot_links,
             "links (frames) of the feet, on the contact plane: soles, or point feet at their contact point")
      .count_at_least(1).required();
  schema.add("foot_points_m", &Params::foot_points_m,
             "contact points (x, y) of each foot in its frame, every foot alike (a sole outline), for the contact "
             "test; empty: the frame origin (point feet)")
      .unit("m").plausible(plausible::foot_point_m());
  schema.add_choice("ground_reference", &Params::ground_reference,
                    "the ground the foot heights are measured from: the plane z = ground_height_m, or the "
                    "lowest point of all feet",
                    {{"plane", Params::GroundReference::plane}, {"lowest_foot", Params::GroundReference::lowest_foot}});
  schema.add("ground_height_m", &Params::ground_height_m, "height of the ground plane, world frame (ground_reference = plane)")
      .unit("m").plausible(plausible::ground_height_m());
  schema.add("contact_height_m", &Params::contact_height_m,
             "a foot is in contact when its lowest contact point is below this height above the ground")
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
  const std::size_t feet = params.foot_links.size();
  ports.add_output(PortSpec{"foot_pos", 3 * feet, "m", "foot frame origins (x, y, z), foot after foot"}
                       .in_frame("world")
                       .sized_by("3 len(params.foot_links)"));
  ports.add_output(PortSpec{"foot_rpy", 3 * feet, "rad", "foot orientations: roll, pitch, yaw, foot after foot"}
                       .in_frame("foot in world")
                       .sized_by("3 len(params.foot_links)"));
  ports.add_output(PortSpec{"imu_rpy", 3, "rad", "IMU frame orientation R_WB R_B,IMU: roll, pitch, yaw"}
                       .in_frame("imu in world"));
  ports.add_output(PortSpec{"foot_height", feet, "m", "lowest contact point of each foot above the ground"}
                       .sized_by("len(params.foot_links)"));
  ports.add_output(PortSpec{"contact", feet, "1", "kinematic contact state per foot: foot_height < contact_height_m"}
                       .sized_by("len(params.foot_links)"));
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
  std::vector<std::size_t> frames{link("imu_link", params.imu_link)};
  for (std::size_t i = 0; i < params.foot_links.size(); ++i) {
    frames.push_back(link(json_pointer_append("foot_links", i), params.foot_links[i]));
  }
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
  write(io.out(kImuRpy), biped::rpy_from_rotation(kinematics_->frame_pose(kImuFrame).rotation));
  const auto foot_pos = io.out(kFootPos);
  const auto foot_rpy = io.out(kFootRpy);
  const auto height = io.out(kFootHeight);
  double ground = params_.ground_height_m;
  if (params_.ground_reference == Params::GroundReference::lowest_foot) ground = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < height.size(); ++i) {
    const RigidPose& foot = kinematics_->frame_pose(kImuFrame + 1 + i);
    write(foot_pos.subspan(3 * i, 3), foot.translation);
    write(foot_rpy.subspan(3 * i, 3), biped::rpy_from_rotation(foot.rotation));
    double lowest = params_.foot_points_m.empty() ? 0.0 : std::numeric_limits<double>::infinity();
    for (const auto& p : params_.foot_points_m) {
      lowest = std::min(lowest, foot.rotation.row(2).head<2>().dot(Eigen::Vector2d(p[0], p[1])));
    }
    height[i] = foot.translation.z() + lowest;
    if (params_.ground_reference == Params::GroundReference::lowest_foot) ground = std::min(ground, height[i]);
  }
  for (std::size_t i = 0; i < height.size(); ++i) {
    height[i] -= ground;
    io.out(kContact)[i] = height[i] < params_.contact_height_m ? 1.0 : 0.0;
  }
}

}  // namespace ftsense::robot_model
