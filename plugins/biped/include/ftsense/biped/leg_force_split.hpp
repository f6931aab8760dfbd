#pragma once
// Total ground reaction force and its split between the legs (method.md section 2; paper eq. 6-9).
//
// Neglecting limb inertia, the total ground reaction force is F = m R_wb f_imu [N] (the IMU's
// specific force includes gravity). It is split by the CoM's position along the axis joining the
// feet (so turning gaits work):
//
//   u     = (o_L - o_R)_xy / |o_L - o_R|_xy                (unit vector, right foot -> left foot)
//   c_lat = (c - (o_L + o_R) / 2)_xy . u                   (lateral CoM relative to the midpoint)
//   alpha = clamp(c_lat / c_lat_max, -1, 1),   F_L = (1 + alpha) F / 2,   F_R = (1 - alpha) F / 2
//
// c_lat_max is `lateral_reach_m` when > 0; otherwise it is recorded as |c_lat| at each onset of
// single support (starting from half the feet's distance). A foot the contact schedule says is in
// swing carries nothing (alpha = +-1). A non-finite IMU reading, orientation or contact state with
// a foot possibly in contact makes the forces NaN: the virtual sensor is not ready, and the stages
// downstream pass that on. Two physical checks make it not ready too:
//   - neither foot in contact (flight) while the vertical specific force (R_wb f_imu)_z is above
//     g / 2: a robot in flight falls freely (0), one that is held reads about g, so the schedule
//     contradicts the IMU and the ground force is unknown (every output NaN). In a true flight
//     all forces are zero;
//   - a foot in contact whose line to the CoM leans more than 45 degrees,
//     |c - o_i|_xy > c_z - o_{i,z}: its force along that line would need a friction coefficient
//     above 1, which no sole has, so the CoM (or the foot's position) is wrong. The split is then
//     unknown (l_force, r_force NaN); the total force F does not depend on c and stays.
//     A CoM that is not ready (NaN) in double support leaves the split unknown as well (in single
//     support alpha is +-1 whatever the CoM). In flight, a non-finite IMU gives NaN, not zero.
// o_L, o_R are the foot frame origins (sole plane under the ankle) in the world frame [m].
// m is `mass_kg`, or with mass_source = "input" the value of input `mass` (for example the URDF's
// total mass from urdf_kinematics).

#include <string_view>

#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class LegForceSplit {
 public:
  static constexpr std::string_view name = "leg_force_split";
  static constexpr std::string_view summary =
      "F = m R_wb f_imu split between the feet by the lateral CoM (paper eq. 6-9)";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"([{"mass_kg": 114.0}, {"mass_source": "input"}])";

  struct Params {
    double mass_kg = 0.0;
    double lateral_reach_m = 0.0;
    double gravity_m_s2 = 9.806;
    enum class MassSource { param, input };
    MassSource mass_source = MassSource::param;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kImuAcc, kBaseRpy, kCom, kLeftFootPos, kRightFootPos, kContact, kMass };
  enum Output : std::size_t { kLeftForce, kRightForce, kTotalForce, kAlpha };

  LegForceSplit(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  Params params_;
  double recorded_reach_m_ = 0.0;
  bool was_double_support_ = true;
};

}  // namespace ftsense::biped
