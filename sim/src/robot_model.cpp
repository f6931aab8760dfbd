#include "ftsense/sim/robot_model.hpp"

#include <locale>
#include <sstream>
#include <stdexcept>

namespace ftsense::sim {

double RobotParams::trunk_kg() const {
  const double leg = hip_yaw_link_kg + hip_roll_link_kg + thigh_kg + shank_kg + ankle_link_kg +
                     foot_kg + 4.0 * pad_kg;
  return total_mass_kg - 2.0 * leg;
}

std::array<double, 2> pad_position(const RobotParams& p, int pad) {
  if (pad < 0 || pad > 3) throw std::out_of_range("pad_position: pad index must be 0..3");
  const double x = (pad < 2 ? 0.5 : -0.5) * p.foot_length_m;
  const double y = (pad % 2 == 0 ? 0.5 : -0.5) * p.foot_width_m;
  return {x, y};
}

namespace {

void write_leg(std::ostream& o, const RobotParams& p, char side) {
  const double sy = side == 'l' ? 1.0 : -1.0;
  const std::string s(1, side);
  const double A = p.upper_leg_m, B = p.lower_leg_m, hs = p.sole_ankle_m, r = p.pad_radius_m;
  o << "<body name='" << s << "_hip_yaw_link' pos='0 " << sy * p.hip_half_width_m << " 0'>\n"
    << " <joint name='" << s << "_hip_yaw' axis='0 0 1'/>\n"
    << " <geom type='sphere' size='0.04' mass='" << p.hip_yaw_link_kg << "'/>\n"
    << " <body name='" << s << "_hip_roll_link'>\n"
    << "  <joint name='" << s << "_hip_roll' axis='1 0 0'/>\n"
    << "  <geom type='sphere' size='0.04' mass='" << p.hip_roll_link_kg << "'/>\n"
    << "  <body name='" << s << "_thigh'>\n"
    << "   <joint name='" << s << "_hip_pitch' axis='0 1 0'/>\n"
    << "   <geom type='capsule' fromto='0 0 0 0 0 " << -A << "' size='0.05' mass='" << p.thigh_kg
    << "'/>\n"
    << "   <body name='" << s << "_shank' pos='0 0 " << -A << "'>\n"
    << "    <joint name='" << s << "_knee' axis='0 1 0'/>\n"
    << "    <geom type='capsule' fromto='0 0 0 0 0 " << -B << "' size='0.045' mass='" << p.shank_kg
    << "'/>\n"
    << "    <body name='" << s << "_ankle_link' pos='0 0 " << -B << "'>\n"
    << "     <joint name='" << s << "_ankle_pitch' axis='0 1 0'/>\n"
    << "     <geom type='sphere' size='0.03' mass='" << p.ankle_link_kg << "'/>\n"
    << "     <body name='" << s << "_foot'>\n"
    << "      <joint name='" << s << "_ankle_roll' axis='1 0 0'/>\n"
    << "      <geom type='box' pos='0 0 " << -hs + 2.0 * r + 0.015 << "' size='"
    << 0.5 * p.foot_length_m << ' ' << 0.5 * p.foot_width_m << " 0.015' mass='" << p.foot_kg
    << "'/>\n"
    << "      <site name='" << s << "_sole' pos='0 0 " << -hs << "'/>\n";
  for (int i = 0; i < 4; ++i) {
    const auto xy = pad_position(p, i);
    o << "      <geom name='" << s << "_pad" << i + 1 << "' class='pad' pos='" << xy[0] << ' '
      << xy[1] << ' ' << -hs + r << "' size='" << r << "' mass='" << p.pad_kg << "'/>\n"
      << "      <site name='" << s << "_pad" << i + 1 << "' pos='" << xy[0] << ' ' << xy[1] << ' '
      << -hs + r << "' size='" << 1.5 * r << "'/>\n";
  }
  o << "     </body>\n    </body>\n   </body>\n  </body>\n </body>\n</body>\n";
}

}  // namespace

std::string suralp_mjcf(const RobotParams& p) {
  if (!(p.trunk_kg() > 0.0)) throw std::invalid_argument("RobotParams: leg masses exceed total mass");
  std::ostringstream o;
  o.imbue(std::locale::classic());
  o.precision(17);
  const double pelvis_z = p.upper_leg_m + p.lower_leg_m + p.sole_ankle_m;  // straight legs
  o << "<mujoco model='suralp_like'>\n"
    << "<compiler angle='radian' inertiafromgeom='true'/>\n"
    << "<option timestep='" << p.timestep_s << "' integrator='Euler' gravity='0 0 "
    << -p.gravity_m_s2 << "'/>\n"
    << "<default>\n"
    << " <joint damping='" << p.joint_damping_Nms_rad << "' armature='" << p.joint_armature_kgm2
    << "'/>\n"
    << " <geom contype='0' conaffinity='0'/>\n"
    << " <default class='pad'>\n"
    << "  <geom type='sphere' contype='2' conaffinity='1' condim='3' friction='" << p.friction
    << " 0.005 0.0001' solref='" << p.contact_timeconst_s << ' ' << p.contact_dampratio << "'/>\n"
    << " </default>\n"
    << "</default>\n"
    << "<worldbody>\n"
    << "<geom name='floor' type='plane' size='100 100 0.1' contype='1' conaffinity='2' friction='"
    << p.friction << " 0.005 0.0001' solref='" << p.contact_timeconst_s << ' '
    << p.contact_dampratio << "'/>\n"
    << "<body name='trunk' pos='0 0 " << pelvis_z << "'>\n"
    << "<freejoint name='root'/>\n"
    << "<geom type='box' pos='0 0 " << p.trunk_com_height_m << "' size='0.1 0.15 0.2' mass='"
    << p.trunk_kg() << "'/>\n"
    << "<site name='imu' pos='0 0 " << p.imu_height_m << "'/>\n";
  write_leg(o, p, 'l');
  write_leg(o, p, 'r');
  o << "</body>\n</worldbody>\n<actuator>\n";
  for (auto name : kJointNames) o << " <motor name='" << name << "' joint='" << name << "'/>\n";
  o << "</actuator>\n<sensor>\n"
    << " <accelerometer name='imu_acc' site='imu'/>\n"
    << " <gyro name='imu_gyro' site='imu'/>\n";
  for (const char* side : {"l", "r"})
    for (int i = 1; i <= 4; ++i)
      o << " <touch name='" << side << "_pad" << i << "_touch' site='" << side << "_pad" << i << "'/>\n";
  o
    << "</sensor>\n</mujoco>\n";
  return o.str();
}

}  // namespace ftsense::sim

#include "ftsense/sim/mujoco_model.hpp"

#include <array>
#include <cstring>

namespace ftsense::sim {

MjModelPtr load_mjcf_string(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();  // ~2 MB: keep it off the stack
  mj_defaultVFS(vfs.get());
  const char* name = "ftsense_model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0)
    throw ModelError("MuJoCo VFS: cannot allocate the model file");
  const int idx = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[idx], xml.data(), xml.size());
  std::array<char, 1000> err{};
  mjModel* m = mj_loadXML(name, vfs.get(), err.data(), static_cast<int>(err.size()));
  mj_deleteVFS(vfs.get());
  if (m == nullptr) throw ModelError(std::string("MuJoCo rejected the model: ") + err.data());
  return MjModelPtr(m);
}

int require_id(const mjModel* m, mjtObj type, const char* name) {
  const int id = mj_name2id(m, type, name);
  if (id < 0) throw ModelError(std::string("model has no object named ") + name);
  return id;
}

}  // namespace ftsense::sim
