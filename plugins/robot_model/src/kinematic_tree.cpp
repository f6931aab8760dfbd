#include "ftsense/robot_model/kinematic_tree.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include <Eigen/Geometry>
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "ftsense/text_file.hpp"

namespace ftsense::robot_model {
namespace {

// urdfdom reports through console_bridge; keep its messages for our error instead of letting
// them reach stderr as extra lines.
class CapturedUrdfMessages final : public console_bridge::OutputHandler {
 public:
  CapturedUrdfMessages() { console_bridge::useOutputHandler(this); }
  ~CapturedUrdfMessages() override { console_bridge::restorePreviousOutputHandler(); }
  CapturedUrdfMessages(const CapturedUrdfMessages&) = delete;
  CapturedUrdfMessages& operator=(const CapturedUrdfMessages&) = delete;

  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
           int /*line*/) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_error_.empty()) first_error_ = text;
  }
  [[nodiscard]] const std::string& first_error() const noexcept { return first_error_; }

 private:
  std::string first_error_;
};

RigidPose to_pose(const urdf::Pose& pose) {
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  RigidPose out;
  out.rotation = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  out.translation = {pose.position.x, pose.position.y, pose.position.z};
  return out;
}

JointType to_joint_type(int type, const std::string& name, std::string_view source) {
  switch (type) {
    case urdf::Joint::FIXED: return JointType::fixed;
    case urdf::Joint::REVOLUTE: return JointType::revolute;
    case urdf::Joint::CONTINUOUS: return JointType::continuous;
    case urdf::Joint::PRISMATIC: return JointType::prismatic;
    case urdf::Joint::FLOATING: return JointType::floating;
    case urdf::Joint::PLANAR: return JointType::planar;
    default: break;
  }
  throw UrdfError(std::string(source) + ": joint '" + name + "' has an unknown type");
}

std::vector<std::string> sorted_names(const auto& items, auto&& keep) {
  std::vector<std::string> names;
  for (const auto& item : items) {
    if (keep(item)) names.push_back(item.name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

RigidPose KinematicTree::Joint::transform(double q) const noexcept {
  RigidPose motion;
  if (type == JointType::revolute || type == JointType::continuous) {
    motion.rotation = Eigen::AngleAxisd(q, axis).toRotationMatrix();
  } else if (type == JointType::prismatic) {
    motion.translation = axis * q;
  }
  return origin * motion;
}

KinematicTree KinematicTree::from_urdf_file(const std::filesystem::path& path) {
  std::string text;
  try {
    text = read_text_file(path, "URDF");
  } catch (const TextFileError& e) {
    throw UrdfError(e.what());
  }
  return from_urdf_text(text, path.string());
}

KinematicTree KinematicTree::from_urdf_text(const std::string& xml, std::string_view source_name) {
  urdf::ModelInterfaceSharedPtr model;
  {
    CapturedUrdfMessages messages;
    try {
      model = urdf::parseURDF(xml);
    } catch (const std::exception& e) {
      throw UrdfError(std::string(source_name) + ": not a valid URDF: " + e.what());
    }
    if (!model) {
      throw UrdfError(std::string(source_name) + ": not a valid URDF" +
                      (messages.first_error().empty() ? std::string() : ": " + messages.first_error()));
    }
  }
  KinematicTree tree;
  std::map<std::string, std::size_t> link_index;
  for (const auto& [name, link] : model->links_) {
    Link l;
    l.name = name;
    if (link->inertial) {
      l.mass_kg = link->inertial->mass;
      const auto& p = link->inertial->origin.position;
      l.com_in_link_m = {p.x, p.y, p.z};
      if (!(l.mass_kg >= 0.0)) {
        throw UrdfError(std::string(source_name) + ": link '" + name + "' has a negative mass");
      }
    }
    link_index[name] = tree.links_.size();
    tree.links_.push_back(std::move(l));
  }
  for (const auto& [name, joint] : model->joints_) {
    Joint j;
    j.name = name;
    j.type = to_joint_type(joint->type, name, source_name);
    j.parent_link = link_index.at(joint->parent_link_name);  // urdfdom checked both links exist
    j.child_link = link_index.at(joint->child_link_name);
    j.origin = to_pose(joint->parent_to_joint_origin_transform);
    const Eigen::Vector3d axis(joint->axis.x, joint->axis.y, joint->axis.z);
    if (j.movable()) {
      if (!(axis.norm() > 1e-12)) {
        throw UrdfError(std::string(source_name) + ": joint '" + name + "' has a zero axis");
      }
      j.axis = axis.normalized();
    }
    tree.links_[j.child_link].parent_joint = tree.joints_.size();
    tree.joints_.push_back(std::move(j));
  }
  return tree;
}

std::optional<std::size_t> KinematicTree::find_link(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == name) return i;
  }
  return std::nullopt;
}

std::optional<std::size_t> KinematicTree::find_joint(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    if (joints_[i].name == name) return i;
  }
  return std::nullopt;
}

std::vector<std::string> KinematicTree::link_names() const {
  return sorted_names(links_, [](const Link&) { return true; });
}
std::vector<std::string> KinematicTree::joint_names() const {
  return sorted_names(joints_, [](const Joint&) { return true; });
}
std::vector<std::string> KinematicTree::movable_joint_names() const {
  return sorted_names(joints_, [](const Joint& j) { return j.movable(); });
}

