#include "ftsense/generic/step_isolator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/generic/jump_noise.hpp"
#include "ftsense/generic/window_step_noise.hpp"

namespace ftsense::generic {

void StepIsolator::Params::describe(ParamSchema<Params>& schema) {
  describe_jump_noise(schema);
  describe_residual_step(schema);
  schema
      .add("virtual_step_std", &Params::virtual_step_std,
           "s_v: the same for each virtual sensor x - r (what the relation says the reading should be); one "
           "value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema
      .add("guard_step_std", &Params::guard_step_std,
           "s_g: how much each fault-free residual row moves across a guard (the mean of 10 ms after it less "
           "that before it; standard deviation, in its unit): with `guard`, a step inside a guard is judged "
           "after it against this; 0 (the default) leaves such steps unjudged; one value applies to all")
      .at_least(0.0)
      .count_at_least(1);
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between wrong namings the tests' z = Phi^-1(1 - T / (2 interval)) aims at")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("confirm_s", &Params::confirm_s,
             "how long a named step waits for the detector on its row (input alarm) to rise before it is "
             "dropped as a transient")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.01, 10.0, "a detector confirms a lasting change within tenths of a second");
  schema.add("guard", &Params::guard,
             "adds input guard (nonzero: the tick is not judged, e.g. change_guard over a landing's transient)");
  schema.add("judge_raised_rows", &Params::judge_raised_rows,
             "also judge a step on a row whose alarm was up before it, with nothing named here: for rows of "
             "readings corrected for the faults already found (plane_fit_residual with `correction`), whose "
             "level is then their fault-free one, so a step away from it begins a fault");
  schema.add("correction", &Params::correction,
             "adds input correction (nonzero: the channel's reading is corrected in the rows, a fault already "
             "found, so a step on it is not blamed)");
}

StepIsolator::StepIsolator(const Params& params, const StageContext& context)
    : guard_wired_(params.guard), correction_wired_(params.correction), judge_raised_rows_(params.judge_raised_rows) {
  const std::size_t dim = context.wired_dim("signal", params.noise_std.size());
  const double period = context.sample_period_s();
  window_ = step_window_ticks(period);
  span_ = std::max(2 * window_, window_ + 2);
  const double alpha = period / params.false_alarm_interval_s;
  if (!(alpha > 0.0 && alpha < 1.0)) {
    throw ConfigError("/params/false_alarm_interval_s", " = " + format_number(params.false_alarm_interval_s) +
                                                            " s must be longer than the sample period");
  }
  z_ = two_sided_z(alpha);
  const double confirm_ticks = std::round(params.confirm_s / period);
  if (!(confirm_ticks >= 1.0 && confirm_ticks <= 1e9)) {
    throw ConfigError("/params/confirm_s", " = " + format_number(params.confirm_s) + " s is " +
                                               format_number(confirm_ticks) + " ticks of " + format_number(period) +
                                               " s; it needs at least one tick");
  }
  confirm_ticks_ = static_cast<std::size_t>(confirm_ticks);
  const auto noise = channel_values(params.noise_std, dim, "noise_std");
  const auto resolution = channel_values(params.resolution, dim, "resolution");
  const auto residual_step = channel_values(params.residual_step_std, dim, "residual_step_std");
  const auto virtual_step = channel_values(params.virtual_step_std, dim, "virtual_step_std");
  const auto guard_step = channel_values(params.guard_step_std, dim, "guard_step_std");
  guard_bar_.resize(dim);
  guard_match_bound_.resize(dim);
  jump_bound_.resize(dim);
  jump_match_bound_.resize(dim);
  residual_bound_.resize(dim);
  release_bound_.resize(dim);
  inv_virtual_step_.resize(dim);
  for (std::size_t j = 0; j < dim; ++j) {
    const double jump_variance = second_difference_variance(noise[j], resolution[j]);
    jump_bound_[j] = z_ * std::sqrt(jump_variance);
    jump_match_bound_[j] = z_ * std::sqrt(jump_variance + residual_step[j] * residual_step[j]);
    residual_bound_[j] = z_ * residual_step[j];
    release_bound_[j] = z_ * std::sqrt(2.0) * residual_step[j];
    inv_virtual_step_[j] = 1.0 / virtual_step[j];
    const bool judged = guard_wired_ && guard_step[j] > 0.0;
    judge_in_guard_ = judge_in_guard_ || judged;
    guard_bar_[j] = judged ? z_ * guard_step[j] : std::numeric_limits<double>::infinity();
    guard_match_bound_[j] = z_ * std::sqrt(jump_variance + guard_step[j] * guard_step[j]);
  }
  ports_.add_input(PortSpec{"signal", dim, std::string(kAnyUnit), "the readings x_j"}.sized_by("as wired"));
  ports_.add_input(PortSpec{"residual", dim, std::string(kAnyUnit),
                            "one residual row per channel that its reading enters one for one (d r_j / d x_j = 1), "
                            "in the readings' unit"}
                       .sized_by("as `signal`"));
  ports_.add_input(PortSpec{"alarm", dim, std::string(kDimensionless),
                            "1 while a detector raises residual row j (nonzero: raised; 0 or NaN: not)"}
                       .sized_by("as `signal`"));
  if (guard_wired_) {
    ports_.add_input(PortSpec{"guard", dim, std::string(kDimensionless),
                              "nonzero on ticks not judged (a landing's transient)"}
                         .sized_by("as `signal`"));
  }
  if (correction_wired_) {
    ports_.add_input(PortSpec{"correction", dim, std::string(kAnyUnit),
                              "the correction each reading carries in the rows (nonzero, or NaN: corrected; "
                              "not blamed by a step)"}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"fault", dim, std::string(kDimensionless), "1 while the channel is blamed, else 0"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_type", dim, std::string(kDimensionless),
                             "fault type code (fault_type.hpp): unclassified when blamed, else none"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_estimate", dim, std::string(kAnyUnit),
                             "b_j, the sum of the steps named on a blamed channel, in the readings' unit; 0 "
                             "otherwise"}
                        .sized_by("as `signal`"));
  x_ring_.assign(dim * span_, 0.0);
  r_ring_.assign(dim * span_, 0.0);
  raised_ring_.assign(dim * span_, 0);
  usable_run_.assign(dim, 0);
  since_named_.assign(dim, window_);
  blamed_.assign(dim, 0);
  alarm_seen_.assign(dim, 0);
  size_.assign(dim, 0.0);
  age_.assign(dim, 0);
  step_.assign(dim, 0.0);
  level_.assign(dim, 0.0);
  cost_.assign(dim, 0.0);
  finite_run_.assign(dim, 0);
  was_guarded_.assign(dim, 0);
  guard_before_.assign(dim, std::numeric_limits<double>::quiet_NaN());
  pending_.assign(dim, 0);
  pending_raised_.assign(dim, 0);
  pending_jump_.assign(dim, 0.0);
  pending_before_.assign(dim, 0.0);
  guard_age_.assign(dim, span_);  // no guard yet
  level_before_.assign(dim, 0.0);
}

