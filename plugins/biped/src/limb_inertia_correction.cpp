#include "ftsense/biped/limb_inertia_correction.hpp"

#include <cmath>
#include <limits>

#include "ftsense/biped/stacked_feet.hpp"
#include "ftsense/low_pass_gain.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::biped {

void LimbInertiaCorrection::Params::describe(ParamSchema<Params>& schema) {
  schema.add("mass_kg", &Params::mass_kg, "total mass M of the robot, the M of F = M R_wb f_imu")
      .unit("kg").greater_than(0.0).plausible(plausible::robot_mass_kg());
  schema.add("leg_effective_mass_kg", &Params::leg_effective_mass_kg,
             "mass m_e that moves with each foot: sum over the leg's links of m_s rho_s, rho_s the link CoM's "
             "distance from the hip over the foot's (leg straight); below the leg's mass; 0: no correction")
      .unit("kg").at_least(0.0).plausible(0.0, 200.0, "a leg weighs grams to tens of kilograms");
  schema.add("cutoff_hz", &Params::cutoff_hz,
             "cut-off f_c of the two low-passes before the second difference: the legs' motion bandwidth, below "
             "1 / (2 T)")
      .unit("Hz").greater_than(0.0).plausible(plausible::cutoff_hz());
  schema.add("gravity_m_s2", &Params::gravity_m_s2, "gravitational acceleration g")
      .unit("m/s^2").greater_than(0.0).plausible(9.7, 9.9, "on Earth");
}

LimbInertiaCorrection::LimbInertiaCorrection(const Params& params, const StageContext& context)
    : params_(params), period_s_(context.sample_period_s()) {
  gain_ = low_pass_gain(params.cutoff_hz, period_s_);
  if (!(params.leg_effective_mass_kg < params.mass_kg)) {
    throw ConfigError("/params/leg_effective_mass_kg", " = " + format_number(params.leg_effective_mass_kg) +
                                                 " kg: a leg's effective mass is below the whole robot's (mass_kg = " +
                                                 format_number(params.mass_kg) + " kg)");
  }
  feet_ = stacked_feet(context, 2);
  ports_.add_input(PortSpec{"total_force", 3, "N", "total ground reaction force M R_wb f_imu", PortRole::virtual_estimate}
                       .in_frame("world"));
  ports_.add_input(PortSpec{"foot_pos", 3 * feet_, "m", "foot frame origins (x, y, z) stacked foot after foot"}
                       .in_frame("world")
                       .sized_by("as wired: 3 per foot"));
  ports_.add_output(PortSpec{"total_force", 3, "N", "F + m_e sum_i (a_i - a_t): with the legs' inertia"}
                        .in_frame("world"));
  feet_pos_.resize(3 * feet_);
}

void LimbInertiaCorrection::Smoothed::add(double x, double gain) noexcept {
  if (samples == 0) {
    first = second = x;
  } else {
    first += gain * (x - first);
    second += gain * (first - second);
  }
  history[2] = history[1];
  history[1] = history[0];
  history[0] = second;
  if (samples < 3) ++samples;
}

void LimbInertiaCorrection::reset() noexcept {
  for (auto& s : feet_pos_) s = Smoothed{};
  for (auto& s : trunk_) s = Smoothed{};
}

void LimbInertiaCorrection::step(const StepIO& io) noexcept {
  const auto force = io.in(kTotalForce);
  const auto foot_pos = io.in(kFootPos);
  const auto out = io.out(kCorrectedForce);
  bool finite = true;
  for (double v : force) finite = finite && std::isfinite(v);
  for (double v : foot_pos) finite = finite && std::isfinite(v);
  if (!finite) {
    for (double& v : out) v = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const double trunk_acc = force[axis] / params_.mass_kg - (axis == 2 ? params_.gravity_m_s2 : 0.0);
    trunk_[axis].add(trunk_acc, gain_);
  }
  for (std::size_t i = 0; i < feet_pos_.size(); ++i) feet_pos_[i].add(foot_pos[i], gain_);
  const double per_tick2 = 1.0 / (period_s_ * period_s_);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    double relative = 0.0;  // sum over the feet of a_i - a_t
    bool ready = trunk_[axis].samples == 3;
    for (std::size_t f = 0; f < feet_; ++f) {
      const Smoothed& p = feet_pos_[3 * f + axis];
      ready = ready && p.samples == 3;
      relative += p.second_difference() * per_tick2 - trunk_[axis].history[1];
    }
    // The second difference is centred on the middle sample: the trunk's acceleration of that tick.
    out[axis] = force[axis] + (ready ? params_.leg_effective_mass_kg * relative : 0.0);
  }
}

}  // namespace ftsense::biped