double KinematicTree::total_mass_kg() const noexcept {
  double m = 0.0;
  for (const auto& l : links_) m += l.mass_kg;
  return m;
}

std::vector<std::size_t> KinematicTree::path_joints(std::size_t from, std::size_t to) const {
  // Both links' chains up to the root; the path leaves `from` upwards to the common ancestor,
  // then goes down to `to`.
  const auto up = [&](std::size_t link) {
    std::vector<std::size_t> chain;
    while (links_[link].parent_joint) {
      chain.push_back(*links_[link].parent_joint);
      link = joints_[chain.back()].parent_link;
    }
    return chain;
  };
  std::vector<std::size_t> a = up(from);
  std::vector<std::size_t> b = up(to);
  while (!a.empty() && !b.empty() && a.back() == b.back()) {
    a.pop_back();
    b.pop_back();
  }
  a.insert(a.end(), b.rbegin(), b.rend());
  return a;
}

std::vector<std::size_t> ForwardKinematics::needed_joints(const KinematicTree& tree, std::size_t base_link,
                                                          std::span<const std::size_t> wanted_frames) {
  std::vector<bool> needed(tree.joints().size(), false);
  const auto mark = [&](std::size_t link) {
    for (std::size_t j : tree.path_joints(base_link, link)) needed[j] = true;
  };
  for (std::size_t l = 0; l < tree.links().size(); ++l) {
    if (tree.links()[l].mass_kg > 0.0) mark(l);
  }
  for (std::size_t l : wanted_frames) mark(l);
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < needed.size(); ++j) {
    if (needed[j]) out.push_back(j);
  }
  return out;
}

ForwardKinematics::ForwardKinematics(const KinematicTree& tree, std::size_t base_link,
                                     std::vector<std::optional<std::size_t>> joint_sources,
                                     std::vector<std::size_t> wanted_frames)
    : joints_(tree.joints()),
      joint_sources_(std::move(joint_sources)),
      base_link_(base_link),
      wanted_frames_(std::move(wanted_frames)),
      link_mass_kg_(tree.links().size(), 0.0),
      link_com_m_(tree.links().size(), Eigen::Vector3d::Zero()),
      poses_(tree.links().size()) {
  if (joint_sources_.size() != joints_.size() || base_link >= tree.links().size()) {
    throw std::invalid_argument("ForwardKinematics: one joint source per joint and a base link of the tree");
  }
  const std::vector<std::size_t> needed = needed_joints(tree, base_link, wanted_frames_);
  for (std::size_t j : needed) {
    const auto& joint = joints_[j];
    if (joint.type == JointType::floating || joint.type == JointType::planar) {
      throw std::invalid_argument("ForwardKinematics: joint '" + joint.name + "' is floating or planar");
    }
  }
  for (const auto& source : joint_sources_) {
    if (source) q_size_ = std::max(q_size_, *source + 1);
  }
  // Breadth-first from the base over the needed joints, in both directions.
  std::vector<bool> reached(tree.links().size(), false);
  std::vector<bool> used(joints_.size(), true);
  for (std::size_t j : needed) used[j] = false;
  reached[base_link] = true;
  std::vector<std::size_t> frontier{base_link};
  while (!frontier.empty()) {
    std::vector<std::size_t> next;
    for (std::size_t link : frontier) {
      for (std::size_t j = 0; j < joints_.size(); ++j) {
        if (used[j]) continue;
        const bool forward = joints_[j].parent_link == link;
        if (!forward && joints_[j].child_link != link) continue;
        const std::size_t other = forward ? joints_[j].child_link : joints_[j].parent_link;
        used[j] = true;
        reached[other] = true;
        steps_.push_back({link, other, j, forward});
        next.push_back(other);
      }
    }
    frontier = std::move(next);
  }
  for (std::size_t l = 0; l < tree.links().size(); ++l) {
    if (tree.links()[l].mass_kg > 0.0 && reached[l]) {
      massive_links_.push_back(l);
      link_mass_kg_[l] = tree.links()[l].mass_kg;
      link_com_m_[l] = tree.links()[l].com_in_link_m;
      total_mass_kg_ += link_mass_kg_[l];
    }
  }
}

void ForwardKinematics::compute(const RigidPose& world_base, std::span<const double> q) noexcept {
  poses_[base_link_] = world_base;
  for (const Step& s : steps_) {
    const auto& source = joint_sources_[s.joint];
    const double position = source && *source < q.size() ? q[*source] : 0.0;
    const RigidPose parent_child = joints_[s.joint].transform(position);
    poses_[s.to_link] = poses_[s.from_link] * (s.along_joint ? parent_child : parent_child.inverse());
  }
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (std::size_t l : massive_links_) {
    weighted += link_mass_kg_[l] * (poses_[l].rotation * link_com_m_[l] + poses_[l].translation);
  }
  com_world_ = total_mass_kg_ > 0.0 ? Eigen::Vector3d(weighted / total_mass_kg_) : world_base.translation;
}

}  // namespace ftsense::robot_model
