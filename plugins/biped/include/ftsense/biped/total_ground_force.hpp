#pragma once
// The total ground reaction force of a legged robot of any number of feet from its trunk IMU
// (method.md section 2, without the split between two legs):
//
//   F = m R_wb f_imu    [N], world frame,
//
// neglecting the limbs' inertia (the IMU's specific force f_imu includes gravity: a robot at rest
// reads +g up, so F = (0, 0, m g)). m is `mass_kg`, or with mass_source = "input" the value of
// input `mass` (for example the URDF's total mass from urdf_kinematics). A non-finite IMU reading
// or orientation gives NaN (not ready). support_force_distribution spreads F_z over the feet.
// Stateless; allocation-free.

#include <string_view>

#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class TotalGroundForce {
 public:
  static constexpr std::string_view name = "total_ground_force";
  static constexpr std::string_view summary = "F = m R_wb f_imu: the total ground reaction force of any legged robot";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"([{"mass_kg": 114.0}, {"mass_source": "input"}])";

  struct Params {
    double mass_kg = 0.0;
    enum class MassSource { param, input };
    MassSource mass_source = MassSource::param;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kImuAcc, kBaseRpy, kMass };
  enum Output : std::size_t { kTotalForce };

  TotalGroundForce(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  Params params_;
};

}  // namespace ftsense::biped
