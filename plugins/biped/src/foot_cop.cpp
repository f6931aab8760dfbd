#include "ftsense/biped/foot_cop.hpp"

#include <limits>

#include "ftsense/plausible_ranges.hpp"

namespace ftsense::biped {

void FootCop::Params::describe(ParamSchema<Params>& schema) {
  schema.add("points", &Params::points, "contact points (x, y) of the foot, foot frame")
      .unit("m").count_at_least(3).required().plausible(plausible::foot_point_m());
  schema.add("min_normal_force_N", &Params::min_normal_force_N,
             "below this normal force the CoP is undefined (no division)")
      .unit("N").greater_than(0.0).plausible(plausible::min_load_N());
}

FootCop::FootCop(const Params& params, const StageContext& /*context*/)
    : polygon_(params.points), min_normal_force_N_(params.min_normal_force_N) {
  if (polygon_.vertices().size() < 3) {
    throw ConfigError("/params/points", "the contact points are collinear; a foot needs a support polygon with area");
  }
  ports_.add_input(PortSpec{"com", 3, "m", "CoM position c"}.in_frame("world"));
  ports_.add_input(PortSpec{"force", 3, "N", "the foot's ground reaction force F_i"}.in_frame("world"));
  ports_.add_input(PortSpec{"foot_pos", 3, "m", "foot frame origin o_i"}.in_frame("world"));
  ports_.add_input(PortSpec{"foot_rpy", 3, "rad", "foot orientation roll, pitch, yaw"}.in_frame("foot in world"));
  ports_.add_output(PortSpec{"cop", 2, "m", "centre of pressure r_i, clamped to the support polygon"}.in_frame("foot"));
  ports_.add_output(PortSpec{"normal_force", 1, "N", "normal force f_z (>= 0)"}.in_frame("foot"));
  ports_.add_output({"loaded", 1, "1", "1 when f_z >= min_normal_force_N"});
}

void FootCop::step(const StepIO& io) noexcept {
  const auto cop = io.out(kCop);
  // Unknown inputs give an unknown CoP and normal force (NaN: virtual sensor not ready).
  double normal = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d r = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  bool loaded = false;
  if (all_finite(io.in(kCom)) && all_finite(io.in(kForce)) && all_finite(io.in(kFootPos)) &&
      all_finite(io.in(kFootRpy))) {
    r = polygon_.centroid();
    const Eigen::Matrix3d rotation = rotation_from_rpy(io.in(kFootRpy));
    const Eigen::Vector3d d = rotation.transpose() * (vector3(io.in(kCom)) - vector3(io.in(kFootPos)));
    const Eigen::Vector3d f = rotation.transpose() * vector3(io.in(kForce));
    normal = f.z() > 0.0 ? f.z() : 0.0;
    if (f.z() >= min_normal_force_N_) {
      r = polygon_.clamp(d.head<2>() - (d.z() / f.z()) * f.head<2>());
      loaded = true;
    }
  }
  cop[0] = r.x();
  cop[1] = r.y();
  io.out(kNormalForce)[0] = normal;
  io.out(kLoaded)[0] = loaded ? 1.0 : 0.0;
}

}  // namespace ftsense::biped
