#pragma once
// Footstep schedule, planned ZMP and swing-foot trajectories for straight slow walking.
//
// Timeline: stand for initial_stand_s with the ZMP midway between the feet; then num_steps steps
// of step_time_s T, each a double-support phase of length rT (r = double_support_ratio; the ZMP
// moves linearly to the new support foot) followed by single support of length (1-r)T (ZMP at
// the support foot's sole centre, the other foot swings); then a final double-support phase of
// length rT bringing the ZMP back midway, and standing.
// Footprints: F0 = right (0, -w), F1 = left (0, +w), F_{k+2} = (min(k+1, n-1) L, +-w) where step k
// swings the foot at F_k to F_{k+2} while F_{k+1} supports (the right foot swings first; the last
// step brings the feet side by side).
// Swing foot, tau = time in single support / its length, in [0, 1]:
//   xy(tau) = xy0 + (xy1 - xy0) s(tau),  s = 10 tau^3 - 15 tau^4 + 6 tau^5
//   z(tau)  = h 16 tau^2 (1 - tau)^2
// so the foot lifts off and lands with zero velocity in every axis (and zero horizontal
// acceleration); the vertical profile leaves the ground faster than a quintic, so the foot does
// not graze the floor right after lift-off.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace ftsense::sim {

struct GaitParams {
  double step_length_m = 0.15;
  double step_time_s = 1.0;
  double double_support_ratio = 0.2;
  int num_steps = -1;             ///< < 0: as many as fit into the scenario duration
  double step_height_m = 0.04;
  double initial_stand_s = 1.5;
  double pelvis_height_m = 0.60;  ///< pelvis origin (hip points) above the ground
  double preview_s = 1.6;
  double foot_half_spacing_m = 0.10;  ///< lateral distance of each sole centre from the midline
  /// Controller: the pelvis reference (x, y) is shifted by
  ///   com_feedback_gain e + com_feedback_integral_gain_1_s integral(e dt),  e = planned - true CoM.
  double com_feedback_gain = 2.0;
  double com_feedback_integral_gain_1_s = 2.0;
};

struct GaitSample {
  Eigen::Vector2d zmp = Eigen::Vector2d::Zero();          ///< planned ZMP (world, m)
  std::array<Eigen::Vector3d, 2> sole{};                  ///< sole frame origin, 0 left, 1 right
  std::array<bool, 2> contact{true, true};                ///< planned contact, 0 left, 1 right
  /// Weight in [0, 1] of the swing-foot levelling correction (see simulator): rises with a
  /// smoothstep over the first 15 % of the foot's swing, falls with a smoothstep over the double
  /// support after its landing, 0 otherwise.
  std::array<double, 2> swing_weight{0.0, 0.0};
};

class GaitPlan {
 public:
  /// num_steps < 0 in params is resolved so that the walk plus final double support ends at
  /// least 1 s before duration_s.
  GaitPlan(const GaitParams& params, double duration_s);

  [[nodiscard]] GaitSample sample(double t) const;
  [[nodiscard]] int num_steps() const { return n_; }
  [[nodiscard]] const GaitParams& params() const { return p_; }
  [[nodiscard]] const std::vector<Eigen::Vector2d>& footprints() const { return fp_; }
  /// Time at which the last step (including the final double support) is finished.
  [[nodiscard]] double walk_end_s() const;

 private:
  GaitParams p_;
  int n_ = 0;
  std::vector<Eigen::Vector2d> fp_;
};

}  // namespace ftsense::sim
