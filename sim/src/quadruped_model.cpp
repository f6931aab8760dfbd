#include "ftsense/sim/quadruped_model.hpp"

#include <locale>
#include <sstream>
#include <stdexcept>

namespace ftsense::sim {

double QuadrupedParams::trunk_kg() const {
  return total_mass_kg - kQuadrupedLegCount * (hip_link_kg + thigh_kg + shank_kg + foot_kg);
}

std::array<double, 3> quadruped_hip_point(const QuadrupedParams& p, int leg) {
  if (leg < 0 || leg >= kQuadrupedLegCount) throw std::out_of_range("quadruped_hip_point: leg must be 0..3");
  const double x = leg < 2 ? p.hip_x_m : -p.hip_x_m;   // lf, rf front
  const double y = leg % 2 == 0 ? p.hip_y_m : -p.hip_y_m;  // lf, lh left
  return {x, y, 0.0};
}

namespace {

LinkInertial sphere(double m, double r) {
  const double i = 0.4 * m * r * r;
  return {m, {0.0, 0.0, 0.0}, {i, i, i}};
}

/// Solid cylinder hanging from the frame origin down its -z axis.
LinkInertial rod(double m, double r, double length) {
  const double ixy = m * (3.0 * r * r + length * length) / 12.0;
  return {m, {0.0, 0.0, -0.5 * length}, {ixy, ixy, 0.5 * m * r * r}};
}

void write_inertial(std::ostream& o, const LinkInertial& in) {
  o << "<inertial pos='" << in.com_m[0] << ' ' << in.com_m[1] << ' ' << in.com_m[2] << "' mass='"
    << in.mass_kg << "' diaginertia='" << in.inertia_kgm2[0] << ' ' << in.inertia_kgm2[1] << ' '
    << in.inertia_kgm2[2] << "'/>";
}

void write_joint(std::ostream& o, const std::string& name, const char* axis, const std::array<double, 2>& range) {
  o << "<joint name='" << name << "' axis='" << axis << "' limited='true' range='" << range[0] << ' '
    << range[1] << "'/>";
}

}  // namespace

QuadrupedInertials quadruped_inertials(const QuadrupedParams& p) {
  QuadrupedInertials in;
  const double m = p.trunk_kg(), l = p.trunk_length_m, w = p.trunk_width_m, h = p.trunk_height_m;
  in.trunk = {m, {0.0, 0.0, 0.0}, {m * (w * w + h * h) / 12.0, m * (l * l + h * h) / 12.0, m * (l * l + w * w) / 12.0}};
  in.hip = sphere(p.hip_link_kg, p.hip_link_radius_m);
  in.thigh = rod(p.thigh_kg, p.thigh_radius_m, p.thigh_m);
  in.shank = rod(p.shank_kg, p.shank_radius_m, p.shank_m);
  in.foot = sphere(p.foot_kg, p.foot_radius_m);
  return in;
}

std::string quadruped_mjcf(const QuadrupedParams& p) {
  if (!(p.trunk_kg() > 0.0)) throw std::invalid_argument("QuadrupedParams: leg masses exceed total mass");
  const QuadrupedInertials in = quadruped_inertials(p);
  std::ostringstream o;
  o.imbue(std::locale::classic());
  o.precision(17);
  const double trunk_z = p.thigh_m + p.shank_m + p.foot_radius_m;  // straight legs, feet on the floor
  o << "<mujoco model='ftsense_quadruped'>\n"
    << "<compiler angle='radian' inertiafromgeom='false'/>\n"
    << "<option timestep='" << p.timestep_s << "' integrator='Euler' gravity='0 0 " << -p.gravity_m_s2
    << "'/>\n"
    << "<default>\n"
    << " <joint damping='" << p.joint_damping_Nms_rad << "' armature='" << p.joint_armature_kgm2 << "'/>\n"
    << " <geom contype='0' conaffinity='0'/>\n"
    << " <motor ctrllimited='true' ctrlrange='" << -p.max_torque_Nm << ' ' << p.max_torque_Nm << "'/>\n"
    << " <default class='foot'>\n"
    << "  <geom type='sphere' contype='2' conaffinity='1' condim='3' friction='" << p.friction
    << " 0.005 0.0001' solref='" << p.contact_timeconst_s << ' ' << p.contact_dampratio << "'/>\n"
    << " </default>\n"
    << "</default>\n"
    << "<worldbody>\n"
    << "<geom name='floor' type='plane' size='100 100 0.1' contype='1' conaffinity='2' friction='"
    << p.friction << " 0.005 0.0001' solref='" << p.contact_timeconst_s << ' ' << p.contact_dampratio
    << "'/>\n"
    << "<body name='trunk' pos='0 0 " << trunk_z << "'>\n"
    << "<freejoint name='root'/>\n";
  write_inertial(o, in.trunk);
  o << "\n<geom type='box' size='" << 0.5 * p.trunk_length_m << ' ' << 0.5 * p.trunk_width_m << ' '
    << 0.5 * p.trunk_height_m << "'/>\n"
    << "<site name='imu' pos='0 0 " << p.imu_height_m << "'/>\n";
  for (int leg = 0; leg < kQuadrupedLegCount; ++leg) {
    const std::string s(kQuadrupedLegs[static_cast<std::size_t>(leg)]);
    const auto hp = quadruped_hip_point(p, leg);
    o << "<body name='" << s << "_hip' pos='" << hp[0] << ' ' << hp[1] << ' ' << hp[2] << "'>\n ";
    write_joint(o, s + "_hip_abd", "1 0 0", p.abd_range_rad);
    write_inertial(o, in.hip);
    o << "<geom type='sphere' size='" << p.hip_link_radius_m << "'/>\n"
      << " <body name='" << s << "_thigh'>\n  ";
    write_joint(o, s + "_hip_flex", "0 1 0", p.flex_range_rad);
    write_inertial(o, in.thigh);
    o << "<geom type='cylinder' fromto='0 0 0 0 0 " << -p.thigh_m << "' size='" << p.thigh_radius_m << "'/>\n"
      << "  <body name='" << s << "_shank' pos='0 0 " << -p.thigh_m << "'>\n   ";
    write_joint(o, s + "_knee", "0 1 0", p.knee_range_rad);
    write_inertial(o, in.shank);
    o << "<geom type='cylinder' fromto='0 0 0 0 0 " << -p.shank_m << "' size='" << p.shank_radius_m << "'/>\n"
      << "   <body name='" << s << "_foot' pos='0 0 " << -p.shank_m << "'>\n    ";
    write_inertial(o, in.foot);
    o << "<geom name='" << s << "_foot' class='foot' size='" << p.foot_radius_m << "'/>\n"
      << "   </body>\n  </body>\n </body>\n</body>\n";
  }
  o << "</body>\n</worldbody>\n<actuator>\n";
  for (auto name : kQuadrupedJointNames) o << " <motor name='" << name << "' joint='" << name << "'/>\n";
  o << "</actuator>\n<sensor>\n"
    << " <accelerometer name='imu_acc' site='imu'/>\n"
    << " <gyro name='imu_gyro' site='imu'/>\n"
    << "</sensor>\n</mujoco>\n";
  return o.str();
}

}  // namespace ftsense::sim
