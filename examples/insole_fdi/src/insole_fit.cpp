#include "insole/insole_fit.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/QR>

namespace insole {
namespace {

bool in_stance(const Eigen::MatrixXd& samples, Eigen::Index t, Eigen::Index j,
               const FitOptions& options) {
  int loaded = 0;
  for (Eigen::Index k = 0; k < samples.cols(); ++k) {
    if (k != j && samples(t, k) > options.contact_force_N) ++loaded;
  }
  return loaded >= options.min_loaded_sensors;
}

}  // namespace

FootFit fit_foot(const Eigen::MatrixXd& samples, const std::vector<std::string>& sensor_names,
                 const FitOptions& options) {
  const Eigen::Index n = samples.cols();
  if (n < 2 || static_cast<std::size_t>(n) != sensor_names.size()) {
    throw FitError("fit: need at least 2 sensors and one name per sensor");
  }
  if (!(options.body_weight_N > 0.0)) throw FitError("fit: body weight must be > 0 N");
  if (!samples.allFinite()) {
    throw FitError("fit: the healthy stretch contains NaN or Inf samples; choose a clean stretch");
  }
  FootFit fit;
  fit.coefficients.assign(static_cast<std::size_t>(n * n), 0.0);
  for (Eigen::Index j = 0; j < n; ++j) {
    const std::string& sensor = sensor_names[static_cast<std::size_t>(j)];
    std::vector<Eigen::Index> rows;
    for (Eigen::Index t = 0; t < samples.rows(); ++t) {
      if (in_stance(samples, t, j, options)) rows.push_back(t);
    }
    const auto m = static_cast<Eigen::Index>(rows.size());
    if (static_cast<std::size_t>(m) < options.min_samples_per_coefficient * static_cast<std::size_t>(n)) {
      std::ostringstream msg;
      msg << "fit: sensor " << sensor << " has " << m << " stance samples in the healthy stretch, "
          << "need at least " << options.min_samples_per_coefficient * static_cast<std::size_t>(n)
          << "; use a longer stretch";
      throw FitError(msg.str());
    }
    Eigen::MatrixXd design(m, n);
    Eigen::VectorXd target(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      design(i, 0) = options.body_weight_N;
      for (Eigen::Index k = 0, column = 1; k < n; ++k) {
        if (k != j) design(i, column++) = samples(rows[static_cast<std::size_t>(i)], k);
      }
      target(i) = samples(rows[static_cast<std::size_t>(i)], j);
    }
    // Scale columns to unit norm so the condition estimate measures collinearity, not units.
    Eigen::VectorXd scale = design.colwise().norm().transpose();
    for (Eigen::Index c = 0; c < n; ++c) {
      if (!(scale(c) > 0.0)) {
        std::ostringstream msg;
        msg << "fit: sensor " << sensor << " cannot be fitted: regressor " << c
            << " (0 = body weight, then the other sensors in order) is zero over every stance "
               "sample; that sensor never loads in the healthy stretch";
        throw FitError(msg.str());
      }
    }
    design = design * scale.cwiseInverse().asDiagonal();
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
    const double r_first = std::abs(qr.matrixR()(0, 0));
    const double r_last = std::abs(qr.matrixR()(n - 1, n - 1));
    const double reciprocal_condition = r_first > 0.0 ? r_last / r_first : 0.0;
    if (!(reciprocal_condition >= options.min_reciprocal_condition)) {
      std::ostringstream msg;
      msg << "fit: sensor " << sensor << " is ill-conditioned: reciprocal condition " << reciprocal_condition
          << " < " << options.min_reciprocal_condition
          << " (its regressors are nearly collinear: two sensors read alike, or one barely loads)";
      throw FitError(msg.str());
    }
    const Eigen::VectorXd theta = (qr.solve(target).array() / scale.array()).matrix();
    for (Eigen::Index c = 0; c < n; ++c) fit.coefficients[static_cast<std::size_t>(j * n + c)] = theta(c);
    fit.reciprocal_condition.push_back(reciprocal_condition);
    fit.stance_samples.push_back(static_cast<std::size_t>(m));

    // Error of the plugin's prediction over the whole stretch (swing predicts 0).
    double sum_sq = 0.0;
    for (Eigen::Index t = 0; t < samples.rows(); ++t) {
      double predicted = 0.0;
      if (in_stance(samples, t, j, options)) {
        predicted = theta(0) * options.body_weight_N;
        for (Eigen::Index k = 0, column = 1; k < n; ++k) {
          if (k != j) predicted += theta(column++) * samples(t, k);
        }
      }
      const double e = samples(t, j) - predicted;
      sum_sq += e * e;
    }
    fit.rms_error_N.push_back(std::sqrt(sum_sq / static_cast<double>(samples.rows())));
  }
  return fit;
}

}  // namespace insole
