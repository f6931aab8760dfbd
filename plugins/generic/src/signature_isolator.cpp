#include "ftsense/generic/signature_isolator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

namespace {
// A column this small (in whitened units squared) sees no fault: not a candidate.
constexpr double kMinColumnNorm = 1e-12;
// A column whose part outside the blamed columns' span is this small a share of it is spanned.
constexpr double kSpannedShare = 1e-9;
}  // namespace

void SignatureIsolator::Params::describe(ParamSchema<Params>& schema) {
  schema.add("group_size", &Params::group_size,
             "channels per group g (one residual each); the wired channels are the groups one after another")
      .at_least(1)
      .at_most(64)
      .required();
  schema
      .add("residual_noise_std", &Params::residual_noise_std,
           "standard deviation sigma_i of each fault-free residual, in its unit; one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between wrong isolations the margin chi^2_1(1 - T / interval) aims at")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("max_faults", &Params::max_faults,
             "how many channels of a group may be blamed at once (at most group_size); a further one only "
             "when its own GLR gain on what the blamed ones leave clears the margin")
      .at_least(1)
      .at_most(64);
  schema.add("row_weights", &Params::row_weights,
             "adds input row_weight (w_i: the share of one observation residual i carries, e.g. "
             "sum_constraint_residual's row_weight)");
}

SignatureIsolator::SignatureIsolator(const Params& params, const StageContext& context)
    : group_size_(static_cast<std::size_t>(params.group_size)),
      max_faults_(static_cast<std::size_t>(params.max_faults)),
      row_weights_(params.row_weights) {
  const std::size_t dim = context.wired_dim("residual", group_size_);
  if (dim % group_size_ != 0) {
    throw ConfigError("/params/group_size", " = " + std::to_string(group_size_) + " does not divide the " +
                                                std::to_string(dim) + " wired residuals into whole groups");
  }
  if (max_faults_ > group_size_) {
    throw ConfigError("/params/max_faults", " = " + std::to_string(max_faults_) + " is more than the " +
                                                std::to_string(group_size_) + " channels of a group; give at most " +
                                                std::to_string(group_size_));
  }
  groups_ = dim / group_size_;
  const std::vector<double> noise = channel_values(params.residual_noise_std, dim, "residual_noise_std");
  inv_std_.resize(dim);
  for (std::size_t i = 0; i < dim; ++i) inv_std_[i] = 1.0 / noise[i];
  const double alpha = context.sample_period_s() / params.false_alarm_interval_s;
  if (!(alpha > 0.0 && alpha < 1.0)) {
    throw ConfigError("/params/false_alarm_interval_s", " = " + format_number(params.false_alarm_interval_s) +
                                                            " s must be longer than the sample period");
  }
  const double z = normal_quantile(1.0 - 0.5 * alpha);
  margin_ = z * z;
  ports_.add_input(PortSpec{"residual", dim, std::string(kAnyUnit), "the residuals r, group after group"}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"alarm", dim, std::string(kDimensionless),
                            "1 while a detector raises residual i (nonzero: raised; 0 or NaN: not)"}
                       .sized_by("as `residual`"));
  ports_.add_input(PortSpec{"signature", dim * group_size_, std::string(kDimensionless),
                            "each group's g x g signature S (row i: residual i, S_ij = d r_i / d x_j), row-major, "
                            "group after group"}
                       .sized_by("residuals x group_size"));
  if (row_weights_) {
    ports_.add_input(PortSpec{"row_weight", dim, std::string(kDimensionless),
                              "w_i, the share of one observation residual i carries (1 / L for L copies of one "
                              "number); not finite or negative: the row is left out this tick"}
                         .sized_by("as `residual`"));
  }
  ports_.add_output(PortSpec{"fault", dim, std::string(kDimensionless), "1 while the channel is blamed, else 0"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"fault_type", dim, std::string(kDimensionless),
                             "fault type code (fault_type.hpp): unclassified when blamed, else none"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"fault_estimate", dim, std::string(kAnyUnit),
                             "f_j, a blamed channel's fault size in the residuals' unit (fitted with the group's "
                             "other blamed channels); 0 otherwise"}
                        .sized_by("as `residual`"));
  ports_.add_output(PortSpec{"cannot_judge", dim, std::string(kDimensionless),
                             "1 while the channel's group is raised and it is neither blamed nor told apart"}
                        .sized_by("as `residual`"));
  const std::size_t g = group_size_;
  blamed_count_.assign(groups_, 0);
  blamed_order_.assign(dim, 0);
  estimate_.assign(dim, 0.0);
  z_.assign(g, 0.0);
  fit_z_.assign(g, 0.0);
  columns_.assign(g * g, 0.0);
  column_sq_.assign(g, 0.0);
  usable_.assign(g, 0);
  fit_index_.assign(g, 0);
  fit_gram_.assign(g * g, 0.0);
  fit_factor_.assign(g * g, 0.0);
  fit_rhs_.assign(g, 0.0);
  fit_size_.assign(g, 0.0);
  cross_.assign(g, 0.0);
  solved_.assign(g, 0.0);
}

