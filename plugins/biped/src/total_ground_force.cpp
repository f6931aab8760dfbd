#include "ftsense/biped/total_ground_force.hpp"

#include <limits>

#include "ftsense/biped/frames.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::biped {

void TotalGroundForce::Params::describe(ParamSchema<Params>& schema) {
  schema.add("mass_kg", &Params::mass_kg, "total robot mass m; required unless mass_source is input")
      .unit("kg").at_least(0.0).plausible(plausible::robot_mass_kg());
  schema.add_choice("mass_source", &Params::mass_source,
                    "where m comes from: mass_kg, or input port mass (e.g. the URDF's total mass)",
                    {{"param", MassSource::param}, {"input", MassSource::input}});
}

void TotalGroundForce::Params::validate(Diagnostics& diag, std::string_view path) const {
  if (mass_source == MassSource::param && !(mass_kg > 0.0)) {
    diag.error(json_pointer_append(path, "mass_kg"),
               "a total robot mass > 0 is required with mass_source = param (or set mass_source to input)");
  }
}

TotalGroundForce::TotalGroundForce(const Params& params, const StageContext& /*context*/) : params_(params) {
  ports_.add_input(PortSpec{"imu_acc", 3, "m/s^2", "IMU specific force f_imu (the IMU is on the trunk)"}
                       .in_frame("imu"));
  ports_.add_input(PortSpec{"base_rpy", 3, "rad", "trunk orientation roll, pitch, yaw (R_wb)"}
                       .in_frame("base in world"));
  if (params.mass_source == Params::MassSource::input) {
    ports_.add_input({"mass", 1, "kg", "total robot mass m (mass_source = input)"});
  }
  ports_.add_output(PortSpec{"total_force", 3, "N", "total ground reaction force F = m R_wb f_imu"}.in_frame("world"));
}

void TotalGroundForce::step(const StepIO& io) noexcept {
  const auto out = io.out(kTotalForce);
  if (!all_finite(io.in(kImuAcc)) || !all_finite(io.in(kBaseRpy))) {
    out[0] = out[1] = out[2] = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const double mass = params_.mass_source == Params::MassSource::input ? io.in(kMass)[0] : params_.mass_kg;
  const Eigen::Vector3d f = ground_reaction_force(mass, io.in(kBaseRpy), io.in(kImuAcc));
  out[0] = f.x();
  out[1] = f.y();
  out[2] = f.z();
}

}  // namespace ftsense::biped
