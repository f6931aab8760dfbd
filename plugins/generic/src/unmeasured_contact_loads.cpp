#include "ftsense/generic/unmeasured_contact_loads.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace ftsense::generic {

UnmeasuredContactLoads::UnmeasuredContactLoads(std::span<const std::array<double, 2>> points,
                                               std::size_t points_per_foot, std::size_t feet)
    : points_per_foot_(std::max<std::size_t>(1, points_per_foot)), feet_(feet) {
  if (!points.empty() && points.size() == points_per_foot_) {
    // W: the left singular vectors of P = [1 x y] beyond its rank span the null space of P^T.
    const auto n = static_cast<Eigen::Index>(points_per_foot_);
    Eigen::MatrixXd p(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      p(i, 0) = 1.0;
      p(i, 1) = points[static_cast<std::size_t>(i)][0];
      p(i, 2) = points[static_cast<std::size_t>(i)][1];
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(p, Eigen::ComputeFullU);
    const auto& sigma = svd.singularValues();
    Eigen::Index rank = 0;
    for (Eigen::Index i = 0; i < sigma.size(); ++i) {
      if (sigma(i) > 1e-9 * sigma(0)) ++rank;
    }
    relations_ = static_cast<std::size_t>(n - rank);
    weights_.assign(points_per_foot_ * relations_, 0.0);
    for (std::size_t i = 0; i < points_per_foot_; ++i) {
      for (std::size_t r = 0; r < relations_; ++r) {
        weights_[i * relations_ + r] =
            svd.matrixU()(static_cast<Eigen::Index>(i), rank + static_cast<Eigen::Index>(r));
      }
    }
  }
  const std::size_t channels = points_per_foot_ * feet_;
  relation_square_.assign(feet_ * relations_, 0.0);
  relation_count_.assign(feet_, 0.0);
  unknowns_.assign(channels, 0);
  fixed_.assign(channels, 0);
  foot_rows_.assign(feet_, 0);
  rhs_.assign(feet_ * relations_, 0.0);
  lower_.assign(channels, 0.0);
  normal_.assign(channels * channels, 0.0);
  gradient_.assign(channels, 0.0);
  basis_.assign((1 + feet_ * relations_) * channels, 0.0);
}

double UnmeasuredContactLoads::relation_rms(std::size_t foot, std::size_t relation) const noexcept {
  if (foot >= feet_ || relation >= relations_ || relation_count_[foot] < kMinSamples) return std::nan("");
  return std::sqrt(relation_square_[foot * relations_ + relation] / relation_count_[foot]);
}

void UnmeasuredContactLoads::reset() noexcept {
  sum_square_ = 0.0;
  sum_count_ = 0.0;
  std::fill(relation_square_.begin(), relation_square_.end(), 0.0);
  std::fill(relation_count_.begin(), relation_count_.end(), 0.0);
}

void UnmeasuredContactLoads::observe_sum(double residual) noexcept {
  if (!std::isfinite(residual)) return;
  sum_square_ += residual * residual;
  sum_count_ += 1.0;
}

void UnmeasuredContactLoads::observe_foot(std::size_t foot, std::span<const double> loads) noexcept {
  if (relations_ == 0 || foot >= feet_ || loads.size() != points_per_foot_) return;
  for (const double x : loads) {
    if (!std::isfinite(x)) return;
  }
  for (std::size_t r = 0; r < relations_; ++r) {
    double e = 0.0;
    for (std::size_t i = 0; i < points_per_foot_; ++i) e += relation_weight(i, r) * loads[i];
    relation_square_[foot * relations_ + r] += e * e;
  }
  relation_count_[foot] += 1.0;
}

void UnmeasuredContactLoads::solve(std::span<double> loads, std::span<const char> unknown,
                                   std::span<const double> lower_bound, std::span<const char> plane_usable,
                                   double leftover) noexcept {
  std::size_t m = 0;
  for (std::size_t k = 0; k < loads.size() && k < unknown.size(); ++k) {
    if (unknown[k] == 0) continue;
    unknowns_[m] = k;
    lower_[m] = k < lower_bound.size() ? lower_bound[k] : 0.0;
    fixed_[m] = 0;
    ++m;
  }
  solved_unknowns_ = m;
  for (std::size_t f = 0; f < feet_; ++f) foot_rows_[f] = 0;
  if (m == 0) return;
  if (!std::isfinite(leftover)) leftover = 0.0;  // no total force: the bounds alone
  // The feet whose plane relations enter: in full contact, holding an unknown, their variances
  // known; and only for two unknowns or more. One the sum determines alone, to the total force's
  // error, which a plane that holds to tens of newtons as a sole rolls cannot better.
  bool any_rows = false;
  if (m >= 2 && relations_ > 0 && sum_count_ >= kMinSamples) {
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t f = unknowns_[i] / points_per_foot_;
      if (f < plane_usable.size() && plane_usable[f] != 0 && relation_count_[f] >= kMinSamples) foot_rows_[f] = 1;
    }
    for (std::size_t f = 0; f < feet_; ++f) {
      if (foot_rows_[f] == 0) continue;
      any_rows = true;
      for (std::size_t r = 0; r < relations_; ++r) {
        double known = 0.0;
        for (std::size_t i = 0; i < points_per_foot_; ++i) {
          const std::size_t j = f * points_per_foot_ + i;
          if (unknown[j] == 0) known += relation_weight(i, r) * loads[j];
        }
        rhs_[f * relations_ + r] = -known;
      }
    }
  }
  if (!any_rows) {
    // The sum alone: the free unknowns share what their bounds leave, equally.
    for (std::size_t pass = 0; pass <= m; ++pass) {
      std::size_t free = 0;
      double held = 0.0;
      for (std::size_t i = 0; i < m; ++i) {
        if (fixed_[i] != 0) {
          held += lower_[i];
        } else {
          ++free;
        }
      }
      const double share = free > 0 ? (leftover - held) / static_cast<double>(free) : 0.0;
      std::size_t worst = m;
      double violation = 0.0;
      for (std::size_t i = 0; i < m; ++i) {
        if (fixed_[i] == 0 && lower_[i] - share > violation) {
          violation = lower_[i] - share;
          worst = i;
        }
      }
      if (worst == m) {
        for (std::size_t i = 0; i < m; ++i) loads[unknowns_[i]] = fixed_[i] != 0 ? lower_[i] : share;
        return;
      }
      fixed_[worst] = 1;
    }
    for (std::size_t i = 0; i < m; ++i) loads[unknowns_[i]] = lower_[i];
    return;
  }
  for (std::size_t pass = 0; pass <= m; ++pass) {
    solve_free(loads, leftover, m);
    std::size_t worst = m;
    double violation = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
      if (fixed_[i] == 0 && lower_[i] - loads[unknowns_[i]] > violation) {
        violation = lower_[i] - loads[unknowns_[i]];
        worst = i;
      }
    }
    if (worst == m) return;
    fixed_[worst] = 1;
  }
  for (std::size_t i = 0; i < m; ++i) loads[unknowns_[i]] = std::max(loads[unknowns_[i]], lower_[i]);
}

