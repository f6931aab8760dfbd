#include "ftsense/generic/signal_validator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/false_alarm_target.hpp"
#include "ftsense/generic/level_run.hpp"

namespace ftsense::generic {

void SignalValidator::Params::describe(ParamSchema<Params>& schema) {
  schema
      .add("noise_std", &Params::noise_std,
           "standard deviation sigma of a healthy reading's noise, in the signal's unit; one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema
      .add("resolution", &Params::resolution,
           "quantisation step q of the reading, in its unit (0: continuous); one value applies to all")
      .at_least(0.0)
      .count_at_least(1);
  schema.add("upper_limit", &Params::upper_limit,
             "upper end of the measuring range (saturation at it); empty: none; one value applies to all");
  schema.add("lower_limit", &Params::lower_limit,
             "lower end of the measuring range (saturation at it); empty: none (a force sensor's 0 N is "
             "a healthy unloaded reading, not a limit); one value applies to all");
  schema.add("rest_value", &Params::rest_value,
             "the value the sensor's driver reads, exactly, when unloaded (0 for a foot force sensor "
             "that reports 0 N in the air); a run on it is not frozen by the reading alone; empty: none; "
             "one value applies to all");
  schema.add("window_s", &Params::window_s, "window of the frozen, noise and spike tests")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.005, 10.0, "tens of samples: milliseconds to seconds");
  schema.add("repeat_min_s", &Params::repeat_min_s,
             "the frozen test's shortest run of repeats (a reading that stays on its level): a driver "
             "holding its last value through lost packets repeats it for less")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.001, 1.0, "a few ticks to a second");
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between false alarms of one test on one healthy channel (sets the quantiles)")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("reference", &Params::reference,
             "adds input reference (a virtual sensor of the same quantity): the follow test, and spike and "
             "noise evidence only where reading - reference shows it too");
  schema.add("guard", &Params::guard,
             "adds input guard (nonzero on ticks whose own motion the rate does not resolve, such as a "
             "landing: change_guard after the contact flags): there no spike is seen and no second "
             "difference is counted, for noise or against it");
  schema
      .add("reference_noise_std", &Params::reference_noise_std,
           "standard deviation sigma_r of the reference's noise at the tick rate, in the signal's unit; "
           "one value applies to all")
      .at_least(0.0)
      .count_at_least(1);
  schema
      .add("min_reference_change", &Params::min_reference_change,
           "the low-passed reference must move this much over the window for the follow test (0: "
           "10 sqrt(sigma^2 + sigma_r^2)); one value applies to all")
      .at_least(0.0)
      .count_at_least(1);
  schema.add("follow_ratio", &Params::follow_ratio,
             "follow test: frozen when the reading moved less than this fraction of the reference's move")
      .greater_than(0.0)
      .at_most(1.0);
  schema.add("noise_margin", &Params::noise_margin,
             "a healthy reading's noise may lie between noise_std / m and m noise_std (load-dependent noise, a "
             "calibration on another log): the tests keep their false-alarm rate over that range")
      .at_least(1.0)
      .plausible(1.0, 4.0, "noise specifications hold within a factor of 1 to 2");
  schema.add("spike_hold_s", &Params::spike_hold_s,
             "the spikes flag holds this long after an episode's first spike (its rate is not known yet), "
             "and at most this long after any spike; taken as window_s when shorter")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.01, 10.0, "tenths of a second: a few gaps of a spike train");
  schema.add("spike_gap_probability", &Params::spike_gap_probability,
             "a spike episode ends after a gap that its measured rate leaves with this probability "
             "(h = ln(1 / p) / rate)")
      .greater_than(0.0)
      .less_than(1.0);
  schema.add("tests", &Params::tests,
             "the tests that run besides invalid and saturation: any of frozen, follow (the reading follows "
             "its reference's moves; with a reference), spikes, noise (without a reference, spikes and noise "
             "need a signal whose own motion the sample rate resolves)");
}

namespace {
constexpr std::array<std::string_view, 4> kOptionalTests{"frozen", "follow", "spikes", "noise"};
}  // namespace

