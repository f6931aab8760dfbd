#pragma once
// A virtual sensor for a pressure insole: every sensor of one foot predicted from the other
// sensors of the same foot and the body weight. A user's own ftsense plugin (not part of ftsense).
//
// Model, per foot with n sensors s_1..s_n [N] and body weight W [N] (m g):
//
//   stance_j  = #{ k != j : s_k > contact_force_N } >= min_loaded_sensors
//   s_hat_j   = a_j W + sum_{k != j} c_jk s_k     when stance_j       [N]
//             = 0                                  otherwise (swing: an unloaded insole reads 0)
//
// The coefficients come from a least-squares fit on a healthy stretch (insole_fit.hpp): row j of
// `coefficients` is [a_j, c_jk for k = 1..n, k != j] (n numbers), rows in sensor order, n x n in
// all. s_hat_j never reads s_j, so the `virtual` output is declared leave-one-out: it may judge the
// very sensors it is computed from, channel by channel.
//
// A non-finite s_k makes every s_hat_j that needs it unavailable: s_hat_j = NaN and
// available_j = 0 (the plugin never invents a value it cannot compute).
//
// Ports: input `measured` [N], n values (n from the wiring); outputs `virtual` [N],
// `residual` [N] (r_j = s_j - s_hat_j), `stance` [1] (stance_j as 0/1) and `available` [1] (0/1),
// n values each; `signature` [1], n x n: d r_j / d s_k (1 for k = j; -c_jk in stance, 0 in swing),
// how a fault on one sensor moves every residual, for signature_isolator. ftsense's independence
// rule, in a stage as in the monitor, accepts a leave-one-out output as the virtual sensor of
// exactly the measured signal it leaves out, so `virtual` could also be wired into a
// difference_residual next to `measured`; the `residual` output saves that stage.

// [snippet:plugin_struct]
#include <cstddef>
#include <string_view>
#include <vector>

#include "ftsense/params.hpp"
#include "ftsense/plugin.hpp"
#include "ftsense/ports.hpp"

namespace insole {

class InsoleVirtualSensor {
 public:
  static constexpr std::string_view name = "insole_virtual_sensor";
  static constexpr std::string_view summary =
      "each insole sensor predicted from the other sensors of its foot and the body weight";

  // Port indices, in the order the constructor declares them.
  static constexpr std::size_t kMeasured = 0;  // input
  static constexpr std::size_t kVirtual = 0;   // outputs
  static constexpr std::size_t kResidual = 1;
  static constexpr std::size_t kStance = 2;
  static constexpr std::size_t kAvailable = 3;
  static constexpr std::size_t kSignature = 4;

  struct Params {
    double body_weight_N = 0.0;
    std::vector<double> coefficients;
    double contact_force_N = 5.0;
    int min_loaded_sensors = 2;
    static void describe(ftsense::ParamSchema<Params>& s);
  };

  InsoleVirtualSensor(const Params& params, const ftsense::StageContext& context);

  [[nodiscard]] const ftsense::Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const ftsense::StepIO& io) noexcept;

  [[nodiscard]] std::size_t sensor_count() const noexcept { return sensor_count_; }

 private:
  std::size_t sensor_count_;
  double body_weight_N_;
  double contact_force_N_;
  std::size_t min_loaded_sensors_;
  std::vector<double> coefficients_;  // n x n, row j = [a_j, c_jk (k != j)]
  ftsense::Ports ports_;
};

}  // namespace insole
// [end-snippet]