bool UnmeasuredContactLoads::foot_total_determined(std::size_t foot) noexcept {
  const std::size_t m = solved_unknowns_;
  // Modified Gram-Schmidt on the rows over the m unknowns: the sum's (all ones), then each
  // relation of each foot whose rows entered (its weights on that foot's unknowns).
  std::size_t rows = 0;
  const auto add_row = [&](auto weight_of_unknown) {
    double* row = basis_.data() + rows * m;
    for (std::size_t a = 0; a < m; ++a) row[a] = weight_of_unknown(a);
    for (std::size_t b = 0; b < rows; ++b) {
      const double* q = basis_.data() + b * m;
      double dot = 0.0;
      for (std::size_t a = 0; a < m; ++a) dot += q[a] * row[a];
      for (std::size_t a = 0; a < m; ++a) row[a] -= dot * q[a];
    }
    double norm = 0.0;
    for (std::size_t a = 0; a < m; ++a) norm += row[a] * row[a];
    norm = std::sqrt(norm);
    if (norm < 1e-9) return;  // dependent on the rows before
    for (std::size_t a = 0; a < m; ++a) row[a] /= norm;
    ++rows;
  };
  add_row([](std::size_t) { return 1.0; });
  for (std::size_t f = 0; f < feet_; ++f) {
    if (foot_rows_[f] == 0) continue;
    for (std::size_t r = 0; r < relations_; ++r) {
      add_row([&](std::size_t a) {
        const std::size_t j = unknowns_[a];
        return j / points_per_foot_ == f ? relation_weight(j % points_per_foot_, r) : 0.0;
      });
    }
  }
  // The foot's indicator s over the unknowns: determined when its projection on the rows is s.
  double norm = 0.0, projected = 0.0;
  for (std::size_t a = 0; a < m; ++a) norm += unknowns_[a] / points_per_foot_ == foot ? 1.0 : 0.0;
  if (norm == 0.0) return true;
  for (std::size_t b = 0; b < rows; ++b) {
    const double* q = basis_.data() + b * m;
    double dot = 0.0;
    for (std::size_t a = 0; a < m; ++a) dot += unknowns_[a] / points_per_foot_ == foot ? q[a] : 0.0;
    projected += dot * dot;
  }
  return projected > norm * (1.0 - 1e-9);
}