void SignatureIsolator::reset() noexcept {
  std::fill(blamed_count_.begin(), blamed_count_.end(), 0);
  std::fill(estimate_.begin(), estimate_.end(), 0.0);
}

void SignatureIsolator::solve_gram(std::size_t n, const double* b, double* x) const noexcept {
  // L L' x = b, L lower triangular in fit_factor_ (row-major, n x n in a g-wide block); a zero
  // pivot marks a spanned column, whose entry is 0.
  const std::size_t g = group_size_;
  const double* factor = fit_factor_.data();
  for (std::size_t a = 0; a < n; ++a) {
    double v = b[a];
    for (std::size_t k = 0; k < a; ++k) v -= factor[a * g + k] * x[k];
    x[a] = factor[a * g + a] > 0.0 ? v / factor[a * g + a] : 0.0;
  }
  for (std::size_t a = n; a-- > 0;) {
    double v = x[a];
    for (std::size_t k = a + 1; k < n; ++k) v -= factor[k * g + a] * x[k];
    x[a] = factor[a * g + a] > 0.0 ? v / factor[a * g + a] : 0.0;
  }
}

void SignatureIsolator::fit_blamed(std::size_t first, std::size_t n) noexcept {
  const std::size_t g = group_size_;
  // Gram matrix G = T_B' T_B of the listed columns.
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b <= a; ++b) {
      double dot = 0.0;
      for (std::size_t i = 0; i < g; ++i) dot += columns_[i * g + fit_index_[a]] * columns_[i * g + fit_index_[b]];
      fit_gram_[a * g + b] = dot;
    }
  }
  // Cholesky G = L L'; a column the earlier ones span (pivot at most kSpannedShare of its norm)
  // gets a zero row, and keeps its last size: its part is taken out of z before the others fit.
  std::copy(z_.begin(), z_.end(), fit_z_.begin());
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b <= a; ++b) {
      double v = fit_gram_[a * g + b];
      for (std::size_t k = 0; k < b; ++k) v -= fit_factor_[a * g + k] * fit_factor_[b * g + k];
      if (b < a) {
        fit_factor_[a * g + b] = fit_factor_[b * g + b] > 0.0 ? v / fit_factor_[b * g + b] : 0.0;
      } else {
        fit_factor_[a * g + a] = v > kSpannedShare * fit_gram_[a * g + a] ? std::sqrt(v) : 0.0;
      }
    }
    if (fit_factor_[a * g + a] == 0.0) {
      const double held = estimate_[first + fit_index_[a]];
      for (std::size_t i = 0; i < g; ++i) fit_z_[i] -= columns_[i * g + fit_index_[a]] * held;
    }
  }
  for (std::size_t a = 0; a < n; ++a) {
    double rhs = 0.0;
    for (std::size_t i = 0; i < g; ++i) rhs += columns_[i * g + fit_index_[a]] * fit_z_[i];
    fit_rhs_[a] = rhs;
  }
  solve_gram(n, fit_rhs_.data(), fit_size_.data());
  // The fitted columns' new sizes; a spanned column's stays.
  for (std::size_t a = 0; a < n; ++a) {
    if (fit_factor_[a * g + a] > 0.0 && std::isfinite(fit_size_[a])) estimate_[first + fit_index_[a]] = fit_size_[a];
  }
}

