#include "ftsense/generic/rejoin_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/generic/jump_noise.hpp"
#include "ftsense/generic/window_step_noise.hpp"

namespace ftsense::generic {

void RejoinDetector::Params::describe(ParamSchema<Params>& schema) {
  describe_jump_noise(schema);
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between jumps of the noise alone beyond the bound (sets z)")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("guard", &Params::guard,
             "adds input guard (nonzero: the tick is not judged, e.g. change_guard over a landing's transient)");
  schema.add("residual", &Params::residual,
             "adds input residual (the channel's constraint residual row, which its reading enters one for one): a "
             "jump is an end only if the row stepped with it over 10 ms windows (load moving between channels "
             "leaves the row)");
  describe_residual_step(schema);
}

RejoinDetector::RejoinDetector(const Params& params, const StageContext& context)
    : guard_wired_(params.guard), residual_wired_(params.residual) {
  const std::size_t dim = context.wired_dim("signal", params.noise_std.size());
  const double alpha = false_alarm_per_tick(context.sample_period_s(), params.false_alarm_interval_s);
  const double z = two_sided_z(alpha);
  const auto noise = channel_values(params.noise_std, dim, "noise_std");
  const auto resolution = channel_values(params.resolution, dim, "resolution");
  const auto residual_step = channel_values(params.residual_step_std, dim, "residual_step_std");
  bound_.resize(dim);
  step_bound_.resize(dim);
  match_bound_.resize(dim);
  for (std::size_t j = 0; j < dim; ++j) {
    const double jump_variance = second_difference_variance(noise[j], resolution[j]);
    bound_[j] = z * std::sqrt(jump_variance);
    step_bound_[j] = z * residual_step[j];
    match_bound_[j] = z * std::sqrt(jump_variance + residual_step[j] * residual_step[j]);
  }
  window_ = step_window_ticks(context.sample_period_s());
  std::size_t next_input = kGuard;
  if (guard_wired_) guard_input_ = next_input++;
  if (residual_wired_) residual_input_ = next_input++;
  ports_.add_input(PortSpec{"signal", dim, std::string(kAnyUnit), "the readings x_j"}.sized_by("as wired"));
  ports_.add_input(PortSpec{"recovered", dim, std::string(kAnyUnit),
                            "the recovery's value y_j of the tick before (previous_tick), in the readings' unit"}
                       .sized_by("as `signal`"));
  ports_.add_input(PortSpec{"fault", dim, std::string(kDimensionless),
                            "1 while the channel was flagged on the tick before (previous_tick; nonzero and "
                            "finite: flagged)"}
                       .sized_by("as `signal`"));
  if (guard_wired_) {
    ports_.add_input(PortSpec{"guard", dim, std::string(kDimensionless),
                              "nonzero on ticks not judged (a landing's transient)"}
                         .sized_by("as `signal`"));
  }
  if (residual_wired_) {
    ports_.add_input(PortSpec{"residual", dim, std::string(kAnyUnit),
                              "the channel's constraint residual row r_j (d r_j / d x_j = 1), from the readings as "
                              "read"}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"rejoined", dim, std::string(kDimensionless),
                             "1 on the tick the reading jumped onto its recovered value, else 0"}
                        .sized_by("as `signal`"));
  x1_.assign(dim, std::numeric_limits<double>::quiet_NaN());
  x2_ = x1_;
  y2_ = x1_;
  flagged2_.assign(dim, 0);
  smooth_before_.assign(dim, 0);
  residual_ring_.assign(residual_wired_ ? dim * 2 * window_ : 0, std::numeric_limits<double>::quiet_NaN());
  candidate_jump_.assign(residual_wired_ ? dim * window_ : 0, std::numeric_limits<double>::quiet_NaN());
}