void UnmeasuredContactLoads::solve_free(std::span<double> loads, double leftover, std::size_t m) noexcept {
  // Fixed unknowns sit at their bounds; the normal equations H u = g over the free ones.
  for (std::size_t i = 0; i < m; ++i) {
    if (fixed_[i] != 0) loads[unknowns_[i]] = lower_[i];
  }
  const double sum_weight = 1.0 / std::max(sum_square_ / sum_count_, 1e-12);
  double sum_rhs = leftover;
  for (std::size_t i = 0; i < m; ++i) {
    if (fixed_[i] != 0) sum_rhs -= lower_[i];
  }
  std::size_t n = 0;  // free unknowns; row a of H is free unknown free_index a
  for (std::size_t i = 0; i < m; ++i) {
    if (fixed_[i] == 0) ++n;
  }
  if (n == 0) return;
  const auto weight_of = [&](std::size_t f, std::size_t r) {
    return 1.0 / std::max(relation_square_[f * relations_ + r] / relation_count_[f], 1e-12);
  };
  std::size_t a = 0;
  for (std::size_t i = 0; i < m; ++i) {
    if (fixed_[i] != 0) continue;
    const std::size_t ji = unknowns_[i];
    const std::size_t fi = ji / points_per_foot_;
    double g = sum_weight * sum_rhs;
    if (foot_rows_[fi] != 0) {
      for (std::size_t r = 0; r < relations_; ++r) {
        double rhs = rhs_[fi * relations_ + r];
        for (std::size_t l = 0; l < m; ++l) {
          if (fixed_[l] != 0 && unknowns_[l] / points_per_foot_ == fi) {
            rhs -= relation_weight(unknowns_[l] % points_per_foot_, r) * lower_[l];
          }
        }
        g += weight_of(fi, r) * relation_weight(ji % points_per_foot_, r) * rhs;
      }
    }
    gradient_[a] = g;
    std::size_t b = 0;
    for (std::size_t l = 0; l < m; ++l) {
      if (fixed_[l] != 0) continue;
      const std::size_t jl = unknowns_[l];
      double h = sum_weight;
      if (foot_rows_[fi] != 0 && jl / points_per_foot_ == fi) {
        for (std::size_t r = 0; r < relations_; ++r) {
          h += weight_of(fi, r) * relation_weight(ji % points_per_foot_, r) * relation_weight(jl % points_per_foot_, r);
        }
      }
      normal_[a * n + b] = h;
      ++b;
    }
    ++a;
  }
  // A ridge toward the equal share keeps H positive definite where the relations leave
  // directions free (two unknowns on one foot's diagonal); it is 1e-9 of the diagonal (enough to
  // keep the free direction within 1e-4 N of rounding, far below what it biases the others).
  double diagonal = 0.0;
  for (std::size_t i = 0; i < n; ++i) diagonal = std::max(diagonal, normal_[i * n + i]);
  const double ridge = 1e-9 * diagonal;
  const double share = sum_rhs / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) {
    normal_[i * n + i] += ridge;
    gradient_[i] += ridge * share;
  }
  // Cholesky H = L L^T in place (lower triangle), then L y = g, L^T u = y.
  for (std::size_t j = 0; j < n; ++j) {
    double d = normal_[j * n + j];
    for (std::size_t k = 0; k < j; ++k) d -= normal_[j * n + k] * normal_[j * n + k];
    d = std::sqrt(std::max(d, 1e-300));
    normal_[j * n + j] = d;
    for (std::size_t i = j + 1; i < n; ++i) {
      double s = normal_[i * n + j];
      for (std::size_t k = 0; k < j; ++k) s -= normal_[i * n + k] * normal_[j * n + k];
      normal_[i * n + j] = s / d;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    double s = gradient_[i];
    for (std::size_t k = 0; k < i; ++k) s -= normal_[i * n + k] * gradient_[k];
    gradient_[i] = s / normal_[i * n + i];
  }
  for (std::size_t ii = n; ii-- > 0;) {
    double s = gradient_[ii];
    for (std::size_t k = ii + 1; k < n; ++k) s -= normal_[k * n + ii] * gradient_[k];
    gradient_[ii] = s / normal_[ii * n + ii];
  }
  a = 0;
  for (std::size_t i = 0; i < m; ++i) {
    if (fixed_[i] != 0) continue;
    loads[unknowns_[i]] = gradient_[a++];
  }
}

}  // namespace ftsense::generic
