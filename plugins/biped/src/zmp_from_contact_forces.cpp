#include "ftsense/biped/zmp_from_contact_forces.hpp"

#include <cmath>

#include "ftsense/biped/frames.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::biped {

void ZmpFromContactForces::Params::describe(ParamSchema<Params>& schema) {
  schema.add("points", &Params::points, "contact points (x, y) of each foot, foot frame")
      .unit("m").count_at_least(1).required().plausible(plausible::foot_point_m());
  schema.add("min_total_force_N", &Params::min_total_force_N, "below this total load the last ZMP is held")
      .unit("N").greater_than(0.0).plausible(plausible::min_load_N());
}

ZmpFromContactForces::ZmpFromContactForces(const Params& params, const StageContext& /*context*/)
    : points_(params.points), min_total_force_N_(params.min_total_force_N) {
  const std::size_t n = points_.size();
  ports_.add_input(PortSpec{"l_forces", n, "N", "left foot contact-point normal forces (measured)"}
                       .sized_by("len(params.points)"));
  ports_.add_input(PortSpec{"r_forces", n, "N", "right foot contact-point normal forces (measured)"}
                       .sized_by("len(params.points)"));
  ports_.add_input(PortSpec{"l_foot_pos", 3, "m", "left foot frame origin"}.in_frame("world"));
  ports_.add_input(PortSpec{"l_foot_rpy", 3, "rad", "left foot orientation roll, pitch, yaw"}
                       .in_frame("foot in world"));
  ports_.add_input(PortSpec{"r_foot_pos", 3, "m", "right foot frame origin"}.in_frame("world"));
  ports_.add_input(PortSpec{"r_foot_rpy", 3, "rad", "right foot orientation roll, pitch, yaw"}
                       .in_frame("foot in world"));
  ports_.add_output(PortSpec{"zmp", 2, "m", "measured ZMP (x, y)"}.in_frame("world"));
  ports_.add_output({"total_normal_force", 1, "N", "sum of all contact-point forces"});
}

void ZmpFromContactForces::reset() noexcept { last_zmp_[0] = last_zmp_[1] = 0.0; }

void ZmpFromContactForces::step(const StepIO& io) noexcept {
  double total = 0.0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  const std::size_t feet[2][3] = {{kLeftForces, kLeftPos, kLeftRpy}, {kRightForces, kRightPos, kRightRpy}};
  for (const auto& foot : feet) {
    const auto forces = io.in(foot[0]);
    if (!all_finite(io.in(foot[1])) || !all_finite(io.in(foot[2]))) continue;
    const Eigen::Matrix3d rotation = rotation_from_rpy(io.in(foot[2]));
    const Eigen::Vector3d origin = vector3(io.in(foot[1]));
    for (std::size_t l = 0; l < points_.size(); ++l) {
      const double f = std::isfinite(forces[l]) ? forces[l] : 0.0;
      const Eigen::Vector3d p = origin + rotation * Eigen::Vector3d(points_[l][0], points_[l][1], 0.0);
      total += f;
      moment += f * p.head<2>();
    }
  }
  if (total >= min_total_force_N_) {
    last_zmp_[0] = moment.x() / total;
    last_zmp_[1] = moment.y() / total;
  }
  io.out(kZmp)[0] = last_zmp_[0];
  io.out(kZmp)[1] = last_zmp_[1];
  io.out(kTotalNormalForce)[0] = total;
}

}  // namespace ftsense::biped
