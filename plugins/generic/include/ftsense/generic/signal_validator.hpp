#pragma once
// Per-channel signal validator: invalid, saturated, frozen, spiky and noisy readings, each judged
// against the sensor's own noise and resolution, with thresholds from a false-alarm target.
//
// Sensor model (unit U of the signal): a healthy reading is x = s + n + quantisation, n white
// with standard deviation sigma (`noise_std`), quantised in steps of q (`resolution`, 0: none),
// within [lower_limit, upper_limit] when those are given. With a `reference` input (a virtual
// sensor of the same quantity, noise sigma_r = `reference_noise_std`), x follows it. All tests
// run on every tick of period T; windows hold n = round(window_s / T) ticks; alpha, the chance of
// a false alarm per test, is T / false_alarm_interval_s, so the flags keep their false-alarm rate
// at any rate. A healthy sensor's noise is seldom known better than within a factor: it grows
// with the load on many sensors, and a calibration log is not the log judged. So every test keeps
// its false-alarm rate for any healthy noise between sigma / m and m sigma, m = `noise_margin`
// (default 1.5): the noise and spike levels below are taken at m sigma, the frozen bound at
// sigma / m. (At m = 1, on 100 s at 1 kHz, a healthy noise 30 % above sigma was flagged on 1091
// ticks, one 30 % below it on 13: `SignalValidator.NoiseMargin*` prints them.)
//
//   invalid     x is NaN or Inf: flagged on that tick.
//   saturation  x >= upper_limit - q / 2 or x <= lower_limit + q / 2: flagged on that tick. And,
//               limits given or not, a reading that the frozen test finds stuck again at the value
//               of its previous stuck episode (within q / 2), after moving in between: a clipped
//               signal returns to the same ceiling whenever its input exceeds it, while a frozen
//               sensor does not leave its value and come back (the first episode is frozen: one
//               stuck value alone cannot tell a clip from a freeze). The value is remembered
//               until reset: a sensor that freezes twice on the same value (within q / 2) is
//               typed saturation the second time, which is how it behaves.
//   frozen      the reading has less tick-to-tick variation than its own noise allows: with
//               d2 = x_t - 2 x_{t-1} + x_{t-2} (6 sigma^2 in variance, slow motion removed),
//               sum(d2^2 over n) < 6 (sigma / m)^2 chi2_nu(alpha) / nu, nu = 36 n / 70
//               (Satterthwaite: overlapping d2 are correlated). Only when sigma / m >= q / 2: a
//               sensor quantised coarser than its noise repeats itself when healthy (a steady load
//               in the middle of a step reads one level for ever), and the noise may be as low as
//               sigma / m (the bound's chi-square quantile assumes Gaussian d2, which a reading
//               that takes two or three levels is not).
//               And sooner where the sensor's noise shows on every tick: a reading that stays on
//               its level (within q / 2 of the reading before) for n_r ticks in a row (n_r + 1
//               readings), n_r = max(2, ceil(max(repeat_min_s / T, ln alpha / ln p))),
//               p = erf(q m / (2 sqrt(2) sigma)) the chance
//               that noise of sigma / m leaves a reading at its level's centre on that level (0
//               for a continuous reading: any run of exact repeats past repeat_min_s; a driver that
//               holds its last value through a few lost packets repeats it healthily for less),
//               and only when n_r < n: a clipped or frozen output is flagged within tens of
//               milliseconds, before the window fills with its silence.
//               Nor while the window holds a reading at the sensor's rest value (`rest_value`,
//               within q / 2): a driver that clamps an unloaded sensor there (a foot force
//               sensor reporting exactly 0 N in the air) repeats it exactly while healthy, so a
//               run on that value is no evidence of its own; the follow test and the constraint
//               residuals judge it against what the sensor should read.
//   follow      with a reference (a test of its own in `tests`; listed without a reference it
//               has nothing to judge): over the window, the low-passed reference moved by
//               |dr| >= `min_reference_change` (default 10 sqrt(sigma^2 + sigma_r^2)) while the
//               low-passed reading moved by less than `follow_ratio` |dr|: a frozen output that
//               still carries electrical noise (typed frozen). Low-pass time constant n T / 8.
//               Leave it out for a reference that carries other sensors' faults (a leave-one-out
//               force moves by a neighbour's offset, which the healthy reading rightly does not
//               follow). Until 2026-12-06 it ran as part of `frozen`.
//   noise       more |d2| > 2 sqrt(6 s^2) in the window than healthy noise gives (s^2 = sigma^2 +
//               q^2 / 4, the worst case: a value on a level boundary reads either level): healthy,
//               each is over with p0 = P(|Z| > 2) = 4.55 %; the count's bound is n p0 + 2 z_alpha
//               sqrt(p0 (1 - p0) n / 2) + 3 (overlapping d2 are correlated: n / 2 draws; the 3
//               let one spike or step pass, which puts up to 3 large d2 in the window). Without a
//               reference, the signal's own motion at the tick rate must be small against its noise.
//   spikes      one reading off both neighbours and back: D = x_{t-1} - (x_{t-2} + x_t) / 2 with
//               |D| > z sqrt(1.5 s^2) (z: the two-sided normal quantile of alpha) and
//               |x_t - x_{t-2}| < |D|. Seen one tick late. A faulty sensor's spikes come at
//               random (rate lambda, exponential gaps), and between them the reading looks
//               healthy: the flag holds through an episode, so that a recovery substitutes each
//               spike on its tick instead of letting it through before the test sees it. The
//               first spike of an episode (rate unknown) holds `spike_hold_s`; once it has n >= 2
//               spikes over D seconds (lambda^ = (n - 1) / D), the flag holds h =
//               ln(1 / p_gap) / lambda^ after the last, within [window_s, spike_hold_s]: a
//               running process leaves so long a gap with probability p_gap
//               (`spike_gap_probability`). D and the gap count only the ticks the test could see
//               (not guarded, finite), so blind stretches bias neither; a channel blind for
//               2 spike_hold_s after its last spike ends the episode all the same. spike_hold_s
//               under window_s is taken as window_s (the rule: spike_episode.hpp, shared with
//               contact_force_fdi). A noise burst ends the
//               episode (its spikes are the noise's tails; the noise test alone clears it).
//   with a reference r (noise and spikes): a tick is evidence only when the reading shows it (the
//               bounds above) and so does the residual y = x - r, with the same sign, against the
//               same bounds at s^2 + sigma_r^2. A sensor's noise and spikes are its own, in y as in
//               x; a load that moves faster than the rate resolves (a foot that bounces on and off
//               the ground, a landing logged at 200 Hz) moves r with x and leaves y alone. A
//               healthy tick passes both with no more chance than either, so the bounds hold.
// Invalid and saturation always run; `tests` chooses among frozen, follow (with a reference),
// spikes and noise. Without a reference, spikes and noise judge the reading's own second
// differences alone, so they hold only for a signal whose own motion the sample rate resolves:
// a foot's landing logged at 200 Hz is one sample off its neighbours, as a spike is. For such a signal leave them out, give a reference,
// or give a `guard` input (change_guard after the contact flags): on a tick it marks, no spike is
// seen and no second difference is counted, for noise or against it, so the tests judge the ticks
// between transients, and a verdict holds through a guard (the noise window keeps the ticks seen,
// as it does through non-finite readings), up to two windows of guarded ticks: a guard that stays
// on empties the window then, as the spike episode ends after twice its longest hold.
// The type reported is the first that fires in the order above (noise before spikes: a burst is
// many spikes, and isolated ones stay under the noise count's bound). A flag clears as soon as its
// test passes again (frozen and noise: the window no longer shows it; spikes: h after the last
// spike). Non-finite readings are left out of the windows.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/generic/spike_episode.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class SignalValidator {
 public:
  static constexpr std::string_view name = "signal_validator";
  static constexpr std::string_view summary =
      "invalid, saturated, frozen, spiky or noisy readings per channel, against the sensor's noise and resolution";
  // For the config reference's port table and the schema (plugin.hpp): inputs reference and guard are optional.
  static constexpr std::string_view example_params = R"([{}, {"reference": true, "guard": true}])";

  // `ftsense calibrate` measures each reading's white noise and quantisation step, and the
  // reference's noise where a reference is wired (tick_noise.hpp).
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
      {"reference_noise_std", "reference", FaultFreeStatistic::tick_noise},
  });

  struct Params {
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    std::vector<double> upper_limit{};
    std::vector<double> lower_limit{};
    std::vector<double> rest_value{};
    double window_s = 0.1;
    double repeat_min_s = 0.02;
    double false_alarm_interval_s = 86400.0;
    bool reference = false;
    bool guard = false;
    std::vector<double> reference_noise_std{0.0};
    std::vector<double> min_reference_change{0.0};
    double follow_ratio = 0.25;
    double noise_margin = 1.5;
    double spike_hold_s = 0.8;
    double spike_gap_probability = 0.01;
    std::vector<std::string> tests{"frozen", "follow", "spikes", "noise"};
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kSignal, kReference };
  enum Output : std::size_t { kFault, kFaultType };

  SignalValidator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  [[nodiscard]] std::size_t window_ticks() const noexcept { return window_; }

 private:
  // What channel j is judged against (set once from the parameters).
  struct Limits {
    double half_step = 0.0;          // q / 2
    double upper = 0.0, lower = 0.0;  // saturation limits (+-inf: none)
    bool stale_test = true;           // sigma / m >= q / 2
    double rest = 0.0;                // the value the driver clamps an unloaded sensor to
    bool has_rest = false;
    double stale_below = 0.0;         // sum(d2^2) of the reading below this: frozen
    std::size_t repeat_ticks = 0;     // n_r: a run of repeats this long is frozen (0: off)
    double noise_level = 0.0;         // |d2| of the reading above this counts for noise
    double spike_above = 0.0;         // |D| of the reading above this: spike
    double residual_noise_level = 0.0;  // the same for x - r, with a reference (sigma_r^2 added)
    double residual_spike_above = 0.0;
    double min_reference_change = 0.0;
  };
  // A window of n values with its running sum; the storage is a slice of a preallocated vector.
  struct Window {
    std::size_t offset = 0;  // into the shared storage
    std::size_t head = 0;
    std::size_t filled = 0;
    double sum = 0.0;
  };
  struct State {
    double y1 = 0.0, y2 = 0.0;  // previous two residuals x - r (with a reference)
    double x1 = 0.0, x2 = 0.0;  // previous two readings
    int y_history = 0, x_history = 0;  // consecutive finite values seen, up to 2
    std::size_t since_rest = 0;        // ticks since the reading was last at its rest value
    std::size_t repeat_run = 0;        // ticks in a row the reading stayed within q / 2 of the one before
    bool stuck = false;                // the frozen test failed on the previous tick
    bool clipped = false;              // the present stuck episode sits where the previous one did
    double stuck_value = 0.0;          // the value of the last stuck episode
    bool stuck_before = false;         // an earlier stuck episode exists
    Window tested_d2;    // 1 where |d2| shows noise (of x, and of x - r with a reference), else 0
    Window reading_d2;   // d2^2 of the reading
    Window lp_signal;    // low-passed reading, n + 1 values (only its ends are used)
    Window lp_reference;
    double lp_x = 0.0, lp_r = 0.0;
    bool lp_started = false;
    // The present spike episode, timed in the ticks the spike test could see (spike_episode.hpp),
    // and all ticks since its last spike.
    SpikeEpisode spikes;
    std::int64_t spike_idle_ticks = 0;
    std::size_t guarded_ticks = 0;  // consecutive guarded ticks (the noise window's blind time)
  };

  static constexpr std::int64_t kTickCap = 1'000'000'000'000;  // tick counters saturate here
  static void push(Window& w, std::vector<double>& storage, std::size_t size, double value) noexcept;
  static double oldest(const Window& w, const std::vector<double>& storage, std::size_t size) noexcept;
  static void clear(Window& w) noexcept;

  Ports ports_;
  std::vector<Limits> limits_;
  std::vector<State> states_;
  std::vector<double> sums_storage_;  // channels x 2 windows of n
  std::vector<double> lp_storage_;    // channels x 2 windows of n + 1
  std::size_t window_ = 10;
  double sample_period_s_;
  double spike_hold_max_ticks_ = 800.0;  // round(spike_hold_s / T): the first spike's hold, the longest h
  SpikeHoldRule spike_rule_;             // in ticks: that, window_s, ln(1 / spike_gap_probability)
  double lp_gain_ = 0.0;
  double noise_count_above_ = 0.0;  // more such |d2| in a window: noise
  double follow_ratio_ = 0.25;
  bool reference_ = false;
  bool frozen_test_ = true, follow_test_ = true, spike_test_ = true, noise_test_ = true;
  bool guard_ = false;
  std::size_t guard_input_ = 0;  // index of input guard, after signal (and reference)
};

}  // namespace ftsense::generic