void SignatureIsolator::step(const StepIO& io) noexcept {
  const auto r = io.in(kResidual);
  const auto alarm = io.in(kAlarm);
  const auto signature = io.in(kSignature);
  const std::span<const double> weight = row_weights_ ? io.in(kRowWeight) : std::span<const double>{};
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  const auto estimate = io.out(kFaultEstimate);
  const auto cannot = io.out(kCannotJudge);
  const std::size_t g = group_size_;
  for (std::size_t group = 0; group < groups_; ++group) {
    const std::size_t first = group * g;
    std::size_t* order = blamed_order_.data() + first;
    std::size_t& count = blamed_count_[group];
    const auto blamed = [&](std::size_t j) { return std::find(order, order + count, j) != order + count; };
    bool raised = false;
    bool known = true;
    for (std::size_t i = 0; i < g; ++i) {
      raised = raised || (std::isfinite(alarm[first + i]) && alarm[first + i] != 0.0);
      const double w = row_weights_ ? weight[first + i] : 1.0;
      const double scale = std::isfinite(w) && w >= 0.0 ? std::sqrt(w) * inv_std_[first + i] : 0.0;
      z_[i] = r[first + i] * scale;
      known = known && (scale == 0.0 || std::isfinite(z_[i]));
      if (scale == 0.0 || !std::isfinite(z_[i])) z_[i] = 0.0;
      // A row left out is 0 in every column (a NaN signature entry there must not spoil the column).
      for (std::size_t j = 0; j < g; ++j) {
        columns_[i * g + j] = scale == 0.0 ? 0.0 : signature[(first + i) * g + j] * scale;
      }
    }
    if (!raised) {
      // Nothing raised: every channel of the group is free again.
      for (std::size_t k = 0; k < count; ++k) estimate_[first + order[k]] = 0.0;
      count = 0;
    }
    bool unexplained = false;  // what the blamed channels leave clears the margin, nobody told apart
    if (raised && known) {
      for (std::size_t j = 0; j < g; ++j) {
        double sq = 0.0;
        bool finite = true;
        for (std::size_t i = 0; i < g; ++i) {
          finite = finite && std::isfinite(columns_[i * g + j]);
          sq += columns_[i * g + j] * columns_[i * g + j];
        }
        column_sq_[j] = sq;
        usable_[j] = finite && std::isfinite(sq) && sq > kMinColumnNorm ? 1 : 0;
      }
      // A blamed channel whose own residual row sees no other channel (a foot in the air: its row
      // is its own reading) and whose own detector is down has its evidence cleared: released,
      // whatever keeps the rest of the group raised.
      for (std::size_t k = 0; k < count;) {
        const std::size_t j = order[k];
        bool own_row = usable_[j] != 0 && std::isfinite(alarm[first + j]) && alarm[first + j] == 0.0;
        for (std::size_t other = 0; other < g && own_row; ++other) {
          if (other != j) own_row = columns_[j * g + other] == 0.0;
        }
        if (!own_row) {
          ++k;
          continue;
        }
        estimate_[first + j] = 0.0;
        std::copy(order + k + 1, order + count, order + k);
        --count;
      }
      // The blamed channels seen this tick, fitted jointly.
      std::size_t n = 0;
      for (std::size_t k = 0; k < count; ++k) {
        if (usable_[order[k]] != 0) fit_index_[n++] = order[k];
      }
      fit_blamed(first, n);
      // A further verdict only while every blamed channel is seen: an unseen one's fault is not
      // taken out of z, and would be blamed on another.
      if (count < max_faults_ && n == count) {
        // Each other channel's gain on what the blamed ones leave.
        long best = -1, second = -1;
        double best_gain = -1.0, second_gain = -1.0;
        for (std::size_t j = 0; j < g; ++j) {
          if (blamed(j) || usable_[j] == 0) continue;
          double tz = 0.0;
          for (std::size_t i = 0; i < g; ++i) tz += columns_[i * g + j] * fit_z_[i];
          double explained = 0.0, spanned = 0.0;
          if (n > 0) {
            for (std::size_t a = 0; a < n; ++a) {
              double dot = 0.0;
              for (std::size_t i = 0; i < g; ++i) dot += columns_[i * g + fit_index_[a]] * columns_[i * g + j];
              cross_[a] = dot;
            }
            solve_gram(n, cross_.data(), solved_.data());
            for (std::size_t a = 0; a < n; ++a) {
              explained += cross_[a] * fit_size_[a];
              spanned += cross_[a] * solved_[a];
            }
          }
          const double own = column_sq_[j] - spanned;
          if (!(own > kSpannedShare * column_sq_[j])) continue;
          const double gain = (tz - explained) * (tz - explained) / own;
          if (gain > best_gain) {
            second = best;
            second_gain = best_gain;
            best = static_cast<long>(j);
            best_gain = gain;
          } else if (gain > second_gain) {
            second = static_cast<long>(j);
            second_gain = gain;
          }
        }
        // The first verdict rests on the detector's alarm; a further one on its own gain.
        const bool significant = count == 0 || best_gain >= margin_;
        if (best >= 0 && significant && (second < 0 || best_gain - second_gain >= margin_)) {
          order[count++] = static_cast<std::size_t>(best);
          fit_index_[n++] = static_cast<std::size_t>(best);
          fit_blamed(first, n);
        } else {
          unexplained = count > 0 && best >= 0 && best_gain >= margin_;
        }
      }
    }
    for (std::size_t j = 0; j < g; ++j) {
      const bool is_blamed = blamed(j);
      fault[first + j] = is_blamed ? 1.0 : 0.0;
      type[first + j] = fault_code(is_blamed ? FaultType::unclassified : FaultType::none);
      estimate[first + j] = is_blamed ? estimate_[first + j] : 0.0;
      cannot[first + j] = raised && !is_blamed && (count == 0 || unexplained) ? 1.0 : 0.0;
    }
  }
}

}  // namespace ftsense::generic
