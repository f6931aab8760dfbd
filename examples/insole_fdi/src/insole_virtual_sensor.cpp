#include "insole/insole_virtual_sensor.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "ftsense/diagnostics.hpp"

namespace insole {

// [snippet:describe]
void InsoleVirtualSensor::Params::describe(ftsense::ParamSchema<Params>& s) {
  s.add("body_weight_N", &Params::body_weight_N, "body weight W = m g of the wearer")
      .unit("N").greater_than(0).required();
  s.add("coefficients", &Params::coefficients,
        "fitted model, n x n row-major: row j = [a_j, c_jk for k != j] (insole_fdi fit writes it)")
      .required().count_at_least(4);
  s.add("contact_force_N", &Params::contact_force_N, "a sensor reading above this is loaded")
      .unit("N").at_least(0);
  s.add("min_loaded_sensors", &Params::min_loaded_sensors,
        "stance for sensor j when at least this many of the other sensors are loaded")
      .at_least(1);
}
// [end-snippet]

// [snippet:constructor]
InsoleVirtualSensor::InsoleVirtualSensor(const Params& params, const ftsense::StageContext& context)
    : sensor_count_(context.wired_dim("measured", 8)),
      body_weight_N_(params.body_weight_N),
      contact_force_N_(params.contact_force_N),
      min_loaded_sensors_(static_cast<std::size_t>(params.min_loaded_sensors)),
      coefficients_(params.coefficients) {  // the only allocation: done once, here
  const std::string where = "/params";  // the pipeline puts it under /stages/<i>
  ftsense::Diagnostics diag;
  const std::size_t n = sensor_count_;
  if (n < 2) {
    diag.error(where, "insole_virtual_sensor needs at least 2 sensors wired to 'measured', got " +
                          std::to_string(n));
  }
  if (coefficients_.size() != n * n) {
    diag.error(where + "/coefficients",
               "has " + std::to_string(coefficients_.size()) + " numbers, expected n x n = " +
                   std::to_string(n * n) + " for the " + std::to_string(n) +
                   " sensors wired to 'measured'; run `insole_fdi fit` to write them");
  }
  if (n >= 2 && min_loaded_sensors_ > n - 1) {
    diag.error(where + "/min_loaded_sensors",
               "= " + std::to_string(min_loaded_sensors_) + " exceeds the " +
                   std::to_string(n - 1) + " other sensors of a foot");
  }
  if (diag.has_errors()) throw ftsense::ConfigError(diag.errors());

  ports_.add_input({"measured", n, "N", "the n sensors of one foot", ftsense::PortRole::measured});
  ports_.add_output({"virtual", n, "N", "s_hat_j from the other sensors and the body weight",
                     ftsense::PortRole::signal, /*leave_one_out=*/true});
  ports_.add_output({"residual", n, "N", "r_j = s_j - s_hat_j"});
  ports_.add_output({"stance", n, "1", "1 when the other sensors say the foot is loaded"});
  ports_.add_output({"available", n, "1", "0 when a sensor s_hat_j needs is not finite"});
  ports_.add_output({"signature", n * n, "1",
                     "d r_j / d s_k, n x n row-major: 1 on the diagonal, -c_jk in stance, 0 in swing"});
}
// [end-snippet]

// [snippet:step]
void InsoleVirtualSensor::step(const ftsense::StepIO& io) noexcept {
  const auto measured = io.in(kMeasured);
  const auto estimate = io.out(kVirtual);
  const auto residual = io.out(kResidual);
  const auto stance = io.out(kStance);
  const auto available = io.out(kAvailable);
  const auto signature = io.out(kSignature);
  const std::size_t n = sensor_count_;
  for (std::size_t j = 0; j < n; ++j) {
    const double* row = coefficients_.data() + j * n;  // [a_j, c_jk for k != j]
    double sum = row[0] * body_weight_N_;
    std::size_t loaded = 0;
    bool finite = true;
    for (std::size_t k = 0, column = 1; k < n; ++k) {
      if (k == j) continue;  // leave-one-out: s_j never enters s_hat_j
      const double s = measured[k];
      finite = finite && std::isfinite(s);
      loaded += s > contact_force_N_ ? 1 : 0;
      sum += row[column++] * s;
    }
    const bool on_ground = loaded >= min_loaded_sensors_;
    stance[j] = on_ground ? 1.0 : 0.0;
    available[j] = finite ? 1.0 : 0.0;
    if (!finite) estimate[j] = std::numeric_limits<double>::quiet_NaN();
    else estimate[j] = on_ground ? sum : 0.0;  // swing: an unloaded insole reads 0
    residual[j] = measured[j] - estimate[j];
    // How a fault on s_k moves r_j: fully for k = j, by -c_jk while s_hat_j is the regression.
    for (std::size_t k = 0, column = 1; k < n; ++k) {
      if (k == j) {
        signature[j * n + k] = 1.0;
        continue;
      }
      const double c_jk = row[column++];
      signature[j * n + k] = on_ground ? -c_jk : 0.0;
    }
  }
}
// [end-snippet]

}  // namespace insole
