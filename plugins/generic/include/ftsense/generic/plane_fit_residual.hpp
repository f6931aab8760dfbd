#pragma once
// Constraint residual "a rigid sole's loads lie on a plane": each contact point's reading less
// what the plane through its foot's other points gives at its position (analytical redundancy
// that holds through an impact, which the total force from a trunk IMU does not see).
//
// Model. Channels: feet x points_per_foot readings x_j [U], foot after foot. A rigid sole on
// pads of equal stiffness sinks by a plane, so in full contact each pad's load is affine in its
// position (x_i, y_i) [m] (`points`, foot frame, every foot alike): N_i = a + b x_i + c y_i. With
// P the rows [1 x_i y_i] and W the orthonormal basis of the null space of P^T (n - 3 relations
// for n >= 4 points not on a line; unmeasured_contact_loads.hpp), the loads satisfy W^T N_f = 0
// up to the sole's departure, and the projection Pi = W W^T (n x n) takes a foot's readings to
// what no plane explains. Channel j's row is the leave-one-out residual of that plane fit,
//
//   r_j = (Pi x_f)_j / Pi_jj = x_j - v_j,    v_j the plane fitted to the foot's other points,
//                                            evaluated at point j (its virtual sensor),
//
// so d r_j / d x_j = 1 (step_isolator's model) and a neighbour k enters it by Pi_jk / Pi_jj.
// Four pads on a rectangle (one relation w = (1, -1, -1, 1) / 2): r_1 = x_1 - x_2 - x_3 + x_4 and
// r_2 = x_2 - x_1 - x_4 + x_3, etc.: a step b on pad 1 moves r_1 by b and every other row by -+b.
//
// A foot's rows are finite only in full contact: every pad can carry load (input `loadable` at
// 1/2 or above, or NaN), reads a finite value above b_k = floor_k + z m sigma_k + q_k / 2 (a pad
// within its noise of zero may have lifted, and a lifted pad reads 0, not the plane's negative
// value; quantity_bounds.hpp's margin, with sigma and q the readings' noise and quantisation
// step measured by `ftsense calibrate`, z at one false alarm per `false_alarm_interval_s`,
// m = `noise_margin`), and, with `substituted` on, none stood for nothing on the tick before (a
// substituted reading is no load). With `correction` on, input c (a recovery's correction of the
// tick before) takes each reading as corrected, x_j - c_j, in the rows and in that test: a fault
// already found and corrected leaves the plane's level, so a step away from zero is a new fault
// (step_isolator's `judge_raised_rows`); a correction that is not finite leaves the foot unjudged.
// Without it the rows are the readings' own, as sum_constraint_residual's. A foot not in full
// contact has NaN rows (not judged downstream), and so has a point no relation involves
// (Pi_jj ~ 0). Points on a line keep the relations of a rigid bar (loads affine along it); three
// points not on a line keep none (a ConfigError).
//
// Allocation-free per tick; O(feet n^2) a tick.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/calibration.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class PlaneFitResidual {
 public:
  static constexpr std::string_view name = "plane_fit_residual";
  static constexpr std::string_view summary =
      "each contact point's reading less the plane its foot's other points give at it, in full contact";
  static constexpr std::string_view example_params =
      R"([{"points_per_foot": 4, "points": [[0.12, 0.075], [0.12, -0.075], [-0.12, 0.075], [-0.12, -0.075]]}, {"points_per_foot": 5, "points": [[0.12, 0.075], [0.12, -0.075], [-0.12, 0.075], [-0.12, -0.075], [0.0, 0.0]], "loadable": true, "correction": true, "substituted": true}])";

  // `ftsense calibrate` measures each reading's white noise and quantisation step (tick_noise.hpp).
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
  });

  struct Params {
    int points_per_foot = 4;
    std::vector<std::array<double, 2>> points{};
    bool loadable = false;
    bool correction = false;
    bool substituted = false;
    std::vector<double> floor{0.0};
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    double noise_margin = 1.5;
    double false_alarm_interval_s = 86400.0;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  // Inputs: signal, then those switched on, in the order loadable, correction, substituted.
  enum Input : std::size_t { kSignal };
  enum Output : std::size_t { kResidual };

  PlaneFitResidual(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

  // Pi_jk / Pi_jj: how reading k enters row j (1 for k = j; 0 where row j enters no relation).
  [[nodiscard]] double row_weight(std::size_t point, std::size_t of_point) const noexcept {
    return row_[point * points_per_foot_ + of_point];
  }
  // The bound b_k above which a pad counts as loaded [U].
  [[nodiscard]] double loaded_above(std::size_t k) const noexcept { return loaded_above_[k]; }

 private:
  Ports ports_;
  bool loadable_wired_ = false;
  bool correction_wired_ = false;
  bool substituted_wired_ = false;
  std::size_t points_per_foot_ = 4;
  std::size_t feet_ = 0;
  std::vector<double> row_;           // points x points, row-major: Pi_jk / Pi_jj (NaN row: no relation)
  std::vector<double> loaded_above_;  // per channel, b_k
  std::vector<double> loads_;         // work: one foot's readings as corrected
};

}  // namespace ftsense::generic
