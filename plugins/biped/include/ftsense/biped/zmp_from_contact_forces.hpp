#pragma once
// The ZMP measured by the foot force sensors: the centre of pressure of all contact points,
//
//   p = sum_l N_l (o_f + R_f [x_l, y_l, 0])_xy / sum_l N_l      over both feet's points,
//
// with o_f, R_f each foot's frame origin and orientation (world). It is computed FROM the
// monitored sensors: a virtual sensor fed with it is not independent of them, and the pipeline's
// independence rule says so (this is the paper's literal choice; method.md section 0). When the
// total load is below min_total_force_N the last ZMP is held. Non-finite pad forces count as 0.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class ZmpFromContactForces {
 public:
  static constexpr std::string_view name = "zmp_from_contact_forces";
  static constexpr std::string_view summary =
      "ZMP as the centre of pressure of both feet's measured contact-point forces";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"({"points": [[0.12, 0.075], [0.12, -0.075], [-0.12, 0.075], [-0.12, -0.075]]})";

  struct Params {
    std::vector<std::array<double, 2>> points;
    double min_total_force_N = 10.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kLeftForces, kRightForces, kLeftPos, kLeftRpy, kRightPos, kRightRpy };
  enum Output : std::size_t { kZmp, kTotalNormalForce };

  ZmpFromContactForces(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  std::vector<std::array<double, 2>> points_;
  double min_total_force_N_;
  double last_zmp_[2] = {0.0, 0.0};
};

}  // namespace ftsense::biped
