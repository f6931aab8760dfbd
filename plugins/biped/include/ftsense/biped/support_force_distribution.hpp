#pragma once
// The total vertical ground reaction force spread over any number of feet in contact (issue 14:
// N contacts; two feet, four, or a hexapod's six, up to kMaxContactPoints = 8).
//
// Model: n feet with origins o_i (world frame, m), contact c_i (1 in contact), the total ground
// reaction force F (world frame, N, e.g. leg_force_split's m R_wb f_imu) and the point p (x, y)
// where its vertical part acts (the ZMP; quasi-static gaits: the CoM's ground projection, which
// a wire such as "com.com[0:2]" selects). On flat ground the feet in contact carry normal forces
// f_i with
//
//     sum_i f_i = F_z,     sum_i f_i (o_i - o_bar)_xy = F_z (p - o_bar)_xy,     f_i >= 0,
//
// o_bar the mean of the feet in contact (coordinates centred for conditioning). Two feet make the
// moment line exact (the lever rule); three in general position fix f exactly; four or more leave
// a family, and the least-norm member is taken. It is the QP of contact_force_qp.hpp with the
// feet as its points:
//
//     minimise || C f - F_z (p - o_bar) ||^2 + w ||f||^2   s.t. 1^T f = F_z, f >= 0,
//
// solved exactly by ActiveSetContactQp (KKT-checked in the tests). w = `weight_m2` (default
// 1e-6 m^2) is small against the support's sum of squared offsets (0.01 to 1 m^2 for legged
// robots), so the moments are met to about w / sum x^2 relative while p lies inside the support
// polygon; outside it, f >= 0 cannot meet them and the QP gives the nearest it can (the foot
// nearest p carries the most).
//
// Outputs per foot: normal force [N] (0 for a foot in swing). NaN for every foot when F_z, p, the
// contact states or the position of a foot in contact is not finite (the virtual sensor is not
// ready); 0 everywhere when no foot is in contact (flight). Allocation-free: the solver is rebuilt
// each tick from fixed-capacity matrices.

#include <string_view>

#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class SupportForceDistribution {
 public:
  static constexpr std::string_view name = "support_force_distribution";
  static constexpr std::string_view summary =
      "total vertical force over N feet in contact: sum and moment about the ZMP met, least-norm (QP)";

  struct Params {
    double weight_m2 = 1e-6;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kTotalForce, kCop, kFootPos, kContact };
  enum Output : std::size_t { kForces };

  SupportForceDistribution(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  double weight_m2_;
  std::size_t feet_;
};

}  // namespace ftsense::biped
