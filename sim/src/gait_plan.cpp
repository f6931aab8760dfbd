#include "ftsense/sim/gait_plan.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ftsense::sim {

namespace {
double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}
}  // namespace

GaitPlan::GaitPlan(const GaitParams& params, double duration_s) : p_(params) {
  if (!(p_.step_time_s > 0.0) || !(p_.double_support_ratio > 0.0 && p_.double_support_ratio < 1.0))
    throw std::invalid_argument("GaitPlan: step_time_s must be > 0 and double_support_ratio in (0,1)");
  const double T = p_.step_time_s, r = p_.double_support_ratio;
  if (p_.num_steps >= 0) {
    n_ = p_.num_steps;
  } else {
    const double avail = duration_s - p_.initial_stand_s - r * T - 1.0;
    n_ = std::max(0, static_cast<int>(std::floor(avail / T)));
  }
  p_.num_steps = n_;
  const double w = p_.foot_half_spacing_m;
  fp_.emplace_back(0.0, -w);
  fp_.emplace_back(0.0, w);
  for (int k = 0; k < n_; ++k) {
    const double x = std::min(k + 1, std::max(n_ - 1, 1)) * p_.step_length_m;
    fp_.emplace_back(n_ == 1 ? 0.0 : x, (k % 2 == 0) ? -w : w);
  }
}

double GaitPlan::walk_end_s() const {
  return p_.initial_stand_s + (n_ + p_.double_support_ratio) * p_.step_time_s;
}

GaitSample GaitPlan::sample(double t) const {
  GaitSample s;
  const double T = p_.step_time_s, r = p_.double_support_ratio;
  auto lift = [](const Eigen::Vector2d& xy) { return Eigen::Vector3d(xy.x(), xy.y(), 0.0); };
  const Eigen::Vector2d mid0 = 0.5 * (fp_[0] + fp_[1]);
  if (n_ == 0 || t < p_.initial_stand_s) {
    s.zmp = mid0;
    s.sole = {lift(fp_[1]), lift(fp_[0])};
    return s;
  }
  const double tw = t - p_.initial_stand_s;
  const int k = static_cast<int>(std::floor(tw / T));
  if (k >= n_) {
    const Eigen::Vector2d& last_support = fp_[static_cast<std::size_t>(n_)];
    const Eigen::Vector2d mid = 0.5 * (fp_[static_cast<std::size_t>(n_)] + fp_[static_cast<std::size_t>(n_) + 1]);
    const double a = std::clamp((tw - n_ * T) / (r * T), 0.0, 1.0);
    s.zmp = last_support + a * (mid - last_support);
    // Final footprints: the last two entries (even index = right foot, as F0).
    const std::size_t a_idx = static_cast<std::size_t>(n_), b_idx = a_idx + 1;
    const bool a_is_right = (a_idx % 2 == 0);
    s.sole[a_is_right ? 1 : 0] = lift(fp_[a_idx]);
    s.sole[a_is_right ? 0 : 1] = lift(fp_[b_idx]);
    s.swing_weight[a_is_right ? 0 : 1] = 1.0 - smoothstep(a);  // the foot that landed last
    return s;
  }
  const double ph = tw - k * T;
  const auto ku = static_cast<std::size_t>(k);
  const Eigen::Vector2d& support = fp_[ku + 1];
  const Eigen::Vector2d prev = (k == 0) ? mid0 : fp_[ku];
  const int swing = (k % 2 == 0) ? 1 : 0;  // right swings on even steps
  const int stance = 1 - swing;
  s.sole[static_cast<std::size_t>(stance)] = lift(support);
  if (ph < r * T) {
    s.zmp = prev + (ph / (r * T)) * (support - prev);
    s.sole[static_cast<std::size_t>(swing)] = lift(fp_[ku]);
    if (k > 0) s.swing_weight[static_cast<std::size_t>(stance)] = 1.0 - smoothstep(ph / (r * T));
  } else {
    s.zmp = support;
    const double tau = std::clamp((ph - r * T) / ((1.0 - r) * T), 0.0, 1.0);
    const double sx = tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
    const double sz = 16.0 * std::pow(tau * (1.0 - tau), 2);
    const Eigen::Vector2d xy = fp_[ku] + sx * (fp_[ku + 2] - fp_[ku]);
    s.sole[static_cast<std::size_t>(swing)] = Eigen::Vector3d(xy.x(), xy.y(), p_.step_height_m * sz);
    s.contact[static_cast<std::size_t>(swing)] = false;
    s.swing_weight[static_cast<std::size_t>(swing)] = smoothstep(tau / 0.15);
  }
  return s;
}

}  // namespace ftsense::sim
