#include "ftsense/sim/quadruped_urdf.hpp"

#include <charconv>
#include <stdexcept>

namespace ftsense::sim {

namespace {

std::string num(double x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x + 0.0);  // + 0.0: no "-0"
  return std::string(buf, res.ptr);
}

std::string xyz(double x, double y, double z) { return num(x) + " " + num(y) + " " + num(z); }

void link(std::string& o, const std::string& name, const LinkInertial& in, const std::string& extra = {}) {
  o += "  <link name=\"" + name + "\">\n";
  o += "    <inertial><origin xyz=\"" + xyz(in.com_m[0], in.com_m[1], in.com_m[2]) + "\" rpy=\"0 0 0\"/><mass value=\"" +
       num(in.mass_kg) + "\"/><inertia ixx=\"" + num(in.inertia_kgm2[0]) + "\" ixy=\"0\" ixz=\"0\" iyy=\"" +
       num(in.inertia_kgm2[1]) + "\" iyz=\"0\" izz=\"" + num(in.inertia_kgm2[2]) + "\"/></inertial>\n";
  o += extra;
  o += "  </link>\n";
}

void joint(std::string& o, const std::string& name, const char* type, const std::string& parent,
           const std::string& child, const std::string& origin, const char* axis = nullptr,
           const std::array<double, 2>* range = nullptr, const QuadrupedParams* p = nullptr) {
  o += "  <joint name=\"" + name + "\" type=\"" + type + "\">\n";
  o += "    <parent link=\"" + parent + "\"/><child link=\"" + child + "\"/><origin xyz=\"" + origin +
       "\" rpy=\"0 0 0\"/>";
  if (axis != nullptr && range != nullptr && p != nullptr) {
    o += "<axis xyz=\"" + std::string(axis) + "\"/>\n";
    o += "    <limit lower=\"" + num((*range)[0]) + "\" upper=\"" + num((*range)[1]) + "\" effort=\"" +
         num(p->max_torque_Nm) + "\" velocity=\"" + num(p->max_velocity_rad_s) + "\"/><dynamics damping=\"" +
         num(p->joint_damping_Nms_rad) + "\"/>";
  }
  o += "\n  </joint>\n";
}

}  // namespace

std::string quadruped_urdf(const QuadrupedParams& p) {
  if (!(p.trunk_kg() > 0.0)) throw std::invalid_argument("QuadrupedParams: leg masses exceed total mass");
  const QuadrupedInertials in = quadruped_inertials(p);
  std::string o;
  o += "<?xml version=\"1.0\"?>\n";
  o += "<!-- ftsense's simulated quadruped (sim/README.md, \"Quadruped\"), generated from QuadrupedParams by\n"
       "     `ftsense-sim --write-urdf configs/quadruped/quadruped.urdf --robot quadruped`. Do not edit:\n"
       "     the test QuadrupedUrdf.CommittedFileIsTheGeneratedOne compares the two byte for byte.\n"
       "     Units: m, kg, kg m^2, rad, N m, rad/s. Foot frames: the foot sphere's centre (radius " +
       num(p.foot_radius_m) + " m). -->\n";
  o += "<robot name=\"ftsense_quadruped\">\n";
  link(o, "trunk", in.trunk,
       "    <collision><origin xyz=\"0 0 0\" rpy=\"0 0 0\"/><geometry><box size=\"" +
           xyz(p.trunk_length_m, p.trunk_width_m, p.trunk_height_m) + "\"/></geometry></collision>\n");
  o += "  <link name=\"imu\"/>\n";
  joint(o, "imu_fixed", "fixed", "trunk", "imu", xyz(0.0, 0.0, p.imu_height_m));
  for (int leg = 0; leg < kQuadrupedLegCount; ++leg) {
    const std::string s(kQuadrupedLegs[static_cast<std::size_t>(leg)]);
    const auto h = quadruped_hip_point(p, leg);
    link(o, s + "_hip", in.hip);
    joint(o, s + "_hip_abd", "revolute", "trunk", s + "_hip", xyz(h[0], h[1], h[2]), "1 0 0", &p.abd_range_rad, &p);
    link(o, s + "_thigh", in.thigh);
    joint(o, s + "_hip_flex", "revolute", s + "_hip", s + "_thigh", xyz(0.0, 0.0, 0.0), "0 1 0", &p.flex_range_rad, &p);
    link(o, s + "_shank", in.shank);
    joint(o, s + "_knee", "revolute", s + "_thigh", s + "_shank", xyz(0.0, 0.0, -p.thigh_m), "0 1 0", &p.knee_range_rad,
          &p);
    link(o, s + "_foot", in.foot,
         "    <collision><origin xyz=\"0 0 0\" rpy=\"0 0 0\"/><geometry><sphere radius=\"" + num(p.foot_radius_m) +
             "\"/></geometry></collision>\n");
    joint(o, s + "_foot_fixed", "fixed", s + "_shank", s + "_foot", xyz(0.0, 0.0, -p.shank_m));
  }
  o += "</robot>\n";
  return o;
}

}  // namespace ftsense::sim