void StepIsolator::reset() noexcept {
  std::fill(x_ring_.begin(), x_ring_.end(), 0.0);
  std::fill(r_ring_.begin(), r_ring_.end(), 0.0);
  std::fill(raised_ring_.begin(), raised_ring_.end(), 0);
  next_ = 0;
  std::fill(usable_run_.begin(), usable_run_.end(), 0);
  std::fill(since_named_.begin(), since_named_.end(), window_);
  for (std::size_t j = 0; j < blamed_.size(); ++j) release(j);
  std::fill(step_.begin(), step_.end(), 0.0);
  std::fill(cost_.begin(), cost_.end(), 0.0);
  std::fill(level_.begin(), level_.end(), 0.0);
  std::fill(finite_run_.begin(), finite_run_.end(), 0);
  std::fill(was_guarded_.begin(), was_guarded_.end(), 0);
  std::fill(guard_before_.begin(), guard_before_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(pending_.begin(), pending_.end(), 0);
  std::fill(pending_raised_.begin(), pending_raised_.end(), 0);
  std::fill(pending_jump_.begin(), pending_jump_.end(), 0.0);
  std::fill(pending_before_.begin(), pending_before_.end(), 0.0);
  std::fill(guard_age_.begin(), guard_age_.end(), span_);
  std::fill(level_before_.begin(), level_before_.end(), 0.0);
}

void StepIsolator::release(std::size_t j) noexcept {
  blamed_[j] = 0;
  alarm_seen_[j] = 0;
  size_[j] = 0.0;
  age_[j] = 0;
}

void StepIsolator::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto r = io.in(kResidual);
  const auto alarm = io.in(kAlarm);
  const std::size_t n = blamed_.size();
  const std::size_t w = window_;
  const double inv_w = 1.0 / static_cast<double>(w);
  // Slot of the sample `back` ticks before this one (0: this tick).
  const auto slot = [&](std::size_t back) { return (next_ + span_ - back) % span_; };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t j = 0; j < n; ++j) {
    const bool guarded = guard_wired_ && io.in(kGuard)[j] != 0.0;  // NaN is nonzero: unknown is guarded
    const bool finite = std::isfinite(x[j]) && std::isfinite(r[j]);
    const bool usable = finite && !guarded;
    if (judge_in_guard_) {
      if (guarded && was_guarded_[j] == 0) {
        // A guard begins: the row's level over the W usable ticks before it is what a step
        // inside it is judged against; a candidate still pending from the guard before is
        // dropped unjudged (its move would span two landings).
        double before = 0.0;
        for (std::size_t k = 1; k <= w; ++k) before += r_ring_[j * span_ + slot(k)];
        guard_before_[j] = usable_run_[j] >= w ? before * inv_w : nan;
        pending_[j] = 0;
        guard_age_[j] = 0;
      } else {
        guard_age_[j] = std::min(guard_age_[j] + 1, span_);
      }
      was_guarded_[j] = guarded ? 1 : 0;
      finite_run_[j] = finite ? std::min(finite_run_[j] + 1, span_) : 0;
    }
    x_ring_[j * span_ + next_] = x[j];
    r_ring_[j * span_ + next_] = r[j];
    raised_ring_[j * span_ + next_] = std::isfinite(alarm[j]) && alarm[j] != 0.0 ? 1 : 0;
    usable_run_[j] = usable ? std::min(usable_run_[j] + 1, span_) : 0;
    since_named_[j] = std::min(since_named_[j] + 1, w);
    step_[j] = nan;
    cost_[j] = nan;
    // A window with guarded samples (a usable run shorter than the span, the samples finite) is
    // judged only for a candidate inside a guard (below), when asked.
    if (usable_run_[j] < span_ && (!judge_in_guard_ || finite_run_[j] < span_)) continue;
    const double* xs = &x_ring_[j * span_];
    const double* rs = &r_ring_[j * span_];
    // The 2W samples oldest first, wrapping once at the ring's end (no modulo per sample).
    double r_after = 0.0, r_before = 0.0, x_after = 0.0, x_before = 0.0;
    std::size_t at = slot(2 * w - 1);
    for (std::size_t k = 0; k < w; ++k, at = at + 1 == span_ ? 0 : at + 1) {
      r_before += rs[at];
      x_before += xs[at];
    }
    for (std::size_t k = 0; k < w; ++k, at = at + 1 == span_ ? 0 : at + 1) {
      r_after += rs[at];
      x_after += xs[at];
    }
    const double dr = (r_after - r_before) * inv_w;
    const double dv = ((x_after - r_after) - (x_before - r_before)) * inv_w;
    step_[j] = dr;
    level_[j] = r_after * inv_w;
    level_before_[j] = r_before * inv_w;
    cost_[j] = std::abs(dr) > residual_bound_[j] ? (dv * inv_virtual_step_[j]) * (dv * inv_virtual_step_[j]) : nan;
  }
  // The rows that stepped on unguarded windows (cost_ finite): the least costly is named when it
  // stands apart.
  const double margin = z_ * z_;
  const std::size_t t = w - 1;  // the step's tick, W - 1 ticks back
  // Row j's window rests on guarded samples (it was judged with a usable run short of the span).
  const auto guarded_window = [&](std::size_t j) { return usable_run_[j] < span_; };
  // Reading j's second difference on the tick `back` ticks before this one.
  const auto second_difference = [&](std::size_t j, std::size_t back) {
    const double* xs = &x_ring_[j * span_];
    return xs[slot(back)] - 2.0 * xs[slot(back + 1)] + xs[slot(back + 2)];
  };
  const auto least_costly = [&]() {
    std::size_t best = n;
    double best_cost = std::numeric_limits<double>::infinity();
    double runner_up = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j) {
      if (!std::isfinite(cost_[j]) || guarded_window(j)) continue;
      if (cost_[j] < best_cost) {
        runner_up = best_cost;
        best_cost = cost_[j];
        best = j;
      } else {
        runner_up = std::min(runner_up, cost_[j]);
      }
    }
    return best < n && best_cost <= margin && runner_up - best_cost >= margin && since_named_[best] >= w ? best : n;
  };
  // The reading's jump on the step's tick, when it is beyond its noise and what its row stepped
  // (a spike of a few ticks jumps by far more than the window's mean moves); NaN otherwise.
  const auto matched_jump = [&](std::size_t j) {
    const double jump = second_difference(j, t);
    return std::abs(jump) > jump_bound_[j] && std::abs(jump - step_[j]) <= jump_match_bound_[j] ? jump : nan;
  };
  const bool blamed_any = std::any_of(blamed_.begin(), blamed_.end(), [](char b) { return b != 0; });
  // A reading corrected in the rows: its step is its found fault changing or ending.
  const auto corrected = [&](std::size_t j) { return correction_wired_ && io.in(kCorrection)[j] != 0.0; };
  if (judge_in_guard_) {
    // Inside a guard loads move fast (a landing foot rolls onto its pads), so a row's cost tells
    // less than the tick's jump: the candidate is the one row within the cost bound whose reading
    // jumped by what its row stepped; none, or two, leave no candidate.
    std::size_t candidate = n;
    double candidate_jump = nan;
    int jumpers = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (!(cost_[j] <= margin)) continue;
      const double jump = matched_jump(j);
      if (!std::isfinite(jump)) continue;
      ++jumpers;
      candidate = j;
      candidate_jump = jump;
    }
    // Nor when another reading jumped on the step's tick or the next (its own jump or the return
    // of one a tick before): pads that move together there are a foot's load shifting, which
    // leaves no one jump to judge.
    bool alone = jumpers == 1;
    for (std::size_t i = 0; i < n && alone; ++i) {
      if (i == candidate) continue;
      // (At W = 1 the step's tick is this one: the next is not seen yet.) A reading without a
      // value there may have jumped: not alone.
      for (std::size_t back = t > 0 ? t - 1 : 0; back <= t && alone; ++back) {
        alone = std::abs(second_difference(i, back)) <= jump_bound_[i];
      }
    }
    if (alone && guarded_window(candidate) && blamed_[candidate] == 0 && since_named_[candidate] >= w &&
        std::isfinite(guard_bar_[candidate])) {
      since_named_[candidate] = 0;
      pending_[candidate] = 1;
      pending_jump_[candidate] = candidate_jump;
      // The level the move is measured from: the row before the guard, or, for a step on one of
      // the W - 1 ticks before the guard began (its window completes inside it), the row before
      // the step (the guard's baseline already holds part of the step).
      pending_before_[candidate] =
          guard_age_[candidate] + 1 < w ? level_before_[candidate] : guard_before_[candidate];
      pending_raised_[candidate] = raised_ring_[candidate * span_ + slot(t + 1)];
    }
  }
  const std::size_t best = least_costly();
  if (best < n) {
    if (std::isfinite(matched_jump(best))) {
      since_named_[best] = 0;
      if (blamed_[best] != 0) {
        size_[best] += step_[best];
        if (std::abs(size_[best]) <= release_bound_[best]) release(best);
      } else if (!corrected(best) && std::abs(level_[best]) > std::abs(level_[best] - step_[best]) &&
                 (judge_raised_rows_ || raised_ring_[best * span_ + slot(t + 1)] == 0 || blamed_any)) {
        // Blamed only for a step away from the row's fault-free level (one towards it ends a
        // fault nobody named, or another channel's), and not on a row raised before the step
        // with nothing named here (the step may begin a second fault or end that one).
        blamed_[best] = 1;
        size_[best] = step_[best];
        age_[best] = 0;
        alarm_seen_[best] = 0;
      }
    }
  }
  // Candidates from inside a guard, once W unguarded ticks have followed it.
  for (std::size_t j = 0; j < n && judge_in_guard_; ++j) {
    if (pending_[j] == 0 || usable_run_[j] < w) continue;
    pending_[j] = 0;
    double after = 0.0;
    for (std::size_t k = 0; k < w; ++k) after += r_ring_[j * span_ + slot(k)];
    const double level = after * inv_w;
    const double moved = level - pending_before_[j];
    if (blamed_[j] == 0 && !corrected(j) && std::abs(moved) > guard_bar_[j] &&
        std::abs(moved - pending_jump_[j]) <= std::min(guard_match_bound_[j], 0.5 * std::abs(pending_jump_[j])) &&
        std::abs(level) > std::abs(level - moved) &&
        (judge_raised_rows_ || pending_raised_[j] == 0 || blamed_any)) {
      blamed_[j] = 1;
      size_[j] = moved;
      age_[j] = 0;
      alarm_seen_[j] = 0;
    }
  }
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  const auto estimate = io.out(kFaultEstimate);
  for (std::size_t j = 0; j < n; ++j) {
    if (blamed_[j] != 0) {
      const bool raised = std::isfinite(alarm[j]) && alarm[j] != 0.0;
      age_[j] = std::min(age_[j] + 1, confirm_ticks_ + 1);
      if (raised) {
        alarm_seen_[j] = 1;
      } else if (alarm_seen_[j] != 0 || age_[j] > confirm_ticks_) {
        release(j);
      }
    }
    fault[j] = blamed_[j] != 0 ? 1.0 : 0.0;
    type[j] = fault_code(blamed_[j] != 0 ? FaultType::unclassified : FaultType::none);
    estimate[j] = blamed_[j] != 0 ? size_[j] : 0.0;
  }
  next_ = (next_ + 1) % span_;
}

}  // namespace ftsense::generic
