#include "ftsense/biped/leg_force_split.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ftsense/biped/frames.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::biped {

void LegForceSplit::Params::describe(ParamSchema<Params>& schema) {
  schema.add("mass_kg", &Params::mass_kg, "total robot mass m; required unless mass_source is input")
      .unit("kg").at_least(0.0).plausible(plausible::robot_mass_kg());
  schema.add("lateral_reach_m", &Params::lateral_reach_m,
             "c_lat_max of eq. 7; 0 records |c_lat| at each single-support onset")
      .unit("m").at_least(0.0)
      .plausible(0.0, 1.0, "a CoM is centimetres to tens of centimetres beside a foot");
  schema.add("gravity_m_s2", &Params::gravity_m_s2,
             "gravity g; a flight (no foot in contact) with a vertical specific force above g / 2 "
             "contradicts the IMU")
      .unit("m/s^2").greater_than(0.0).plausible(1.5, 15.0, "9.81 on Earth, 1.62 on the Moon, 3.71 on Mars");
  schema.add_choice("mass_source", &Params::mass_source,
                    "where m comes from: mass_kg, or input port mass (e.g. the URDF's total mass)",
                    {{"param", MassSource::param}, {"input", MassSource::input}});
}

void LegForceSplit::Params::validate(Diagnostics& diag, std::string_view path) const {
  if (mass_source == MassSource::param && !(mass_kg > 0.0)) {
    diag.error(json_pointer_append(path, "mass_kg"),
               "a total robot mass > 0 is required with mass_source = param (or set mass_source to input)");
  }
}

LegForceSplit::LegForceSplit(const Params& params, const StageContext& /*context*/) : params_(params) {
  ports_.add_input(PortSpec{"imu_acc", 3, "m/s^2", "IMU specific force f_imu (the IMU is on the trunk)"}
                       .in_frame("imu"));
  ports_.add_input(PortSpec{"base_rpy", 3, "rad", "trunk orientation roll, pitch, yaw (R_wb)"}
                       .in_frame("base in world"));
  ports_.add_input(PortSpec{"com", 3, "m", "CoM position"}.in_frame("world"));
  ports_.add_input(PortSpec{"l_foot_pos", 3, "m", "left foot frame origin o_L"}.in_frame("world"));
  ports_.add_input(PortSpec{"r_foot_pos", 3, "m", "right foot frame origin o_R"}.in_frame("world"));
  ports_.add_input({"contact", 2, "1", "contact state (left, right) from the gait schedule, 0 or 1"});
  if (params.mass_source == Params::MassSource::input) {
    ports_.add_input({"mass", 1, "kg", "total robot mass m (mass_source = input)"});
  }
  ports_.add_output(PortSpec{"l_force", 3, "N", "left foot ground reaction force F_L"}.in_frame("world"));
  ports_.add_output(PortSpec{"r_force", 3, "N", "right foot ground reaction force F_R"}.in_frame("world"));
  ports_.add_output(PortSpec{"total_force", 3, "N", "total ground reaction force F = m R_wb f_imu"}.in_frame("world"));
  ports_.add_output({"alpha", 1, "1", "split factor alpha in [-1, 1]; NaN when the split is unknown"});
}

void LegForceSplit::reset() noexcept {
  recorded_reach_m_ = 0.0;
  was_double_support_ = true;
}

void LegForceSplit::step(const StepIO& io) noexcept {
  const auto contact = io.in(kContact);
  const bool left = contact[0] > 0.5;
  const bool right = contact[1] > 0.5;
  // Without a finite IMU reading, orientation or contact state the total force is unknown: NaN
  // tells the stages downstream that the virtual sensor is not ready (a zero would be a value).
  Eigen::Vector3d total = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  if (all_finite(io.in(kImuAcc)) && all_finite(io.in(kBaseRpy))) {
    const double mass = params_.mass_source == Params::MassSource::input ? io.in(kMass)[0] : params_.mass_kg;
    total = ground_reaction_force(mass, io.in(kBaseRpy), io.in(kImuAcc));
  }
  if (!all_finite(contact)) total.setConstant(std::numeric_limits<double>::quiet_NaN());
  const Eigen::Vector3d o_l = vector3(io.in(kLeftFootPos));
  const Eigen::Vector3d o_r = vector3(io.in(kRightFootPos));
  const Eigen::Vector3d c = vector3(io.in(kCom));
  const Eigen::Vector2d across = (o_l - o_r).head<2>();
  const double distance = across.norm();
  const Eigen::Vector2d u = distance > 1e-6 ? Eigen::Vector2d(across / distance) : Eigen::Vector2d(0.0, 1.0);
  const double c_lat = (c - 0.5 * (o_l + o_r)).head<2>().dot(u);
  // A stance foot's force runs along its line to the CoM; leaning beyond 45 degrees it would need
  // a friction coefficient above 1: the CoM or the foot position is wrong, the split unknown.
  const auto beyond_friction = [&c](const Eigen::Vector3d& o) {
    return (c - o).head<2>().norm() > c.z() - o.z();
  };
  // In double support the split needs the CoM; in single support it is +-1 whatever the CoM.
  const bool split_known = (!(left && right) || std::isfinite(c_lat)) && !(left && beyond_friction(o_l)) &&
                           !(right && beyond_friction(o_r));
  if (was_double_support_ && left != right && std::isfinite(c_lat) && std::abs(c_lat) > 1e-3) {
    recorded_reach_m_ = std::abs(c_lat);
  }
  was_double_support_ = left && right;
  double reach = params_.lateral_reach_m > 0.0 ? params_.lateral_reach_m : recorded_reach_m_;
  if (!(reach > 1e-3)) reach = std::max(0.5 * distance, 1e-3);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double alpha = 0.0;
  if (left && right) {
    alpha = split_known ? std::clamp(c_lat / reach, -1.0, 1.0) : kNaN;
  } else if (left) {
    alpha = split_known ? 1.0 : kNaN;
  } else if (right) {
    alpha = split_known ? -1.0 : kNaN;
  } else if (!all_finite(contact)) {
    alpha = kNaN;  // the schedule is unknown, so is the split (total is NaN too)
  } else {
    const double mass = params_.mass_source == Params::MassSource::input ? io.in(kMass)[0] : params_.mass_kg;
    // Flight: a free fall reads about 0, so a robot held up (about g) contradicts the schedule.
    const bool held = !(total.z() <= 0.5 * params_.gravity_m_s2 * mass);
    if (held) {
      total.setConstant(kNaN);
      alpha = kNaN;
    } else {
      total.setZero();  // no ground force to split
    }
  }
  const auto fl = io.out(kLeftForce);
  const auto fr = io.out(kRightForce);
  const auto ft = io.out(kTotalForce);
  for (int i = 0; i < 3; ++i) {
    fl[i] = 0.5 * (1.0 + alpha) * total[i];
    fr[i] = 0.5 * (1.0 - alpha) * total[i];
    ft[i] = total[i];
  }
  io.out(kAlpha)[0] = alpha;
}

}  // namespace ftsense::biped