void RejoinDetector::reset() noexcept {
  std::fill(x1_.begin(), x1_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(x2_.begin(), x2_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(y2_.begin(), y2_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(flagged2_.begin(), flagged2_.end(), 0);
  std::fill(smooth_before_.begin(), smooth_before_.end(), 0);
  std::fill(residual_ring_.begin(), residual_ring_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(candidate_jump_.begin(), candidate_jump_.end(), std::numeric_limits<double>::quiet_NaN());
  candidate_next_ = 0;
  ring_next_ = 0;
}

void RejoinDetector::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto y1 = io.in(kRecovered);  // y(t-1)
  const auto fault = io.in(kFault);   // the flag of t-1
  const auto rejoined = io.out(kRejoined);
  const std::size_t ring = 2 * window_;
  for (std::size_t j = 0; j < bound_.size(); ++j) {
    const bool flagged1 = std::isfinite(fault[j]) && fault[j] != 0.0;
    const bool guarded = guard_wired_ && io.in(guard_input_)[j] != 0.0;  // NaN is nonzero: unknown is guarded
    const double d0 = x[j] - 2.0 * x1_[j] + x2_[j];
    const double d1 = x[j] - 2.0 * y1[j] + y2_[j];
    // NaN in any sample fails both comparisons: not judged.
    const bool jumped = std::abs(d0) > bound_[j];
    const bool judged = flagged1 && flagged2_[j] && !guarded && smooth_before_[j];
    const bool onto_recovered = judged && jumped && std::abs(d1) <= bound_[j];
    if (!residual_wired_) {
      rejoined[j] = onto_recovered ? 1.0 : 0.0;
    } else {
      // The row's sample of this tick (NaN where guarded: no step is judged across a transient).
      const double r = io.in(residual_input_)[j];
      double* const samples = residual_ring_.data() + j * ring;
      samples[ring_next_] = guarded ? std::numeric_limits<double>::quiet_NaN() : r;
      rejoined[j] = 0.0;
      // Each tick's candidate (its d0; NaN: none) waits W - 1 ticks for its window after; one
      // re-admitted meanwhile is dropped. The candidate judged now is the one from W - 1 ticks
      // back, in the slot after this tick's (this tick's own at W = 1).
      double* const candidates = candidate_jump_.data() + j * window_;
      if (!flagged1) std::fill(candidates, candidates + window_, std::numeric_limits<double>::quiet_NaN());
      candidates[candidate_next_] = onto_recovered ? d0 : std::numeric_limits<double>::quiet_NaN();
      const double jump = candidates[candidate_next_ + 1 == window_ ? 0 : candidate_next_ + 1];
      if (std::isfinite(jump)) {
        // The ring holds r[t-W .. t+W-1], oldest at ring_next_ + 1: its window step, over each
        // window's finite samples, at least half of each (an end just after a landing's guard
        // has the guard's last ticks in its window before).
        double before = 0.0, after = 0.0;
        std::size_t n_before = 0, n_after = 0;
        for (std::size_t k = 0; k < window_; ++k) {
          const double b = samples[(ring_next_ + 1 + k) % ring];
          const double a = samples[(ring_next_ + 1 + window_ + k) % ring];
          if (std::isfinite(b)) before += b, ++n_before;
          if (std::isfinite(a)) after += a, ++n_after;
        }
        const bool enough = 2 * n_before >= window_ && 2 * n_after >= window_ && n_before > 0 && n_after > 0;
        const double step = enough ? after / static_cast<double>(n_after) - before / static_cast<double>(n_before)
                                   : std::numeric_limits<double>::quiet_NaN();
        // NaN fails both: not an end.
        rejoined[j] = std::abs(step) > step_bound_[j] && std::abs(jump - step) <= match_bound_[j] ? 1.0 : 0.0;
      }
    }
    // The tick after a jump (and the one after that) holds it in its second difference, and y's
    // line through it: judged only after a tick whose d0 stayed within the bound.
    smooth_before_[j] = std::isfinite(d0) && !jumped ? 1 : 0;
    x2_[j] = x1_[j];
    x1_[j] = x[j];
    y2_[j] = y1[j];
    flagged2_[j] = flagged1 ? 1 : 0;
  }
  if (residual_wired_) {
    ring_next_ = ring_next_ + 1 == ring ? 0 : ring_next_ + 1;
    candidate_next_ = candidate_next_ + 1 == window_ ? 0 : candidate_next_ + 1;
  }
}

}  // namespace ftsense::generic
