#pragma once
// Static crawl for the quadruped: one foot swings at a time, order lh, lf, rh, rf, and the CoM
// stays inside the triangle of the three stance feet while a foot is in the air.
//
// Timeline: stand initial_stand_s with the CoM at the centre of the four feet; then num_cycles
// cycles of cycle_s, each four slots of T = cycle_s / 4, one per leg in kCrawlOrder. Slot n:
//   shift  (1 - swing_ratio) T, all four feet down: the CoM moves from the previous target to
//          target n with s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5 (zero velocity and acceleration
//          at both ends);
//   swing  swing_ratio T: the CoM holds target n; the slot's foot moves stride_m forward,
//          xy = xy0 + (stride, 0) s(tau), z = r + h 16 tau^2 (1 - tau)^2 (r the foot radius, h
//          step_height_m): lift-off and touchdown with zero velocity.
// After the last slot a final shift of (1 - swing_ratio) T brings the CoM back to the centre of
// the four feet (then standing). Speed = stride_m / cycle_s.
// Footholds (foot sphere centres, world): (+-hip_x, +-stance_half_width_m, r) at the start, each
// leg's x advancing by stride_m per cycle.
// CoM target of slot n: the mean of the three stance feet and the swing foot's mid-stride point
// (where a body at constant speed would be), moved to the nearest point whose distance from
// every edge of the stance triangle is at least stability_margin_m (projection onto the
// intersection of the three inset half-planes). The CoM's ground projection then stays at least
// stability_margin_m inside the support triangle throughout the swing, and inside the support
// quadrilateral during the shift (both targets lie in it; it is convex).
// Units: m, s.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace ftsense::sim {

struct CrawlParams {
  double stride_m = 0.08;          ///< forward step of each foot per cycle
  double cycle_s = 4.0;            ///< all four feet step once
  double swing_ratio = 0.5;        ///< share of each leg's slot spent swinging
  double step_height_m = 0.04;     ///< swing foot apex above the ground
  double body_height_m = 0.30;     ///< hip points (trunk centre) above the ground
  double stance_half_width_m = 0.12;  ///< feet at y = +-this (the hips are at +-0.10)
  double stability_margin_m = 0.03;   ///< CoM distance from the support triangle's edges in swing
  double initial_stand_s = 1.5;
  int num_cycles = -1;             ///< < 0: as many as end at least 1 s before the duration
};

/// Swing order as leg indices of kQuadrupedLegs: lh, lf, rh, rf.
inline constexpr std::array<int, 4> kCrawlOrder = {2, 0, 3, 1};

struct CrawlSample {
  Eigen::Vector2d com = Eigen::Vector2d::Zero();  ///< planned CoM (x, y), world
  std::array<Eigen::Vector3d, 4> foot{};           ///< foot sphere centres, world, kQuadrupedLegs order
  std::array<bool, 4> contact{true, true, true, true};
  int swing_leg = -1;                              ///< the leg in the air, -1: none
};

class CrawlPlan {
 public:
  /// Throws std::invalid_argument if the inset stance triangle is empty (margin too large).
  CrawlPlan(const CrawlParams& params, double hip_x_m, double foot_radius_m, double duration_s);

  [[nodiscard]] CrawlSample sample(double t) const;
  [[nodiscard]] int num_cycles() const { return cycles_; }
  [[nodiscard]] const CrawlParams& params() const { return p_; }
  /// Time at which the last slot and the final shift are finished.
  [[nodiscard]] double walk_end_s() const;
  /// Smallest distance of a CoM target from its stance triangle's edges (>= stability_margin_m).
  [[nodiscard]] double min_margin_m() const { return min_margin_; }

 private:
  struct Slot {
    int leg;
    std::array<Eigen::Vector2d, 4> feet;  // footholds during the slot's shift (before its swing)
    Eigen::Vector2d com_from, com_to;
  };
  CrawlParams p_;
  double r_;
  int cycles_ = 0;
  std::vector<Slot> slots_;
  std::array<Eigen::Vector2d, 4> final_feet_{};
  Eigen::Vector2d final_com_ = Eigen::Vector2d::Zero();
  double min_margin_ = 0.0;
};

/// Signed distance of p from the boundary of the convex hull of `points` (positive inside), m.
/// With fewer than three points that are not collinear: minus the distance to the hull (a
/// segment or a point), so the value is never positive.
[[nodiscard]] double support_margin_m(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& points);

}  // namespace ftsense::sim
