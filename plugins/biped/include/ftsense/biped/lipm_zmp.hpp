#pragma once
// The ZMP from the CoM and the total ground reaction force, on the inverted pendulum (issue 14).
//
// Neglecting the angular momentum about the CoM, the total ground reaction force F (world frame,
// N; e.g. total_ground_force's m R_wb f_imu, which includes gravity) acts along the line from the
// ZMP p on the ground to the CoM c. With the ground at height z_g:
//
//   p_xy = c'_xy - (c'_z - z_g) F_xy / F_z,     c' = c + (dx, dy, 0),     z_g = min_i o_i,z
//
// (F_xy / F_z = a_xy / (g + a_z) for the CoM acceleration a: the LIPM's p = c - z_c c''_xy / g
// when a_z = 0). o_i are the feet's frame origins (3 per foot, world frame, m): on flat ground one
// foot is always down, so the lowest is the ground. (dx, dy) = (`com_offset_x_m`, `com_offset_y_m`)
// is a constant world-frame correction of the CoM for a model whose mass distribution is off
// (calibrated where the robot stands still and the ZMP is known; defaults 0). It is fixed in the
// world frame, so it holds while the heading stays put.
//
// Output zmp (x, y) [m], world frame. NaN (not ready) when an input is not finite or F_z <= 0
// (nothing pushes on the ground, so there is no ZMP). Stateless; allocation-free. Low-pass F
// upstream (low_pass) for a trunk IMU's vibration: F_xy / F_z of one tick is noisy.

#include <string_view>

#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class LipmZmp {
 public:
  static constexpr std::string_view name = "lipm_zmp";
  static constexpr std::string_view summary =
      "ZMP p = c - (c_z - z_g) F_xy / F_z from the CoM and the total ground force (inverted pendulum)";

  struct Params {
    double com_offset_x_m = 0.0;
    double com_offset_y_m = 0.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kTotalForce, kCom, kFootPos };
  enum Output : std::size_t { kZmp };

  LipmZmp(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  Params params_;
  std::size_t feet_;
};

}  // namespace ftsense::biped
