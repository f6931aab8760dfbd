#pragma once
// The offline fit of InsoleVirtualSensor's coefficients on a healthy stretch of one foot.
//
// For each sensor j, over the samples t of the stretch where stance_j holds (the plugin's rule),
// least squares on the column-scaled design matrix
//
//   X_j = [ W, s_k(t) for k != j ]   (m_j x n),    y_j = s_j(t)   (m_j),    [N]
//   theta_j = argmin || X_j theta - y_j ||_2       = [a_j, c_jk (k != j)]
//
// solved by a column-pivoting Householder QR (no normal equations, no inverse). The fit refuses,
// with a FitError naming the sensor, when fewer than `min_samples_per_coefficient * n` stance
// samples exist, when a sample is not finite, or when X_j is ill-conditioned: its reciprocal
// condition estimate |R_nn| / |R_11| (of the scaled, pivoted R) is below `min_reciprocal_condition`
// (a sensor that never loads, or two sensors that always read alike).

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace insole {

class FitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FitOptions {
  double body_weight_N = 0.0;
  double contact_force_N = 5.0;
  int min_loaded_sensors = 2;
  double min_reciprocal_condition = 1e-6;
  std::size_t min_samples_per_coefficient = 20;
};

struct FootFit {
  std::vector<double> coefficients;     // n x n, the plugin's `coefficients`
  std::vector<double> rms_error_N;      // per sensor, over the whole stretch (stance and swing)
  std::vector<double> reciprocal_condition;  // per sensor
  std::vector<std::size_t> stance_samples;   // per sensor
};

// `samples` holds one healthy row per tick (m x n, newtons); `sensor_names` (n) name the sensors
// in messages.
[[nodiscard]] FootFit fit_foot(const Eigen::MatrixXd& samples,
                               const std::vector<std::string>& sensor_names,
                               const FitOptions& options);

}  // namespace insole