void SignalValidator::Params::validate(Diagnostics& diag, std::string_view path) const {
  const std::vector<std::string> names(kOptionalTests.begin(), kOptionalTests.end());
  for (std::size_t i = 0; i < tests.size(); ++i) {
    if (std::find(names.begin(), names.end(), tests[i]) == names.end()) {
      diag.error(json_pointer_append(std::string(path) + "/tests", i),
                 "unknown test '" + tests[i] + "' (invalid and saturation always run); " + suggest(tests[i], names));
    } else if (std::find(tests.begin(), tests.begin() + static_cast<std::ptrdiff_t>(i), tests[i]) !=
               tests.begin() + static_cast<std::ptrdiff_t>(i)) {
      diag.error(json_pointer_append(std::string(path) + "/tests", i),
                 "'" + tests[i] + "' is listed twice; list each test once");
    }
  }
}

SignalValidator::SignalValidator(const Params& params, const StageContext& context)
    : sample_period_s_(context.sample_period_s()),
      follow_ratio_(params.follow_ratio),
      reference_(params.reference),
      guard_(params.guard) {
  const auto chosen = [&](std::string_view test) {
    return std::find(params.tests.begin(), params.tests.end(), test) != params.tests.end();
  };
  frozen_test_ = chosen("frozen");
  follow_test_ = chosen("follow");
  spike_test_ = chosen("spikes");
  noise_test_ = chosen("noise");
  const std::size_t dim = context.wired_dim("signal", params.noise_std.size());
  const auto noise_std = channel_values(params.noise_std, dim, "noise_std");
  const auto resolution = channel_values(params.resolution, dim, "resolution");
  const auto upper = channel_values(params.upper_limit, dim, "upper_limit", true);
  const auto lower = channel_values(params.lower_limit, dim, "lower_limit", true);
  const auto rest = channel_values(params.rest_value, dim, "rest_value", true);
  const auto reference_noise = channel_values(params.reference_noise_std, dim, "reference_noise_std");
  const auto min_change = channel_values(params.min_reference_change, dim, "min_reference_change");

  const double ticks = std::round(params.window_s / sample_period_s_);
  if (!(ticks >= 10.0 && ticks <= 1e6)) {
    throw ConfigError("/params/window_s", " = " + format_number(params.window_s) + " s is " + format_number(ticks) +
                                              " ticks of " + format_number(sample_period_s_) +
                                              " s; the variance tests need 10 to 1e6 ticks");
  }
  window_ = static_cast<std::size_t>(ticks);
  spike_hold_max_ticks_ = std::max(std::round(params.spike_hold_s / sample_period_s_), ticks);
  spike_rule_ = {spike_hold_max_ticks_, ticks, -std::log(params.spike_gap_probability)};
  check_noise_margin(params.noise_margin);
  const double alpha = false_alarm_per_tick(sample_period_s_, params.false_alarm_interval_s);
  // Overlapping second differences: nu = 36 n / 70 degrees of freedom (Satterthwaite).
  const double nu = 36.0 * static_cast<double>(window_) / 70.0;
  const double low_quantile = chi_square_quantile(nu, alpha) / nu;
  const double spike_z = two_sided_z(alpha);
  // Noise: the count of |d2| > 2 sqrt(6) s in the window. Healthy, each is over with p0 =
  // P(|Z| > 2); overlapping d2 are correlated, so the count's spread is taken as that of n / 2
  // independent draws (normal approximation of the binomial), and 3 more are allowed: one spike
  // or step puts up to 3 large d2 in the window, which is not noise.
  const double p0 = std::erfc(std::numbers::sqrt2);
  const double independent = 0.5 * static_cast<double>(window_);
  noise_count_above_ = static_cast<double>(window_) * p0 +
                       (-normal_quantile(alpha)) * std::sqrt(p0 * (1.0 - p0) * independent) * 2.0 + 3.0;
  limits_.resize(dim);
  for (std::size_t j = 0; j < dim; ++j) {
    Limits& l = limits_[j];
    const double q = resolution[j];
    const double sigma2 = noise_std[j] * noise_std[j];
    // Worst case of quantisation: a value on a level boundary reads either level, a fair coin of
    // variance q^2 / 4 (q^2 / 12 is only the average over values).
    const double quantisation2 = q * q / 4.0;
    const double own2 = sigma2 + quantisation2;
    const double residual2 = own2 + (reference_ ? reference_noise[j] * reference_noise[j] : 0.0);
    const double m = params.noise_margin;
    l.half_step = 0.5 * q;
    if (std::isfinite(upper[j]) && std::isfinite(lower[j]) && !(upper[j] - lower[j] > q)) {
      throw ConfigError("/params/upper_limit/" + std::to_string(j),
                        " = " + format_number(upper[j]) + " is not above lower_limit + resolution (" +
                            format_number(lower[j] + q) + ")");
    }
    l.upper = std::isfinite(upper[j]) ? upper[j] : std::numeric_limits<double>::infinity();
    l.lower = std::isfinite(lower[j]) ? lower[j] : -std::numeric_limits<double>::infinity();
    l.stale_test = noise_std[j] / m >= 0.5 * q;
    l.has_rest = std::isfinite(rest[j]);
    l.rest = l.has_rest ? rest[j] : 0.0;
    l.stale_below = 6.0 * sigma2 * static_cast<double>(window_) * low_quantile / (m * m);
    {
      // n_r (header), for noise as low as sigma / m.
      const double run = healthy_level_run_ticks(q, noise_std[j] / m, alpha);
      const double ticks = std::ceil(std::max(params.repeat_min_s / sample_period_s_, run) - 1e-9);
      l.repeat_ticks = l.stale_test && ticks < static_cast<double>(window_) ? static_cast<std::size_t>(std::max(2.0, ticks))
                                                                            : 0;
    }
    l.noise_level = 2.0 * m * std::sqrt(6.0 * own2);
    l.spike_above = spike_z * m * std::sqrt(1.5 * own2);
    l.residual_noise_level = 2.0 * m * std::sqrt(6.0 * residual2);
    l.residual_spike_above = spike_z * m * std::sqrt(1.5 * residual2);
    l.min_reference_change =
        min_change[j] > 0.0 ? min_change[j]
                            : 10.0 * std::sqrt(sigma2 + reference_noise[j] * reference_noise[j]);
  }
  // Low-pass of time constant n T / 8 for the follow test: its noise is small against a move.
  lp_gain_ = -std::expm1(-8.0 / static_cast<double>(window_));

  ports_.add_input(PortSpec{"signal", dim, std::string(kAnyUnit), "the readings x to validate"}.sized_by("as wired"));
  if (reference_) {
    ports_.add_input(PortSpec{"reference", dim, std::string(kAnyUnit),
                              "a virtual sensor of the same quantity (reference)", PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  if (guard_) {
    guard_input_ = reference_ ? 2 : 1;
    ports_.add_input(PortSpec{"guard", dim, std::string(kDimensionless),
                              "nonzero on a tick whose own motion the rate does not resolve (a transient): no spike "
                              "or noise evidence there",
                              PortRole::virtual_estimate}
                         .sized_by("as `signal`"));
  }
  ports_.add_output(PortSpec{"fault", dim, std::string(kDimensionless), "1 while a test fails, else 0"}
                        .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"fault_type", dim, std::string(kDimensionless),
                     "fault type code (fault_type.hpp): none, invalid, saturation, frozen, spikes or noise"}
                        .sized_by("as `signal`"));
  states_.resize(dim);
  sums_storage_.assign(2 * dim * window_, 0.0);
  lp_storage_.assign(2 * dim * (window_ + 1), 0.0);
  for (std::size_t j = 0; j < dim; ++j) {
    states_[j].tested_d2.offset = (2 * j) * window_;
    states_[j].reading_d2.offset = (2 * j + 1) * window_;
    states_[j].lp_signal.offset = (2 * j) * (window_ + 1);
    states_[j].lp_reference.offset = (2 * j + 1) * (window_ + 1);
  }
}

void SignalValidator::push(Window& w, std::vector<double>& storage, std::size_t size, double value) noexcept {
  double& slot = storage[w.offset + w.head];
  if (w.filled == size) {
    w.sum -= slot;
  } else {
    ++w.filled;
  }
  slot = value;
  w.sum += value;
  w.head = (w.head + 1) % size;
  if (w.head == 0) {
    // Once a window, the exact sum: a running sum of millions of ticks would drift.
    double exact = 0.0;
    for (std::size_t i = 0; i < size; ++i) exact += storage[w.offset + i];
    w.sum = exact;
  }
}

double SignalValidator::oldest(const Window& w, const std::vector<double>& storage, std::size_t size) noexcept {
  // Full ring: the slot at head is the oldest (it is overwritten next).
  return storage[w.offset + (w.filled == size ? w.head : 0)];
}

void SignalValidator::clear(Window& w) noexcept {
  w.head = 0;
  w.filled = 0;
  w.sum = 0.0;
}

void SignalValidator::reset() noexcept {
  for (State& s : states_) {
    State fresh;
    fresh.tested_d2.offset = s.tested_d2.offset;
    fresh.reading_d2.offset = s.reading_d2.offset;
    fresh.lp_signal.offset = s.lp_signal.offset;
    fresh.lp_reference.offset = s.lp_reference.offset;
    s = fresh;
  }
  std::fill(sums_storage_.begin(), sums_storage_.end(), 0.0);
  std::fill(lp_storage_.begin(), lp_storage_.end(), 0.0);
}

void SignalValidator::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  const std::size_t n = window_;
  for (std::size_t j = 0; j < limits_.size(); ++j) {
    const Limits& l = limits_[j];
    State& s = states_[j];
    const double r = reference_ ? io.in(kReference)[j] : 0.0;
    FaultType found = FaultType::none;

    if (!std::isfinite(x[j])) {
      // Nothing of this tick enters a window; the differences restart after the gap (and the d2
      // window then spans more than n + 2 readings: judge it as if one of them were at rest).
      s.x_history = s.y_history = 0;
      s.since_rest = 0;
      s.repeat_run = 0;
      s.lp_started = false;
      clear(s.lp_signal);
      clear(s.lp_reference);
      if (s.spikes.count > 0.0) s.spike_idle_ticks = std::min(s.spike_idle_ticks + 1, kTickCap);
      fault[j] = 1.0;
      type[j] = fault_code(FaultType::invalid);
      continue;
    }
    if (x[j] >= l.upper - l.half_step || x[j] <= l.lower + l.half_step) found = FaultType::saturation;

    // Frozen: the reading's own second differences. (Their noise and spike evidence, the
    // reading's part of the tests below, is taken here, before the history moves on.)
    double reading_d2 = 0.0, reading_spike = 0.0, reading_span = 0.0;
    if (s.x_history == 2) {
      reading_d2 = x[j] - 2.0 * s.x1 + s.x2;
      reading_spike = s.x1 - 0.5 * (s.x2 + x[j]);
      reading_span = x[j] - s.x2;
      push(s.reading_d2, sums_storage_, n, reading_d2 * reading_d2);
    }
    s.repeat_run = s.x_history > 0 && std::abs(x[j] - s.x1) <= l.half_step ? std::min(s.repeat_run + 1, window_) : 0;
    s.x2 = s.x1;
    s.x1 = x[j];
    s.x_history = std::min(s.x_history + 1, 2);
    // Without gaps the d2 window spans the last n + 2 readings; one of them at rest makes it no
    // evidence (a gap restarts the count, so a window across it waits n + 2 readings too).
    s.since_rest = l.has_rest && std::abs(x[j] - l.rest) <= l.half_step ? 0 : std::min(s.since_rest + 1, n + 2);
    const bool repeated = l.repeat_ticks > 0 && s.repeat_run >= l.repeat_ticks && s.since_rest > s.repeat_run;
    const bool stuck = found == FaultType::none && frozen_test_ && l.stale_test &&
                       (repeated || (s.reading_d2.filled == n && s.since_rest >= n + 2 && s.reading_d2.sum < l.stale_below));
    if (stuck && !s.stuck) {
      // A new stuck episode: at the previous one's value, a clip.
      s.clipped = s.stuck_before && std::abs(x[j] - s.stuck_value) <= l.half_step;
      s.stuck_value = x[j];
      s.stuck_before = true;
    }
    s.stuck = stuck;
    if (stuck) found = s.clipped ? FaultType::saturation : FaultType::frozen;

    // Follow (typed frozen): the reading does not follow the reference's move over the window.
    if (reference_ && std::isfinite(r)) {
      if (!s.lp_started) {
        s.lp_x = x[j];
        s.lp_r = r;
        s.lp_started = true;
      } else {
        s.lp_x += lp_gain_ * (x[j] - s.lp_x);
        s.lp_r += lp_gain_ * (r - s.lp_r);
      }
      push(s.lp_signal, lp_storage_, n + 1, s.lp_x);
      push(s.lp_reference, lp_storage_, n + 1, s.lp_r);
      if (found == FaultType::none && follow_test_ && s.lp_reference.filled == n + 1) {
        const double reference_move = std::abs(s.lp_r - oldest(s.lp_reference, lp_storage_, n + 1));
        const double reading_move = std::abs(s.lp_x - oldest(s.lp_signal, lp_storage_, n + 1));
        if (reference_move >= l.min_reference_change && reading_move < follow_ratio_ * reference_move) {
          found = FaultType::frozen;
        }
      }
    } else if (reference_) {
      s.lp_started = false;
      clear(s.lp_signal);
      clear(s.lp_reference);
    }

    // Spikes and noise: on x, and with a reference on x - r too (the same sign); not on a guarded
    // tick (NaN: guarded). A finite x - r has a finite x, so its history spans the reading's.
    const double y = x[j] - r;
    const bool guarded = guard_ && !(io.in(guard_input_)[j] == 0.0);
    if (std::isfinite(y)) {
      if (s.y_history == 2) {
        const double d2 = y - 2.0 * s.y1 + s.y2;
        const bool noisy = std::abs(reading_d2) > l.noise_level &&
                           (!reference_ || (std::abs(d2) > l.residual_noise_level && d2 * reading_d2 > 0.0));
        // A guarded tick is not seen: no evidence either way, so the window keeps the ticks seen
        // and the verdict holds through the guard, as through a non-finite reading (counted as
        // quiet, a landing's guard emptied a noise burst's window on every stride).
        if (!guarded) push(s.tested_d2, sums_storage_, n, noisy ? 1.0 : 0.0);
        // Blind for two windows (a guard that stays on): the verdict lapses, and the window
        // fills again from seen ticks.
        s.guarded_ticks = guarded ? std::min(s.guarded_ticks + 1, 2 * n) : 0;
        if (s.guarded_ticks == 2 * n) clear(s.tested_d2);
        const double off_neighbours = s.y1 - 0.5 * (s.y2 + y);
        const bool spike =
            std::abs(reading_spike) > l.spike_above && std::abs(reading_span) < std::abs(reading_spike) &&
            (!reference_ || (std::abs(off_neighbours) > l.residual_spike_above &&
                             std::abs(y - s.y2) < std::abs(off_neighbours) && off_neighbours * reading_spike > 0.0));
        if (!guarded) {
          s.spikes.see(1.0);
          if (spike) {
            s.spikes.spike(spike_rule_);
            s.spike_idle_ticks = 0;
          }
        }
      }
      s.y2 = s.y1;
      s.y1 = y;
      s.y_history = std::min(s.y_history + 1, 2);
    } else {
      s.y_history = 0;
    }
    // Noise before spikes: a burst is many spikes; isolated spikes stay under the count's bound.
    if (found == FaultType::none && noise_test_ && s.tested_d2.filled == n &&
        s.tested_d2.sum > noise_count_above_) {
      found = FaultType::noise;
    }
    // The hold counts seen ticks; a channel blind for twice the longest hold (a guard or a
    // reference that stays on, NaN readings) ends the episode all the same.
    if (found == FaultType::noise || !s.spikes.running() ||
        static_cast<double>(s.spike_idle_ticks) >= 2.0 * spike_hold_max_ticks_) {
      s.spikes.end();
    }
    if (found == FaultType::none && spike_test_ && s.spikes.count > 0.0) found = FaultType::spikes;
    if (s.spikes.count > 0.0) s.spike_idle_ticks = std::min(s.spike_idle_ticks + 1, kTickCap);

    fault[j] = found == FaultType::none ? 0.0 : 1.0;
    type[j] = fault_code(found);
  }
}

}  // namespace ftsense::generic
