// Why this file is longer than the ~500 lines a file usually holds: it is the biped robust
// detector's one evidence loop, whose tests (jump, frozen, noise, airborne, sum residual, gain
// regression) share each channel's state tick by tick. Issue 13 replaces it with the generic FDI
// layer (signal validators, constraint residuals, change detection, classification, recovery),
// which splits it by role; cutting the loop into files before that would only scatter the state.
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>

#include "ftsense/biped/frames.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/median_of_three.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::biped {

namespace {

// Which evidence wins when several tests fire on one channel.
int priority(FaultType type) {
  switch (type) {
    case FaultType::invalid: return 6;
    case FaultType::frozen:
    case FaultType::saturation: return 5;
    case FaultType::noise: return 4;
    case FaultType::spikes: return 3;
    case FaultType::gain: return 2;
    case FaultType::drift:
    case FaultType::offset: return 1;
    case FaultType::none:
    case FaultType::unclassified: return 0;  // never raised here
  }
  return 0;
}

// The smallest |k| of a gain fault: a reading under a tenth of its force carries no usable
// scale of it (and the recovery N / k must stay bounded).
constexpr double kMinGain = 0.1;

// Tick counters stop here (about 12 days at 1 kHz): past it they would overflow.
constexpr int kCountCap = 1'000'000'000;

// sum (a - mean a)(b - mean b) over samples of total weight w, from sum a b, sum a and sum b.
double centred(double sum_ab, double sum_a, double sum_b, double w) { return sum_ab - sum_a * sum_b / w; }

bool corrects(FaultType type) {
  return type == FaultType::offset || type == FaultType::drift || type == FaultType::gain;
}

// Recovered from its own reading (corrected, low-passed or median-filtered) rather than
// substituted from the total force.
bool own_estimate(FaultType type) {
  return corrects(type) || type == FaultType::noise || type == FaultType::spikes;
}

// A channel's reading step as the jump test's sum residual takes it: a gain fault's reading is
// taken corrected (x / k), any other as read.
double in_residual(FaultType type, double gain, double step) { return type == FaultType::gain ? step / gain : step; }

// Ring buffers without an integer division per access (a 64-bit division costs tens of cycles;
// the window sums read two jump windows of each ring every tick): the slot `back` ticks before
// the newest of a ring of `size` whose next write goes to slot `next` (back < size), and the
// slot after `i`.
std::size_t ring_back(std::size_t next, std::size_t size, std::size_t back) noexcept {
  return next > back ? next - 1 - back : next + size - 1 - back;
}
std::size_t ring_after(std::size_t i, std::size_t size) noexcept { return i + 1 == size ? 0 : i + 1; }

}  // namespace

void ContactForceFdi::Params::describe(ParamSchema<Params>& schema) {
  schema.add("points_per_foot", &Params::points_per_foot,
             "force channels per foot (contact points with a sensor: 4 for a sole of 4 pads, 1 for a point foot); "
             "measured lists them foot after foot")
      .at_least(1).at_most(64).required();
  schema.add("noise_std_N", &Params::noise_std_N, "nominal standard deviation of a healthy sensor's noise")
      .unit("N").greater_than(0.0)
      .plausible(1e-3, 200.0, "millinewtons (load cells) to tens of newtons (insoles)");
  schema.add("weight_N", &Params::weight_N,
             "the robot's weight m g, for the thresholds that follow from the load (0: unknown; then give "
             "sum_threshold_N and gain_min_load_N)")
      .unit("N").at_least(0.0).plausible(5.0, 5000.0, "a 0.5 kg toy to a 500 kg machine");
  schema.add("airborne_height_m", &Params::airborne_height_m, "a pad this high above the ground carries nothing")
      .unit("m").greater_than(0.0).plausible(plausible::foot_height_m());
  schema.add("airborne_settle_s", &Params::airborne_settle_s, "time a pad must be airborne before it is tested")
      .unit("s").at_least(0.0).plausible(0.0, 5.0, "a part of a swing phase (0.2 to 1 s)");
  schema.add("airborne_threshold_N", &Params::airborne_threshold_N, "|mean reading| of an airborne pad that is a fault; 0: 4 sigma_x, the readings' error sigma_x = sqrt(noise_std_N^2 + resolution_N^2 / 12)")
      .unit("N").at_least(0.0).plausible(plausible::force_threshold_N());
  schema.add("airborne_clear_N", &Params::airborne_clear_N, "|mean reading| of an airborne pad that re-admits it; 0: 2 sigma_x")
      .unit("N").at_least(0.0).plausible(plausible::force_threshold_N());
  schema.add("jump_threshold_N", &Params::jump_threshold_N, "one-tick change of a single channel that is a jump candidate; 0: 10 sigma_x")
      .unit("N").at_least(0.0).plausible(plausible::force_threshold_N());
  schema.add("jump_confirm_N", &Params::jump_confirm_N, "smallest sum-residual step that confirms a jump; 0: 12.5 sigma_x")
      .unit("N").at_least(0.0).plausible(plausible::force_threshold_N());
  schema.add("jump_window_s", &Params::jump_window_s, "window of the sum-residual step test")
      .unit("s").greater_than(0.0).at_most(1.0).plausible(1e-4, 1.0, "one tick at 10 kHz to a second");
  schema.add("touchdown_guard_s", &Params::touchdown_guard_s,
             "no jump or spike test this long after any foot touches down (landing impacts)")
      .unit("s").at_least(0.0).plausible(0.0, 5.0, "landing impacts settle within tenths of a second");
  schema.add("touchdown_height_m", &Params::touchdown_height_m,
             "a foot touches down when all its pads come below this height")
      .unit("m").greater_than(0.0).plausible(plausible::foot_height_m());
  schema.add("resolution_N", &Params::resolution_N,
             "quantisation step q of the sensors (0: continuous): readings within q / 2 count as repeated")
      .unit("N").at_least(0.0)
      .plausible(0.0, 100.0, "force sensors quantise in steps of up to a few newtons");
  schema.add("zero_clamp_N", &Params::zero_clamp_N,
             "the sensors' driver reports any reading below this as exactly 0 N (0: none known): a zero "
             "reading is frozen evidence only while the leave-one-out force exceeds it by sum_threshold_N")
      .unit("N").at_least(0.0)
      .plausible(0.0, 1000.0, "a clamp of a few noise deviations");
  schema.add("upper_limit_N", &Params::upper_limit_N,
             "top of the sensors' measuring range: stuck there is saturation (0: unknown, judged by the "
             "largest value seen)")
      .unit("N").at_least(0.0);
  schema.add("frozen_min_s", &Params::frozen_min_s,
             "shortest run on one level that is frozen (longer when quantisation makes healthy repeats likely)")
      .unit("s").greater_than(0.0).plausible(plausible::flag_delay_s());
  schema.add("false_alarm_interval_s", &Params::false_alarm_interval_s,
             "mean time between false alarms of the frozen test on one healthy channel (sets its run length)")
      .unit("s").greater_than(0.0).plausible(1.0, 1e9, "from a second (tests) to decades");
  schema.add("spike_threshold_N", &Params::spike_threshold_N, "deviation from both neighbours that is a spike; 0: 30 sigma_x")
      .unit("N").at_least(0.0).plausible(plausible::force_threshold_N());
  schema.add("spike_hold_s", &Params::spike_hold_s,
             "the spikes flag stays at most this long after the last spike (this long after an episode's first)")
      .unit("s").at_least(0.0).plausible(plausible::flag_delay_s());
  schema.add("spike_gap_probability", &Params::spike_gap_probability,
             "chance that a spiking sensor still spiking leaves a gap as long as the hold (sets the hold from the "
             "episode's spike rate)")
      .greater_than(0.0).less_than(1.0).plausible(1e-6, 0.2, "a hold of 1.6 to 14 mean gaps");
  schema.add("noise_window_s", &Params::noise_window_s, "window of the noise-burst test")
      .unit("s").greater_than(0.0).at_most(1.0).plausible(1e-3, 1.0, "ten ticks at 10 kHz to a second");
  schema.add("noise_factor", &Params::noise_factor,
             "second differences above this many healthy standard deviations count as noisy")
      .greater_than(0.0).plausible(1.0, 100.0, "below 1 standard deviation healthy noise counts as noisy");
  schema.add("sum_cutoff_hz", &Params::sum_cutoff_hz, "low-pass cut-off of the sum residual for the unisolated test")
      .unit("Hz").greater_than(0.0).plausible(plausible::cutoff_hz());
  schema.add("sum_threshold_N", &Params::sum_threshold_N,
             "|low-passed corrected sum residual| (what the flagged channels' corrections leave) that is an "
             "unisolated or virtual-sensor fault; 0: 7 % of weight_N")
      .unit("N").at_least(0.0).plausible(plausible::force_threshold_N());
  schema.add("clear_s", &Params::clear_s, "time the raising test must stay clear to re-admit a channel")
      .unit("s").at_least(0.0).plausible(plausible::flag_delay_s());
  schema.add("hold_s", &Params::hold_s, "a raised flag stays at least this long; spikes keep it this long after the last")
      .unit("s").at_least(0.0).plausible(plausible::flag_delay_s());
  schema.add("gain_window_s", &Params::gain_window_s,
             "window of the stance regression of the sum residual on each channel (gain test)")
      .unit("s").greater_than(0.0).at_most(60.0)
      .plausible(0.05, 60.0, "a part of a stance phase to a minute");
  schema.add("gain_threshold", &Params::gain_threshold,
             "|1 - 1/k| of a channel reading k times its force that is a gain fault")
      .greater_than(0.0).less_than(1.0);
  schema.add("gain_explained", &Params::gain_explained,
             "share of the sum residual's power a channel's gain fit must explain to be blamed")
      .greater_than(0.0).less_than(1.0);
  schema.add("gain_isolation_margin", &Params::gain_isolation_margin,
             "share of the residual's power by which the blamed channel's fit must beat every other channel's")
      .greater_than(0.0).less_than(1.0);
  schema.add("gain_min_load_N", &Params::gain_min_load_N,
             "RMS load a channel must carry over the gain window to be judged by the gain test; 0: 2.5 % of weight_N")
      .unit("N").at_least(0.0).plausible(plausible::force_threshold_N());
  schema.add("follow_ratio", &Params::follow_ratio,
             "an offset or drift whose reading spans less than this share of its leave-one-out force's span is "
             "a frozen output that keeps its noise")
      .greater_than(0.0).less_than(0.5);
  schema.add("ramp_history_s", &Params::ramp_history_s,
             "how far back the sum residual's history reaches (16 block means) when a fault the air finds is "
             "typed: a ramp there that ends at the air's level makes it a drift")
      .unit("s").greater_than(0.0).at_most(600.0)
      .plausible(1.0, 120.0, "a few strides to two minutes");
  schema.add("points", &Params::points,
             "the contact points (x, y) of each foot's channels on a rigid sole, foot frame, every foot alike (as "
             "contact_point_height's points; a $ref to one definition keeps them one): a foot's loads in full "
             "contact then lie on a plane, which apportions what the total force leaves among substituted "
             "channels; empty: the sum alone (equal shares)")
      .unit("m").count_at_most(64).plausible(plausible::foot_point_m());
}

void ContactForceFdi::LineFit::add(double t, double b, double weight) noexcept {
  const double x = t - t0;
  n += weight;
  st += weight * x;
  sb += weight * b;
  stt += weight * x * x;
  stb += weight * x * b;
}

double ContactForceFdi::LineFit::span() const noexcept {
  if (n <= 0) return 0.0;
  const double variance = stt / n - (st / n) * (st / n);
  return variance > 0 ? std::sqrt(12.0 * variance) : 0.0;  // the length of a uniform spread
}

double ContactForceFdi::LineFit::slope_scale() const noexcept {
  if (n <= 0) return 0.0;
  const double spread = stt - st * st / n;
  return spread > 0 ? std::sqrt(spread) : 0.0;
}

void ContactForceFdi::LineFit::solve(double& a, double& s) const noexcept {
  if (n <= 0) return;
  const double det = n * stt - st * st;
  if (det > 1e-12 * n * n) {
    s = (n * stb - st * sb) / det;
    a = (sb - s * st) / n;
  } else {
    s = 0.0;
    a = sb / n;
  }
}

namespace {
// The variance, in units of its input's (white), of a low-pass y += a (r - y) seeded with its first
// value, which keeps the weight w = (1 - a)^k after k ticks: w^2 + a (1 - w^2) / (2 - a).
double seeded_low_pass_variance(double a, double seed_weight) {
  const double w2 = seed_weight * seed_weight;
  return w2 + a * (1.0 - w2) / (2.0 - a);
}

// Window lengths in ticks, checked before anything is allocated: a window is at most 100,000
// ticks (e.g. 1 s at 100 kHz), so a tiny tick period cannot ask for gigabytes.
constexpr double kMaxWindowTicks = 100000.0;
int window_ticks(double window_s, double period_s, int minimum, const char* key) {
  const double ticks = window_s / period_s;
  if (!(ticks <= kMaxWindowTicks)) {
    throw ConfigError(std::string("/params/") + key,
                      " = " + format_number(window_s) + " violates at most 100000 ticks of the pipeline's " +
                          format_number(period_s) + " s (a window this long is a configuration error)");
  }
  return std::max(minimum, static_cast<int>(std::lround(ticks)));
}

// The airborne test judges the mean of the readings taken after airborne_settle_s over at least
// this long (and at least 10 readings): a healthy sensor's noise (noise_std_N = 2 N) averages to
// about 0.5 N over 20 readings at 1 kHz, far below airborne_threshold_N. A length of its own, not
// the settling time: one waits out the lift-off, the other averages the noise.
constexpr double kAirborneMeanWindow_s = 0.02;

// The thresholds a config leaves at 0, in the readings' error sigma (noise_std_N and the
// quantisation resolution_N: sqrt(noise^2 + q^2 / 12)): an airborne
// mean of 20 readings has sigma / 4.5, so 4 sigma is 18 of its sigmas; a healthy reading's
// one-tick change has sqrt(2) sigma plus the load's own change, a jump needs 10 sigma; a spike
// 30 sigma. They are the values the SURALP walk (sigma = 2 N) was run with.
constexpr double kAirborneSigmas = 4.0, kAirborneClearSigmas = 2.0;
constexpr double kJumpSigmas = 10.0, kJumpConfirmSigmas = 12.5, kSpikeSigmas = 30.0;
// And in the robot's weight W = m g: the low-passed sum residual's bound (the unmodelled limb
// dynamics, about 20 N RMS, 1.8 % of W, on the simulated SURALP) and the load a channel must carry for the
// gain regression.
constexpr double kSumThresholdWeight = 0.07, kGainMinLoadWeight = 0.025;
}  // namespace

ContactForceFdi::ContactForceFdi(const Params& params, const StageContext& context)
    : params_(params),
      period_s_(context.sample_period_s()),
      feet_points_(static_cast<std::size_t>(std::max(1, params.points_per_foot))),
      noise_window_ticks_(window_ticks(params.noise_window_s, context.sample_period_s(), 4, "noise_window_s")),
      jump_window_ticks_(window_ticks(params.jump_window_s, context.sample_period_s(), 2, "jump_window_s")) {
  if (!(kAirborneMeanWindow_s / context.sample_period_s() <= kMaxWindowTicks)) {
    throw ConfigError("", "the pipeline's sample period " + format_number(context.sample_period_s()) +
                              " s is too short for contact_force_fdi: its airborne mean of " +
                              format_number(kAirborneMeanWindow_s) + " s would be more than 100000 ticks");
  }
  // The frozen test's run length n_f (header): the probability p that healthy noise leaves a
  // reading on its quantisation level, and alpha, the false-alarm probability per tick.
  repeat_band_N_ = 0.5 * params.resolution_N;
  // The noise test's bars (step): a pad's second difference, and its foot's summed reading's.
  tick_noise_N_ = std::sqrt(6.0 * (params_.noise_std_N * params_.noise_std_N + repeat_band_N_ * repeat_band_N_)) *
                  params_.noise_factor;
  foot_noise_N_ = tick_noise_N_ * std::sqrt(static_cast<double>(feet_points_));
  {
    const double stay = std::erf(params.resolution_N / (2.0 * std::sqrt(2.0) * params.noise_std_N));
    const double alpha = std::min(0.5, context.sample_period_s() / params.false_alarm_interval_s);
    const double run = stay > 0.0 ? std::log(alpha) / std::log(std::min(stay, 1.0 - 1e-15)) : 0.0;
    const double ticks = std::max(params.frozen_min_s / context.sample_period_s(), run);
    // Beyond kMaxWindowTicks a healthy reading may sit on one level longer than any window: its
    // quantiser is coarser than its noise can dither (10 N steps under 0.7 N of noise: p = 1 -
    // 1e-12). A reading alone then cannot tell a stuck sensor from a steady load, so the repeat
    // test is off (its counter never reaches the cap) and a stuck sensor is left to the sum
    // residual and the follow test, which judge it against the load it should read.
    repeat_test_off_ = !(ticks <= kMaxWindowTicks);
    frozen_ticks_ = repeat_test_off_ ? std::numeric_limits<int>::max()
                                     : std::max(2, static_cast<int>(std::ceil(ticks - 1e-9)));
  }
  smoothing_ = -std::expm1(-2.0 * 3.141592653589793 * kSmoothingHz * period_s_);
  // Five time constants of that low-pass: a step has settled to within e^-5 (under 1 %).
  smoother_settle_s_ = 5.0 / (2.0 * 3.141592653589793 * kSmoothingHz);
  // Half a settling, less half a tick (a window a tick late on a rounded sum skips no turn).
  short_window_stagger_s_ = 0.5 * smoother_settle_s_ - 0.5 * period_s_;
  // A stuck reading's noise through the low-pass y += a (x - y): std sigma sqrt(a / (2 - a)); its
  // range stays within +-4 of those, and a quantised one moves by a level more.
  still_band_N_ = params_.resolution_N +
                  8.0 * params_.noise_std_N * std::sqrt(smoothing_ / (2.0 - smoothing_));
  guard_pending_limit_s_ = 4.0 * params.touchdown_guard_s + 2.0 * jump_window_ticks_ * period_s_;
  spike_rule_ = {params_.spike_hold_s, std::min(params_.clear_s, params_.spike_hold_s),
                 std::log(1.0 / params_.spike_gap_probability)};
  min_airborne_samples_ = std::max(10, static_cast<int>(std::lround(kAirborneMeanWindow_s / context.sample_period_s())));
  // Thresholds left at 0 follow from the readings' error and the robot's weight W (header). The
  // error is the noise and the quantisation, sigma^2 + q^2 / 12: where the noise cannot dither a
  // coarse quantiser, a healthy reading on a steady load still steps by q between levels, and
  // thresholds of noise alone (10 N steps under 0.7 N of noise: a 7 N jump threshold) would take
  // every level change for a jump.
  const double sigma =
      std::sqrt(params.noise_std_N * params.noise_std_N + params.resolution_N * params.resolution_N / 12.0);
  reading_sigma_N_ = sigma;
  if (const double q = params.resolution_N; q > 0.0) {
    const double pi = std::numbers::pi;
    quantiser_bias_N_ = 0.5 * q * std::exp(-2.0 * pi * pi * params.noise_std_N * params.noise_std_N / (q * q));
  }
  const auto derive = [](double& value, double derived) {
    if (value == 0.0) value = derived;
  };
  derive(params_.airborne_threshold_N, kAirborneSigmas * sigma);
  derive(params_.airborne_clear_N, kAirborneClearSigmas * sigma);
  derive(params_.jump_threshold_N, kJumpSigmas * sigma);
  derive(params_.jump_confirm_N, kJumpConfirmSigmas * sigma);
  derive(params_.spike_threshold_N, kSpikeSigmas * sigma);
  if (params.weight_N == 0.0 && (params.sum_threshold_N == 0.0 || params.gain_min_load_N == 0.0)) {
    throw ConfigError("/params/weight_N", "is needed: sum_threshold_N and gain_min_load_N follow from the robot's "
                                          "weight m g (N) unless both are given");
  }
  derive(params_.sum_threshold_N, kSumThresholdWeight * params.weight_N);
  derive(params_.gain_min_load_N, kGainMinLoadWeight * params.weight_N);
  zero_evidence_above_N_ = std::max(params_.airborne_threshold_N, params_.zero_clamp_N + params_.sum_threshold_N);
  residual_near_N_ = params_.follow_ratio * params_.sum_threshold_N;
  if (params_.airborne_clear_N >= params_.airborne_threshold_N) {
    const auto shown = [](double given, double used) {
      return format_number(used) + (given == 0.0 ? " (derived from noise_std_N and resolution_N)" : "");
    };
    throw ConfigError("/params/airborne_clear_N", " = " + shown(params.airborne_clear_N, params_.airborne_clear_N) +
                                                      " violates < " +
                                                      shown(params.airborne_threshold_N, params_.airborne_threshold_N) +
                                                      " (airborne_threshold_N: re-admission needs a lower level)");
  }
  // The feet: as many as the measured channels make, points_per_foot each.
  const std::size_t n = context.wired_dim("measured", 2 * feet_points_);
  if (n == 0 || n % feet_points_ != 0) {
    throw ConfigError("/inputs/measured", "carries " + std::to_string(n) + " channels, not a whole number of feet of " +
                                              std::to_string(feet_points_) + " (points_per_foot)");
  }
  feet_ = n / feet_points_;
  const std::string per_point = "as wired: points_per_foot per foot";
  ports_.add_input(PortSpec{"measured", n, "N", "contact-point forces, foot after foot", PortRole::measured}
                       .sized_by(per_point));
  ports_.add_input(PortSpec{"total_force", 3, "N", "total ground reaction force m R_wb f_imu", PortRole::virtual_estimate}
                       .in_frame("world"));
  ports_.add_input(PortSpec{"point_height", n, "m",
                            "height of each channel's contact point above the ground (kinematics, e.g. "
                            "contact_point_height); NaN: unknown, taken as on the ground"}
                       .sized_by("as measured"));
  ports_.add_output(PortSpec{"fault", n, "1", "1 when the channel is judged faulty"}.sized_by(per_point));
  ports_.add_output(PortSpec{"fault_type", n, "1", "fault type code (fault_type.hpp)"}.sized_by(per_point));
  ports_.add_output(PortSpec{"fault_estimate", n, "N", "measured - recovered: the estimated fault contribution"}
                        .sized_by(per_point));
  ports_.add_output(PortSpec{"recovered", n, "N", "the force to use downstream"}.sized_by(per_point));
  ports_.add_output(PortSpec{"virtual", n, "N", "leave-one-out virtual force: 0 airborne, else F_z - sum of the others",
                             PortRole::signal, /*leave_one_out=*/true}
                        .sized_by(per_point));
  ports_.add_output({"sum_residual", 1, "N", "low-passed sum of recovered forces - F_z"});
  ports_.add_output({"unisolated", 1, "1", "1 while the corrected sum residual is off with no channel to blame (a fault not isolated, or of the virtual sensor)"});
  ports_.add_output({"virtual_ready", 1, "1", "1 while the total force F_z is finite (0: virtual sensor not ready)"});
  ports_.add_output(PortSpec{"cannot_judge", n, "1",
                             "1 for a channel not flagged while unisolated is 1: the virtual sensor is not ready, or "
                             "the sum residual is off with no channel to blame"}
                        .sized_by(per_point));
  gain_window_ticks_ = window_ticks(params.gain_window_s, context.sample_period_s(), 10, "gain_window_s");
  sum_block_target_ticks_ = std::max(
      1, static_cast<int>(std::lround(window_ticks(params.ramp_history_s, context.sample_period_s(), 1, "ramp_history_s") /
                                      static_cast<double>(generic::LevelHistory::kCapacity))));
  gain_forgetting_ = std::exp(-1.0 / gain_window_ticks_);
  gain_window_.resize(n);
  since_unexplained_.resize(n);
  gain_raw_rr_.assign(n, 0.0);
  gain_held_ticks_.assign(n, 0);
  joint_gain_set_.assign(n, 0);
  gain_held_rr_.assign(n, 0.0);
  stance_powers_.assign(n, StancePowers{});
  stance_cusum_.assign(n, StancePowers{});
  guard_powers_.assign(n, StancePowers{});
  stance_min_ticks_ = std::max(2, static_cast<int>(std::min(std::round(params.clear_s / period_s_), 1e9)));
  residual_level_gain_ = 1.0 / static_cast<double>(stance_min_ticks_);
  channels_.resize(n);
  for (auto& c : channels_) {
    c.second_diff.assign(static_cast<std::size_t>(noise_window_ticks_), 0.0);
    c.first_diff.assign(static_cast<std::size_t>(noise_window_ticks_), 0.0);
    c.noisy_tick.assign(static_cast<std::size_t>(noise_window_ticks_), 0);
  }
  residual_ring_.assign(static_cast<std::size_t>(2 * jump_window_ticks_), 0.0);
  last_touchdown_s_.assign(feet_, -1e9);
  foot_airborne_.assign(feet_, 0);
  foot_reads_unloaded_.assign(feet_, 0);
  foot_sum_.assign(feet_, {0.0, 0.0});
  foot_sum_ticks_.assign(feet_, 0);
  foot_d2_.assign(feet_, 0.0);
  foot_unread_.assign(feet_, 0);
  foot_landing_pads_.assign(feet_, 0);
  landing_state_.assign(n, kNoLandingStep);
  for (auto* range : {&still_lo_, &still_hi_, &since_low_min_, &since_low_max_, &since_high_min_, &since_high_max_}) {
    range->assign(still_windows_.size() * n, 0.0);
  }
  still_grounded_.assign(still_windows_.size() * n, 0);
  smoothed_.assign(n, 0.0);
  judgeable_.assign(n, 0);
  channel_foot_.resize(n);
  for (std::size_t j = 0; j < n; ++j) channel_foot_[j] = j / feet_points_;
  if (!params.points.empty() && params.points.size() != feet_points_) {
    throw ConfigError("/params/points", "has " + std::to_string(params.points.size()) +
                                            " points, not points_per_foot = " + std::to_string(feet_points_) +
                                            " (one [x, y] per channel of a foot, in the order of measured)");
  }
  unmeasured_ = UnmeasuredContactLoads(params.points, feet_points_, feet_);
  unknown_.assign(n, 0);
  lower_bound_.assign(n, 0.0);
  plane_usable_.assign(feet_, 0);
  const std::size_t relations = unmeasured_.relations_per_foot();
  const std::size_t ring = static_cast<std::size_t>(2 * jump_window_ticks_);
  relation_ring_.assign(feet_ * relations * ring, 0.0);
  full_contact_run_.assign(feet_, 0);
  relation_group_.assign(feet_, 0);
  relation_group_age_.assign(feet_, 0);
  relation_expect_.assign(feet_ * relations, 0.0);
  relation_step_.assign(feet_ * relations, 0.0);
  relation_before_.assign(feet_ * relations, 0.0);
  relation_step_known_.assign(feet_, 0);
  relation_verdict_.assign(relations > 0 ? feet_ : 0, 0);
  relation_group_size_.assign(relations > 0 ? feet_ : 0, 0);
  relation_step_square_.assign(feet_ * relations, 0.0);
  relation_step_count_.assign(feet_, 0.0);
  relation_z_ = generic::normal_quantile(1.0 - 0.5 * std::min(0.5, context.sample_period_s() / params.false_alarm_interval_s));
  // A pad's one-tick excursion N_{k-1} - (N_k + N_{k-2}) / 2 carries sqrt(3/2) sigma_x of noise.
  rocking_bar_N_ = relation_z_ * std::sqrt(1.5) * reading_sigma_N_;
  step_back_bar_N_ = relation_z_ * std::sqrt(2.0) * reading_sigma_N_;
  // One decision per landing, and landings are at least a guard apart.
  guard_z_ = generic::normal_quantile(1.0 - 0.5 * std::min(0.5, params.touchdown_guard_s / params.false_alarm_interval_s));
}

void ContactForceFdi::reset() noexcept {
  for (auto& c : channels_) {
    std::vector<double> ring = std::move(c.second_diff);
    std::vector<double> ring1 = std::move(c.first_diff);
    std::vector<int> flags = std::move(c.noisy_tick);
    std::fill(flags.begin(), flags.end(), 0);
    std::fill(ring.begin(), ring.end(), 0.0);
    std::fill(ring1.begin(), ring1.end(), 0.0);
    c = Channel{};
    c.second_diff = std::move(ring);
    c.first_diff = std::move(ring1);
    c.noisy_tick = std::move(flags);
  }
  std::fill(residual_ring_.begin(), residual_ring_.end(), 0.0);
  residual_next_ = 0;
  residual_count_ = 0;
  usable_ticks_in_a_row_ = 0;
  residual_level_ = corrected_level_ = 0.0;
  residual_level_seed_weight_ = 1.0;
  residual_before_touchdown_ = 0.0;
  residual_before_known_ = was_touching_down_ = false;
  guard_onsets_clear_ticks_ = 0;
  guard_began_s_ = last_flag_change_s_ = last_tick_s_ = -1e300;
  guard_step_ticks_ = -1;
  guard_step_square_ = 0.0;
  guard_step_count_ = 0;
  group_before_ = 0.0;
  sum_filtered_ = 0.0;
  residual_smoothed_ = 0.0;
  residual_smoothed_started_ = false;
  for (StillWindow& w : still_windows_) w = StillWindow{};
  next_short_window_ = 0;
  next_short_window_s_ = -1e300;
  unread_candidate_ = channels_.size();
  residual_within_bound_s_ = -1e300;
  still_window_settle_until_s_ = -1e300;
  started_ = false;
  group_pending_ = false;
  late_pending_ = group_deferred_ = false;
  ticks_since_divisor_change_ = kCountCap;
  guard_powers_last_s_ = -1e300;
  std::fill(last_touchdown_s_.begin(), last_touchdown_s_.end(), -1e9);
  std::fill(foot_sum_.begin(), foot_sum_.end(), std::array<double, 2>{0.0, 0.0});
  std::fill(foot_sum_ticks_.begin(), foot_sum_ticks_.end(), 0);
  std::fill(foot_airborne_.begin(), foot_airborne_.end(), 0);
  restart_gain_window();
  since_unexplained_.restart();
  since_unexplained_open_ = false;
  gain_unisolated_ = false;
  unmeasured_.reset();
  sum_levels_.clear();
  sum_block_ticks_ = sum_block_count_ = 0;
  sum_block_sum_ = sum_block_t_sum_ = 0.0;
  sum_block_clean_ = true;
  sum_block_d2_.fill(0.0);
  sum_block_d2_next_ = sum_block_d2_count_ = 0;
  sum_block_full_run_ = 0;
  sum_block_last_means_ = {0.0, 0.0};
  std::fill(full_contact_run_.begin(), full_contact_run_.end(), 0);
  relation_next_ = 0;
  std::fill(relation_group_.begin(), relation_group_.end(), 0);
  std::fill(relation_step_known_.begin(), relation_step_known_.end(), 0);
  std::fill(relation_step_square_.begin(), relation_step_square_.end(), 0.0);
  std::fill(relation_step_count_.begin(), relation_step_count_.end(), 0.0);
}

void ContactForceFdi::raise(Channel& c, FaultType type, double t) noexcept {
  if (c.type == FaultType::none) {
    c.flagged_since = t;
    last_flag_change_s_ = t;
    c.type = type;
  } else if (priority(type) > priority(c.type)) {
    c.type = type;
    c.still_load_drift = false;  // no longer the drift it was raised as
  }
  c.clear_since = -1.0;
}

void ContactForceFdi::clear(Channel& c) noexcept {
  if (c.type != FaultType::none) last_flag_change_s_ = last_tick_s_;
  c.type = FaultType::none;
  c.end_pending = false;
  c.offset = c.slope = 0.0;
  c.gain = 1.0;
  c.fit_has_air = c.air_refit = c.air_block_reads_zero = false;
  c.still_load_drift = false;
  c.clear_since = -1.0;
  c.following = c.frozen_by_follow = c.follows_load = false;
  c.sign_fault = false;
  c.reads_as_gain = false;
  c.negative_fit = SlopeFit{};
  c.air_levels.clear();  // the fault's swings are no healthy level
}

bool ContactForceFdi::load_rocked(std::size_t j, double spike, std::span<const double> measured) const noexcept {
  // Another pad of the foot that reads its load (healthy, or corrected: a noise burst's or a
  // spiking pad's excursions are its own; a gain's taken as its load, N / k) made the opposite
  // one-tick excursion on this tick, beyond what its noise makes on a tick (z sqrt(3/2) sigma_x),
  // and came back: its reading moved over the two ticks by less than that excursion (a step of s
  // moves it by s, twice its excursion s / 2; a heel's neighbour on a rising load, by 2 ticks of
  // its rise). Load went from one to the other and back (a heavy biped's heel chatters off the
  // ground for a tick every 7 ms, its neighbour's excursion 30-35 N, for longer than a landing's
  // guard), though an impact may shed some of it from the foot's sum. Sensors' spikes are
  // independent: two opposite on one tick are not. (Every pad's previous readings are still
  // those before this tick: they move on after the channels' pass.)
  const std::size_t first = channel_foot_[j] * feet_points_;
  for (std::size_t i = first; i < first + feet_points_; ++i) {
    const Channel& n = channels_[i];
    if (i == j || (n.type != FaultType::none && !corrects(n.type))) continue;
    const double scale = n.type == FaultType::gain ? 1.0 / n.gain : 1.0;
    const double excursion = scale * (n.previous - 0.5 * (measured[i] + n.previous2));
    const double moved = scale * (measured[i] - n.previous2);
    if (excursion * spike < 0.0 && std::abs(excursion) > rocking_bar_N_ && std::abs(moved) < std::abs(excursion)) {
      return true;
    }
  }
  return false;
}

bool ContactForceFdi::unread(std::size_t j, std::span<const double> height) const noexcept {
  const FaultType type = channels_[j].type;
  if (type == FaultType::noise) return true;
  return type != FaultType::none && !own_estimate(type) && !(height[j] > params_.airborne_height_m);
}

double ContactForceFdi::fault_size(const Channel& c, double t, double load_before) noexcept {
  // A gain fault's size on a reading x = k N: (k - 1) N = (1 - 1/k) x.
  return c.type == FaultType::gain ? (1.0 - 1.0 / c.gain) * load_before : fault_at(c, t);
}

bool ContactForceFdi::steps_back(double jump, double size) const noexcept {
  return std::abs(jump + size) < 0.4 * std::abs(size) + params_.jump_confirm_N;
}

bool ContactForceFdi::residual_steps_by(double step, double expected, double confirm_N) const noexcept {
  // About the expected step: not much less, not much more, and beyond the confirmation step.
  return step * expected > 0.0 && std::abs(step) >= confirm_N &&
         std::abs(step - expected) <= std::max(params_.jump_confirm_N, 0.5 * std::abs(expected));
}

double ContactForceFdi::recent_residual_mean(std::size_t skip) const noexcept {
  const std::size_t w = static_cast<std::size_t>(jump_window_ticks_);
  double sum = 0.0;
  for (std::size_t i = skip; i < w + skip; ++i) sum += residual_ring_[ring_back(residual_next_, residual_ring_.size(), i)];
  return sum / static_cast<double>(w);
}

bool ContactForceFdi::SlopeFit::negative_slope(double& k) const noexcept {
  if (n < 3.0) return false;
  const double mv = sv / n, mx = sx / n;
  const double cvv = svv / n - mv * mv, cxv = sxv / n - mx * mv, cxx = sxx / n - mx * mx;
  if (!(cvv > 0.0)) return false;
  const double slope = cxv / cvv;
  const double standard_error = std::sqrt(std::max(0.0, cxx - slope * cxv) / (n * cvv));
  if (!(slope + 4.0 * standard_error < 0.0)) return false;  // negative beyond 4 standard errors
  // And the gain model x = k v explains the readings better than an offset x = v + b (a negative
  // offset read only while its load is light looks like a falling line).
  const double gain_k = sxv / svv;
  const double gain_residual = sxx - gain_k * sxv;
  const double offset_residual = (sxx - 2.0 * sxv + svv) - (sx - sv) * (sx - sv) / n;
  if (!(gain_k < 0.0 && gain_residual < offset_residual)) return false;
  k = std::min(gain_k, -kMinGain);  // the recovery divides by it
  return true;
}

void ContactForceFdi::step(const StepIO& io) noexcept {
  const double t = io.time_s;
  const auto measured = io.in(kMeasured);
  const double fz = io.in(kTotalForce)[2];
  const bool fz_ok = std::isfinite(fz);
  if (!started_) start_time_s_ = t;
  last_tick_s_ = t;
  const int ticks_since_start = started_ ? 2 : 0;

  // Pad heights from kinematics (unknown, NaN, is taken as on the ground: every test below
  // compares a height with "greater than").
  const auto height = io.in(kPointHeight);

  // Evidence, channel by channel.
  const double tick_noise = tick_noise_N_;
  double last_touchdown_s = -1e9;  // of any foot
  for (std::size_t f = 0; f < feet_; ++f) {
    bool any = false;
    for (std::size_t l = 0; l < feet_points_; ++l) any = any || height[f * feet_points_ + l] > params_.touchdown_height_m;
    if (foot_airborne_[f] && !any) last_touchdown_s_[f] = t;
    foot_airborne_[f] = any ? 1 : 0;
    last_touchdown_s = std::max(last_touchdown_s, last_touchdown_s_[f]);
  }
  const bool touching_down = t - last_touchdown_s < params_.touchdown_guard_s;
  // The sum residual before a touchdown's guard began (a later touchdown inside it keeps it):
  // what a fault's end seen inside the guard is judged against.
  if (touching_down && !was_touching_down_) {
    residual_before_known_ = residual_count_ >= static_cast<std::size_t>(jump_window_ticks_);
    residual_before_touchdown_ = recent_residual_mean();
    guard_began_s_ = t;
    // A jump still pending from the guard before would be judged across two landings, against a
    // bar learnt on one: dropped.
    for (auto& c : channels_) c.onset_after_guard = false;
  }
  was_touching_down_ = touching_down;
  // The second difference of each foot's summed reading: load moving between the pads of a foot
  // (a rocking or chattering foot) leaves it small, a pad's own noise does not. Unknown (taken as
  // large) while a pad has no value.
  for (std::size_t f = 0; f < feet_; ++f) {
    double sum = 0.0;
    bool known = true;
    for (std::size_t l = 0; l < feet_points_; ++l) {
      const double x = measured[f * feet_points_ + l];
      known = known && std::isfinite(x);
      sum += x;
    }
    foot_d2_[f] = known && foot_sum_ticks_[f] >= 2 ? sum - 2.0 * foot_sum_[f][0] + foot_sum_[f][1]
                                                   : std::numeric_limits<double>::infinity();
    foot_sum_[f][1] = foot_sum_[f][0];
    foot_sum_[f][0] = sum;
    foot_sum_ticks_[f] = known ? std::min(foot_sum_ticks_[f] + 1, 2) : 0;
    // Its pads whose readings are not their loads (as flagged until this tick): substituted
    // from the total force under load, or reading a noise burst. The summed reading then does not
    // cancel load moving between them and the others.
    foot_unread_[f] = 0;
    for (std::size_t l = 0; l < feet_points_; ++l) foot_unread_[f] += unread(f * feet_points_ + l, height) ? 1 : 0;
    foot_landing_pads_[f] = 0;
    for (std::size_t l = 0; l < feet_points_; ++l) {
      const std::size_t j = f * feet_points_ + l;
      const Channel& c = channels_[j];
      const bool known = ticks_since_start > 0;  // a previous reading to step from
      const bool lands = known && pad_lands(c, measured[j], height[j]);
      const bool step = lands || (known && ring_step(c, measured[j], height[j], t));
      landing_state_[j] = static_cast<char>(lands ? kLands : step ? kRingStep : kNoLandingStep);
      foot_landing_pads_[f] += step ? 1 : 0;
    }
  }
  const double foot_noise = foot_noise_N_;
  int jump_candidates = 0;
  bool group_emptied = false;  // every member of the pending group was a one-tick spike
  bool any_step = false;  // a channel stepped this tick (the still-reading test's window restarts)
  double jump_sum = 0.0;
  int late_candidates = 0;  // healthy channels stepping while a group is pending
  double late_jump_sum = 0.0;
  double raw_sum = 0.0;
  double median_lag_correction = 0.0;  // for the last tick's residual (below)
  bool all_finite_readings = true;  // the gain test takes only ticks where every channel has a value
  // A gain fault's reading enters the jump test's residual as x / k (below): a gain set, refitted or
  // dropped on a loaded pad steps that residual by x (1 / k_new - 1 / k_old) on the next tick,
  // which a group of jumps whose windows straddle it would take for its own step (a x0.5 gain that
  // ended in the air, dropped as its heel took 200 N: three healthy neighbours confirmed as
  // offsets 2 ms later). Counted from jump_confirm_N, the step the confirmation tells from none:
  // a sign flip's k, refined on every tick it is loaded, moves it by less (counted, it kept every
  // group from forming and the flip's end was judged 10 ms late). In the air, or without a
  // value, its reading is not in the residual as x / k.
  bool divisor_changed = false;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    const bool airborne = height[j] > params_.airborne_height_m;
    const double divisor = c.type == FaultType::gain ? c.gain : 1.0;
    if (divisor != c.residual_divisor && !airborne && std::isfinite(x) &&
        std::abs(x / divisor - x / c.residual_divisor) >= params_.jump_confirm_N) {
      divisor_changed = true;
    }
    c.residual_divisor = divisor;
    if (!std::isfinite(x)) {
      all_finite_readings = false;
      raise(c, FaultType::invalid, t);
      c.stale_count = 0;
      c.restart_air_readings();
      c.jump_pending = c.late_candidate = c.relation_pending = false;  // no candidate without a value
      c.median_gap = 0.0;
      raw_sum += c.recovered;
      continue;
    }
    // The sum residual of the jump test takes a gain fault's reading with its correction (a sign
    // flip's load changes, read twice over, must not make its neighbours' changes look like
    // steps), and a spiking channel's as the median of its last three readings (a 250 N spike
    // moves a 10 ms window's mean by 50 N at 500 Hz). Offsets stay as read: their correction
    // ends with the jump that ends them.
    // A median of three lags a step by a tick (at 200 Hz, 70 N as a spiking heel lands), which a
    // neighbour's step in the same window took for its confirmation: once the next reading shows
    // the step stayed (no spike returns within half its rise), the last tick's residual takes
    // the reading instead.
    if (c.type == FaultType::spikes && std::abs(c.median_gap) > params_.jump_threshold_N &&
        std::abs(x - c.previous) < 0.5 * std::abs(c.previous - c.previous2)) {
      median_lag_correction += c.median_gap;
    }
    c.median_gap = 0.0;
    if (c.type == FaultType::gain) {
      raw_sum += airborne ? 0.0 : x / c.gain;
    } else if (c.type == FaultType::spikes && ticks_since_start > 0) {
      const double median = generic::median_of_three(x, c.previous, c.previous2);
      raw_sum += median;
      c.median_gap = fz_ok ? x - median : 0.0;
    } else {
      raw_sum += x;
    }
    if (c.type == FaultType::invalid) clear(c);  // a finite value re-admits at once
    if (ticks_since_start > 0) {
      const double change = x - c.previous;
      // A drift's reading stepping back by about its size s on this tick (nearer -s than no
      // step), s beyond the noise of a tick's change, and its foot's summed reading stepping
      // alike (load moving between the foot's pads leaves that sum alone): a cue for the
      // stance comparison (gain_regression), not a decision.
      if (c.type == FaultType::drift) {
        const double size = fault_at(c, t);
        const std::size_t f = channel_foot_[j];
        const double foot_change = foot_sum_ticks_[f] >= 2 ? foot_sum_[f][0] - foot_sum_[f][1]
                                                           : std::numeric_limits<double>::quiet_NaN();
        if (std::abs(size) > step_back_bar_N_ && std::abs(change + size) < 0.5 * std::abs(size) &&
            std::abs(foot_change + size) < 0.5 * std::abs(size)) {
          c.stepped_back_s = t;
        }
      }
      // A pad on its zero level that may carry no more than a driver's zero clamp (in the air, or
      // on the ground with a load within the clamp and the total force's error) may repeat
      // itself: no evidence either way, so the run neither grows nor restarts. Any other value
      // repeated in the air is evidence (a noisy sensor does not repeat 1.3 N).
      const bool unloaded = airborne || (std::isfinite(c.last_virtual) && c.last_virtual < zero_evidence_above_N_);
      const bool unloaded_zero = unloaded && std::abs(x) <= repeat_band_N_;
      if (std::abs(change) > repeat_band_N_) {
        c.stale_count = 0;
      } else if (!unloaded_zero) {
        c.stale_count = std::min(c.stale_count + 1, kCountCap);
      }
      // A pad's own landing: a pad on the ground left no load by the others, reading its zero
      // level, takes its load back as the foot rolls onto it. That contact is as abrupt as a
      // foot's touchdown and rings alike (at 200 Hz: tens of newtons in one tick, chatter on and
      // off), so the jump and spike tests leave the pad alone while it rings: until its changes
      // have stayed below jump_threshold_N for jump_window_s, or while it steps to or from its
      // air level (its contact lost and made again: a heavy robot's heel bounces 8-10 ms apart), at
      // most touchdown_guard_s after the landing (a ring that has died out is over; a step after
      // it is judged like any other).
      // A fault that starts while it rings is left to the sum residual and the air test.
      const bool lands = landing_state_[j] == kLands;
      if (lands) {
        c.last_pad_landing_s = t;
        c.last_landing_ring_s = t;
      }
      // Rung until the tick before: this tick's change is what the tests below judge.
      const bool in_landing_guard = t - c.last_pad_landing_s < params_.touchdown_guard_s;
      const bool pad_landing =
          in_landing_guard && (t - c.last_landing_ring_s < params_.jump_window_s ||
                               (std::abs(change) > params_.jump_threshold_N && contact_step(c, x)));
      if (pad_landing && std::abs(change) > params_.jump_threshold_N) c.last_landing_ring_s = t;
      // A neighbour of this pad whose reading is not its load (substituted under load, or a
      // noise burst): the foot's sum then misses the load that moves between it and this pad (a
      // heel chattering on and off), so this pad's roughness is no verdict of noise, nor its
      // one-tick excursion one of a spike: not judged then.
      // (A channel flagged already keeps being judged, so that it can be cleared.)
      const bool neighbour_unread = foot_unread_[channel_foot_[j]] > (unread(j, height) ? 1 : 0);
      const double spike = c.previous - 0.5 * (x + c.previous2);
      const bool spikes_seen = !touching_down && !pad_landing;
      if (spikes_seen) c.spikes.see(period_s_);
      // A sensor's spike is in its foot's summed reading too (the sum's own spike, -d2 / 2, at
      // least half the pad's, same sign); load that rocks between the pads of a foot for a tick
      // (a pad chattering on and off the ground) is not. Unknown (a pad without a value): counted.
      const std::size_t foot = channel_foot_[j];
      const double foot_spike = -0.5 * foot_d2_[foot];
      const bool in_foot_sum = !std::isfinite(foot_spike) || foot_spike * spike >= 0.5 * spike * spike;
      // Nor is load that rocked (load_rocked: asked last, as it scans the foot).
      if (spikes_seen && std::abs(spike) > params_.spike_threshold_N &&
          std::abs(x - c.previous2) < 0.5 * params_.spike_threshold_N && in_foot_sum &&
          (!neighbour_unread || c.type == FaultType::spikes) && !load_rocked(j, spike, measured)) {
        c.spikes.spike(spike_rule_);
      }
      const double innovation = x - 2.0 * c.previous + c.previous2;
      // A pad making its contact (inside its landing's guard) whose reading leaves or regains its
      // air level within these three readings, none below it: its contact chatters (a 180 kg
      // biped's outer heel lets go for a tick every 6 ms for 0.14 s as its foot rolls onto it), the
      // sensor is not noisy. A contact does not pull, a noise burst does (on an unloaded pad half
      // its readings lie below the air level), and under load a burst's readings seldom fall to
      // it: a burst still shows (and one already flagged keeps being judged on every tick, as
      // beside an unread neighbour).
      const bool contact_chatter =
          in_landing_guard && std::abs(std::min({x, c.previous, c.previous2})) <= params_.airborne_threshold_N;
      c.noisy_count -= c.noisy_tick[c.second_diff_next];
      c.second_diff[c.second_diff_next] = std::abs(innovation);
      c.noisy_tick[c.second_diff_next] = std::abs(innovation) > tick_noise &&
                                                 std::abs(foot_d2_[channel_foot_[j]]) > foot_noise &&
                                                 (!(neighbour_unread || contact_chatter) || c.type == FaultType::noise)
                                             ? 1
                                             : 0;
      c.noisy_count += c.noisy_tick[c.second_diff_next];
      c.first_diff[c.second_diff_next] = std::abs(change);
      c.second_diff_next = ring_after(c.second_diff_next, c.second_diff.size());
      c.jump_pending = false;
      c.late_candidate = false;
      c.relation_pending = false;
      // A member of the pending group whose reading is back within half its jump of the reading
      // before it, on the tick after, jumped for one tick: a spike, not a step. At 200 Hz the
      // jump window is two ticks, and a 100 N spike moves its mean by 50 N. (Judged against the
      // reading before, not its trend: a noise burst's trend is its last swing, and extrapolated
      // it took a burst's swings for steps. So a step against a pad unloading as fast as half
      // the step per tick, at a slow log rate, leaves the group too: found by the other tests.)
      const auto back = [&](double jump) { return std::abs(x - c.previous2) < 0.5 * std::abs(jump); };
      bool spiked_back = false;  // its return is no step of its own (no late candidate)
      if (c.jump_member && group_pending_ && group_age_ == 1 && back(c.jump_size)) {
        spiked_back = true;
        c.jump_member = false;
        group_sum_ -= in_residual(c.type, c.gain, c.jump_size);
        --group_size_;
        group_emptied = group_emptied || group_size_ == 0;
      }
      if (c.late_member && late_pending_ && late_age_ == 1 && back(c.late_jump)) {
        c.late_member = false;
        late_sum_ -= in_residual(c.type, c.gain, c.late_jump);
        --late_size_;
      }
      // Likewise a member of its foot's plane group (inside a touchdown guard).
      if (c.relation_member && relation_group_[foot] == 1 && relation_group_age_[foot] == 1 &&
          back(c.relation_jump_size)) {
        c.relation_member = false;
        const std::size_t relations = unmeasured_.relations_per_foot();
        const double jump = in_residual(c.type, c.gain, c.relation_jump_size);
        for (std::size_t r = 0; r < relations; ++r) {
          relation_expect_[foot * relations + r] -= unmeasured_.relation_weight(j - foot * feet_points_, r) * jump;
        }
        bool members = false;
        for (std::size_t i = 0; i < feet_points_; ++i) members = members || channels_[foot * feet_points_ + i].relation_member;
        if (!members) relation_group_[foot] = 0;
      }
      // Any time but a landing: a rolling foot's pads change a few newtons per tick, far below
      // jump_threshold_N, and the sum-residual confirmation rejects what is not a sensor step.
      // Nor on a tick another pad of its foot lands or, ringing, jumps on or off: a heel landing
      // late jolts its neighbours by tens of newtons on that tick, which F_z misses as it does a
      // foot's impact (a 20 N jolt of a toe pad was confirmed an offset), and a pad chattering
      // on and off trades its load with them on each of its jumps. Only those ticks: kept shut
      // while the heel rang (10 ms and more), the test missed a gain that began 9 ms after such
      // a landing.
      const bool neighbour_landing = foot_landing_pads_[foot] > (landing_state_[j] != kNoLandingStep ? 1 : 0);
      const bool may_jump = !touching_down && !pad_landing && !neighbour_landing;
      // A noise burst's swings are the fault the channel is flagged for, not steps.
      const bool steps = std::abs(change) > params_.jump_threshold_N &&
                         std::abs(innovation) > params_.jump_threshold_N && c.type != FaultType::noise;
      // The still test's windows restart on a step: it may be a fault's onset or end the jump test
      // did not judge. But a landing foot's unflagged pads step as they take their loads (none of
      // them is named while its foot lands): no restart, so a window holds the load that landing
      // moves off the other foot's pads, which a stuck one among them does not follow. (Inside
      // its foot's guard the jump test judges no step: touching_down holds.)
      any_step = any_step || (steps && (c.type != FaultType::none || !foot_landing(foot, t)));
      if (steps && may_jump && !group_pending_ && !late_pending_) {
        c.jump_pending = true;
        c.jump_gain_led = gain_leads(c);  // this tick's powers are not yet added
        c.jump_virtual_before = c.last_virtual;
        c.jump_size = change;
        c.candidate_load = c.previous;
        c.candidate_flagged = c.type != FaultType::none;
        ++jump_candidates;
        // In the terms of the sum residual, which takes a gain fault's reading corrected.
        jump_sum += in_residual(c.type, c.gain, change);
      } else if (steps && may_jump && !late_pending_ && !spiked_back && fz_ok &&
                 residual_count_ == residual_ring_.size() &&
                 (c.type == FaultType::none ||
                  (c.jump_member && !c.end_pending && corrects(c.type) &&
                   steps_back(change, fault_size(c, t, c.previous))))) {
        // A healthy channel's step while a group awaits its confirmation (the other foot's pads
        // unloading at its lift-off, a fault starting within the jump window; a member of that
        // group too, as the load it moved keeps moving), or a member's step back by its fault's
        // size (the fault's end, which the end test below leaves to the group it is in): a late
        // group, decided with the pending one (below), not lost.
        c.late_candidate = true;
        c.late_jump = change;
        c.late_load_before = c.previous;
        c.late_from_flagged = c.type != FaultType::none;
        ++late_candidates;
        late_jump_sum += in_residual(c.type, c.gain, change);  // as the sum residual takes it
      } else if (steps && may_jump && !late_pending_ && !c.jump_member && !c.end_pending && corrects(c.type) &&
                 fz_ok && residual_count_ == residual_ring_.size()) {
        // A step while another group awaits its confirmation (a landing foot's pads jumping as
        // it rolls on): judged on its own window, as a group of its own would be, when it steps
        // back by the fault's size (the fault may have ended; an onset on a healthy channel waits
        // for the next free group, as before).
        if (steps_back(change, fault_size(c, t, c.previous))) {
          c.end_pending = true;
          c.end_after_guard = false;
          c.end_jump = in_residual(c.type, c.gain, change);  // as the sum residual takes it
          // Before the pending group's jump, which the group's own confirmation then accounts for
          // (its step is added to what this end implies once the group is decided).
          c.end_before = group_before_;
          c.end_group = group_serial_;
          c.end_since_s = t;
          c.end_clear_ticks = 0;
        }
      } else if (steps && touching_down && !pad_landing && unmeasured_.relations_per_foot() > 0 &&
                 relation_group_[channel_foot_[j]] != 1) {  // 2: decided last tick, free again
        // Inside a touchdown guard the sum residual carries the impact; the foot's plane does not.
        c.relation_pending = true;
        c.relation_jump = change;
        c.relation_candidate_load = c.previous;
        c.candidate_flagged = c.type != FaultType::none;
      } else if (steps && touching_down && !pad_landing && !c.end_pending && corrects(c.type) &&
                 (c.type == FaultType::gain || c.fit_has_air) && !gain_reads_air_level(c, x) &&
                 t - last_touchdown_s_[channel_foot_[j]] >= params_.touchdown_guard_s && fz_ok &&
                 residual_before_known_) {
        // A step back by the fault's size on a foot that is not landing, while another foot is:
        // the fault may have ended. Only a fault whose model is settled (measured in the air, or
        // a gain): an offset raised by a jump may yet be a gain, whose error shrinks as its foot
        // hands load over at the landing, as an end would. The sum residual carries the other
        // foot's impact now, so it judges the step once the guard is over (the loads have
        // settled by then), against what it was before the guard (at 200 Hz a load shifting at
        // a landing moves a pad by tens of newtons in a tick: the residual, not the step, tells
        // a sensor's end).
        const double estimate = fault_size(c, t, c.previous);
        if (steps_back(change, estimate)) {
          c.end_pending = true;
          c.end_after_guard = true;
          // Ended, the fault leaves the residual by its size (a gain's reading is taken as x / k:
          // the load L = x_before / k then reads L / k): not by the step, which at a landing also
          // carries the load the foot hands over.
          c.end_jump = c.type == FaultType::gain ? -(1.0 - 1.0 / c.gain) * c.previous / c.gain : -estimate;
          c.end_before = residual_before_touchdown_;
          c.end_since_s = t;
          c.end_clear_ticks = 0;
        }
      }
    }
    if (airborne) {
      // A step in flight (a fault starting or ending in the air): the mean starts again there, and
      // so does the air's fit of the fault, at its next reading in the air, this swing or the
      // next (one line through the readings before and after a step would average the two
      // levels: a fault that ended mid-swing was kept at half its size).
      if (c.airborne_ticks > 0 && ticks_since_start > 0 && std::abs(x - c.previous) > params_.jump_threshold_N) {
        close_air_window(c);
        c.restart_air_readings();
        c.air_refit = c.fit_has_air;
      }
      ++c.airborne_ticks;
      if (c.airborne_ticks * period_s_ >= params_.airborne_settle_s) {
        if (c.airborne_count == 0) c.air_origin_s = t;
        const double u = t - c.air_origin_s;
        c.airborne_sum += x;
        c.airborne_u_sum += u;
        c.airborne_uu_sum += u * u;
        c.airborne_ux_sum += u * x;
        c.air_window_flagged = c.air_window_flagged || c.type != FaultType::none;
        ++c.airborne_count;
        // The latest block of min_airborne_samples readings: does it read zero? (A fault that
        // ends mid-swing, by a step too small to restart the mean, leaves the swing's mean
        // beyond airborne_clear_N to the landing; its last block does not.)
        c.air_block_sum += x;
        if (++c.air_block_count >= min_airborne_samples_) {
          c.air_block_reads_zero = std::abs(c.air_block_sum / c.air_block_count) < params_.airborne_clear_N;
          c.air_block_sum = 0.0;
          c.air_block_count = 0;
        }
      }
    } else {
      close_air_window(c);
      c.restart_air_readings();  // (air_refit stays until the air's fit next takes a reading)
    }
    c.max_seen = std::max(c.max_seen, x);
    if (x > c.ceiling_N + repeat_band_N_) c.ceiling_N = std::numeric_limits<double>::quiet_NaN();  // not clipped there
    // A pad only pushes: a loaded pad reading below -airborne_threshold_N is a negative offset
    // or a negative multiple of its load (a sign flip). The least-squares line of the reading on
    // the leave-one-out force (fitted once that force is known, below) tells them apart: slope
    // about 1, or k < 0; a pad read right side up again under load clears it.
    const bool shows_load = !airborne && std::isfinite(c.last_virtual) && c.last_virtual > params_.gain_min_load_N;
    if (!airborne && x < -params_.airborne_threshold_N) {
      c.negative_ticks = std::min(c.negative_ticks + 1, kCountCap);
      c.positive_ticks = 0;
    } else {
      c.negative_ticks = 0;
      c.positive_ticks = shows_load && x > params_.airborne_threshold_N ? std::min(c.positive_ticks + 1, kCountCap) : 0;
      if (!c.sign_fault) c.negative_fit = SlopeFit{};
    }
  }

  ticks_since_divisor_change_ = divisor_changed ? 0 : std::min(ticks_since_divisor_change_ + 1, kCountCap);
  relation_jumps(measured, height, t);
  // Sum residual history for the jump confirmation.
  const double raw_residual = fz_ok ? raw_sum - fz : 0.0;
  if (median_lag_correction != 0.0 && residual_count_ > 0) {
    residual_ring_[ring_back(residual_next_, residual_ring_.size(), 0)] += median_lag_correction;
  }
  residual_ring_[residual_next_] = raw_residual;
  residual_next_ = ring_after(residual_next_, residual_ring_.size());
  residual_count_ = std::min(residual_count_ + 1, residual_ring_.size());
  // The sum held before the jump: a corrected residual (last tick's, low-passed) already beyond
  // the total force's error bound holds a fault no test has named yet (a dead pad under a
  // landing heel), and loads moving in or out of it step the residual like a sensor would: its
  // steps are no evidence, and the other tests name that fault first.
  const bool sum_held = !residual_smoothed_started_ || std::abs(residual_smoothed_) <= params_.sum_threshold_N;
  // Nor while the jump window before this tick holds a change of a gain's correction.
  const bool divisor_settled = ticks_since_divisor_change_ >= jump_window_ticks_;
  if (jump_candidates > 0 && fz_ok && sum_held && divisor_settled && !unread_landing_may_explain(height, jump_sum)) {
    group_pending_ = true;
    ++group_serial_;
    group_before_ = recent_residual_mean(1);  // the window before this tick's jump
    group_age_ = 0;
    group_sum_ = jump_sum;
    group_size_ = jump_candidates;
    for (auto& c : channels_) {
      c.jump_member = c.jump_pending;
      if (c.jump_member) {
        c.jump_load_before = c.candidate_load;
        c.jump_from_flagged = c.candidate_flagged;
      }
    }
  }
  // A late group forms only while no fault's end is pending: an end's residual step is judged
  // against the first group's decision alone.
  const auto ends_waiting = [&] {
    return std::any_of(channels_.begin(), channels_.end(), [](const Channel& c) { return c.end_pending; });
  };
  if (late_candidates > 0 && group_pending_ && !ends_waiting()) {
    late_pending_ = true;
    late_age_ = 0;
    late_sum_ = late_jump_sum;
    late_size_ = late_candidates;
    for (auto& c : channels_) c.late_member = c.late_candidate;
  }
  // While a loaded channel is substituted from the total force, the sum residual carries that
  // channel's unmeasured changes, and while one reads a noise burst, its swings (a 10 ms mean of
  // 40 N noise moves by 13 N; spikes come too seldom to matter): confirming a jump then takes
  // three times the step, and while one is substituted at least sum_threshold_N, the bound of the
  // total force's error that its share carries (a substituted heel pad chattering on and off
  // the ground hands 40-55 N to its neighbours and back within a tick, which at 1 N of noise
  // would confirm their moves as a group of offsets).
  // When such a channel's foot is rolling on or off (some pads up), its load changes fast and
  // unmeasured, and no jump is confirmed at all.
  bool unmeasured_in_residual = false;  // a loaded channel substituted, or reading a noise burst
  bool substituted_loaded = false;
  bool substituting_rolling = false;
  bool uncorrected_loaded = false;  // a loaded channel flagged as anything but a corrected fault
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    const bool airborne = height[j] > params_.airborne_height_m;
    const bool substituted = channels_[j].type != FaultType::none && !own_estimate(channels_[j].type) && !airborne;
    const FaultType type = channels_[j].type;
    uncorrected_loaded = uncorrected_loaded || (type != FaultType::none && !corrects(type) && !airborne);
    const bool noisy_loaded = type == FaultType::noise && !airborne;
    unmeasured_in_residual = unmeasured_in_residual || substituted || noisy_loaded;
    substituted_loaded = substituted_loaded || substituted;
    substituting_rolling = substituting_rolling || (substituted && foot_airborne_[channel_foot_[j]] != 0);
  }
  bool group_dropped = false;
  if (group_emptied && group_pending_) {
    group_pending_ = false;
    group_dropped = true;
  }
  if (substituting_rolling && group_pending_) {
    group_pending_ = false;
    group_dropped = true;
  }
  // A gain's correction changed within a pending group's window: its step is in the residual's.
  if (divisor_changed && group_pending_) {
    group_pending_ = false;
    group_dropped = true;
  }
  if ((substituting_rolling || divisor_changed) && (late_pending_ || group_deferred_)) {
    group_dropped = group_dropped || group_deferred_;
    late_pending_ = group_deferred_ = false;
    for (auto& c : channels_) c.late_member = false;
  }
  // Every late member spiked for a tick, and the first group is still in its window: it is
  // decided alone, as before.
  if (late_pending_ && late_size_ == 0 && !group_deferred_) late_pending_ = false;
  const double confirm_N = substituted_loaded    ? std::max(3.0 * params_.jump_confirm_N, params_.sum_threshold_N)
                           : unmeasured_in_residual ? 3.0 * params_.jump_confirm_N
                                                    : params_.jump_confirm_N;
  // Confirm (or drop) the pending group once the window after the jump is complete.
  bool group_confirmed = false;
  bool group_decided = false;
  if (group_pending_ && group_age_++ >= jump_window_ticks_ - 1) {
    group_pending_ = false;
    if (late_pending_) {
      // A late group's jump is in this window: decided with it, once its window is over.
      group_deferred_ = true;
    } else if (residual_count_ == residual_ring_.size()) {
      group_decided = true;
      const double step =
          recent_residual_mean() - recent_residual_mean(static_cast<std::size_t>(jump_window_ticks_));
      // Pads trading load jump in opposite directions and leave the residual alone: not a fault.
      group_confirmed = std::abs(group_sum_) >= confirm_N && residual_steps_by(step, group_sum_, confirm_N);
    } else {
      group_decided = true;
      group_dropped = true;
    }
  }
  // The late group, a jump window after its jump, with the first if that one is still undecided:
  // the residual's step from before the first group's jump is the first's sum, the late one's, or
  // both (a dropped first group: the late one's only); the hypothesis that passes the step test
  // and lies nearest is taken. (The first group's own window holds the late jump, so it cannot
  // be judged alone.)
  bool late_decided = false;
  bool late_confirmed = false;
  if (late_pending_ && late_age_++ >= jump_window_ticks_ - 1) {
    late_pending_ = false;
    late_decided = true;
    const bool first_open = group_deferred_;
    group_deferred_ = false;
    if (first_open) group_decided = true;
    if (residual_count_ == residual_ring_.size()) {
      const double step = recent_residual_mean() - group_before_;
      const double first = first_open ? group_sum_ : 0.0;
      double best = std::numeric_limits<double>::infinity();
      // Each group's own sum must reach the confirmation step, as it must alone (two moves under it
      // are no step of a sensor, even where the residual drifts by their sum).
      const auto consider = [&](double expected, bool with_first, bool with_late) {
        if ((with_first && std::abs(first) < confirm_N) || (with_late && std::abs(late_sum_) < confirm_N)) return;
        if (!residual_steps_by(step, expected, confirm_N) || std::abs(step - expected) >= best) return;
        best = std::abs(step - expected);
        group_confirmed = with_first;
        late_confirmed = with_late;
      };
      if (late_size_ > 0) consider(late_sum_, false, true);
      if (first_open) consider(first, true, false);
      if (first_open && late_size_ > 0) consider(first + late_sum_, true, true);
    } else if (first_open) {
      group_dropped = true;
    }
  }
  // Ends seen while this group was pending: its step, if it was one, is in theirs too.
  if (group_decided || group_dropped) {
    for (auto& c : channels_) {
      if (!c.end_pending || c.end_after_guard || c.end_group != group_serial_) continue;
      if (group_dropped) {
        c.end_pending = false;
      } else if (group_confirmed) {
        c.end_jump += group_sum_;
      }
    }
  }

  // A fault's end seen inside another foot's touchdown guard: once the guard is over and the
  // residual has had a jump window to settle, it must have stepped by what the end implies, as a
  // jump's group must (a healthy pad's move as the load shifts leaves the residual alone). One
  // seen while another group was pending: after its own jump window, by its step.
  // Two ends judged on one residual could each be matched by the step of one of them (a fault
  // that ended and a flagged pad that handed its load over): with more than one pending, none is
  // re-admitted this way.
  int ends_pending = 0;
  for (const auto& c : channels_) ends_pending += c.end_pending ? 1 : 0;
  for (auto& c : channels_) {
    if (!c.end_pending) continue;
    if (!corrects(c.type) ||
        t - c.end_since_s > guard_pending_limit_s_) {
      c.end_pending = false;  // re-typed, or the guards kept coming: left to the other tests
      continue;
    }
    if (c.end_after_guard && touching_down) {
      c.end_clear_ticks = 0;  // a further landing: its impact must pass too
      continue;
    }
    if (!fz_ok) continue;
    if (++c.end_clear_ticks < jump_window_ticks_) continue;
    c.end_pending = false;
    if (ends_pending > 1) continue;
    // A gain's error in the residual scales with its load: one whose pad has since gone to its air
    // level left the residual with its load, ended or not (the next stance judges it).
    if (gain_reads_air_level(c, measured[static_cast<std::size_t>(&c - channels_.data())])) continue;
    if (residual_steps_by(recent_residual_mean() - c.end_before, c.end_jump, confirm_N)) clear(c);
  }

  // Onset jumps inside a touchdown guard that their foot's plane could not judge: once the guard
  // is over and the residual has had a jump window to settle, it must have stepped from its mean
  // before the guard by one of them, as an end seen there must, and by more than a landing moves
  // it on a healthy walk (z times the RMS of that step over the walk's healthy guards so far:
  // the total force's error before and after a landing differs by tens of newtons, where within
  // a jump window it barely moves). A pad's step in the guard is often load shifting with its
  // foot's other pads on the same tick: such a group is judged by its net step, and a group of
  // two or more cannot name its pad. One match alone is raised; two (or an end pending beside)
  // cannot be told apart, and none is.
  bool onsets_pending = false;
  for (const auto& c : channels_) onsets_pending = onsets_pending || c.onset_after_guard;
  if (onsets_pending) {
    // Dropped unjudged when the guards kept coming, or when a channel was raised or re-admitted
    // since the guard began: that moved the residual (offsets are in it as read), so its step no
    // longer measures these jumps alone.
    bool expired = false;
    for (const auto& c : channels_) {
      expired = expired || (c.onset_after_guard && (t - c.guard_onset_since_s > guard_pending_limit_s_ ||
                                                    last_flag_change_s_ >= c.guard_onset_guard_began_s));
    }
    if (touching_down) guard_onsets_clear_ticks_ = 0;
    if (!touching_down && fz_ok && !expired) ++guard_onsets_clear_ticks_;
    if (expired || guard_onsets_clear_ticks_ >= jump_window_ticks_) {
      int matches = 0;
      std::size_t match = channels_.size();
      for (std::size_t j = 0; j < channels_.size() && !expired; ++j) {
        const Channel& c = channels_[j];
        if (!c.onset_after_guard) continue;
        const std::size_t foot = channel_foot_[j];
        double net = 0.0;
        bool first_of_group = true;
        for (std::size_t i = 0; i < feet_points_; ++i) {
          const std::size_t k = foot * feet_points_ + i;
          const Channel& o = channels_[k];
          if (!o.onset_after_guard || o.guard_onset_since_s != c.guard_onset_since_s) continue;
          first_of_group = first_of_group && k >= j;
          net += o.guard_onset_jump;
        }
        if (!first_of_group) continue;  // its group is judged once
        if (guard_step_count_ < kMinGuardSteps) continue;  // a landing's own step not known yet
        const double bar = landing_step_bar(confirm_N);
        if (std::abs(net) >= bar && residual_steps_by(recent_residual_mean() - c.guard_onset_before, net, bar)) {
          ++matches;
          // Nameable only when its whole plane group of that tick is the pad alone (the
          // qualifying members are among that group's).
          match = c.guard_onset_plane_group == 1 ? j : channels_.size();
        }
      }
      // The bar was learnt on guards with no channel flagged; a substituted, gain-corrected or
      // noisy channel moves the residual by what it does not read, an offset not at all and a
      // drift by its slope over the guard (a few newtons). Re-typed channels (an offset taken
      // for a gain or a frozen output) fall here too: raise() records only new flags.
      bool comparable = true;
      for (const auto& c : channels_) {
        comparable = comparable && (c.type == FaultType::none || c.type == FaultType::offset || c.type == FaultType::drift);
      }
      if (matches == 1 && match < channels_.size() && ends_pending == 0 && comparable) {
        Channel& c = channels_[match];
        if (c.type == FaultType::none && !(height[match] > params_.airborne_height_m)) {
          raise_jump_onset(c, c.guard_onset_jump, c.guard_onset_load, t);
        }
      }
      for (auto& c : channels_) c.onset_after_guard = false;
      guard_onsets_clear_ticks_ = 0;
    }
  }
  // The residual's step across each guard, a jump window after it, counted when no channel is
  // flagged and none was raised or re-admitted since the guard began (an onset judged there, or
  // found by another test, is no healthy landing).
  if (touching_down) {
    guard_step_ticks_ = 0;
  } else if (guard_step_ticks_ >= 0 && fz_ok && ++guard_step_ticks_ >= jump_window_ticks_) {
    guard_step_ticks_ = -1;
    bool healthy = residual_before_known_ && last_flag_change_s_ < guard_began_s_;
    for (const auto& c : channels_) healthy = healthy && c.type == FaultType::none;
    if (healthy) {
      // Clipped at the bar once it is known: a fault not raised on this guard (ambiguous, or its
      // judgment still to come) would otherwise raise the bar for the rest of the walk; a
      // healthy step beyond z_g of the RMS is rare enough that the clip barely lowers it.
      double step = std::abs(recent_residual_mean() - residual_before_touchdown_);
      if (guard_step_count_ >= kMinGuardSteps) {
        step = std::min(step, landing_step_bar(params_.jump_confirm_N));
      }
      guard_step_square_ += step * step;
      ++guard_step_count_;
    }
  }

  // The feet's plane verdicts, taken before any member is raised (a raise sets the offset the
  // verdict's level check corrects by), and the size of each group decided this tick.
  for (std::size_t f = 0; f < relation_verdict_.size(); ++f) {
    relation_verdict_[f] = relation_group_[f] == 2 && relation_confirmed(f, measured, t) ? 1 : 0;
    relation_group_size_[f] = 0;
    for (std::size_t i = 0; i < feet_points_ && relation_group_[f] == 2; ++i) {
      relation_group_size_[f] += channels_[f * feet_points_ + i].relation_member ? 1 : 0;
    }
  }
  // Decisions.
  const int min_airborne_samples = min_airborne_samples_;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    if (!std::isfinite(x)) continue;
    // The channel's jump, when its group is decided: the sum residual's group, then (inside a
    // touchdown guard) its foot's plane group; each with its own jump and load before it.
    // A jump of a channel flagged when it jumped is no onset: a stuck output's step back to its
    // load is its end, whichever test re-admitted it while the group was pending (the follow
    // test, on that very step).
    const bool in_air = height[j] > params_.airborne_height_m;
    const auto decide = [&](double jump, double load_before, bool from_flagged, bool gains_load) {
      if (corrects(c.type) && !gain_reads_air_level(c, x) && steps_back(jump, fault_size(c, t, load_before))) {
        // The fault ended with a jump back. In the air, where the reading is the fault itself, a
        // step back by half the fault's size is within steps_back's band and is a fault that
        // changed: there the reading must be back within its noise of 0 (else the mean of the
        // readings after the step decides: the air test, below).
        // But an offset that may be a gain, whose gain explained the residual better before the
        // step and whose load stepped with it as the gain implies, is a gain whose pad is
        // unloading: its reading falls by k times the load's fall, which steps back by about the
        // offset when the pad sheds its onset load within a jump window (a lift-off logged at
        // 200 Hz), and the residual then steps by the offset as an end's would. The
        // offset-or-gain test's own decision, taken on the step that would otherwise have ended
        // it (step_is_gains_load).
        if (gains_load) {
          if (c.type != FaultType::gain) take_gain(c, *onset_gain(c));
        } else if (!(in_air && c.fit_has_air) || std::abs(x) < params_.airborne_threshold_N) {
          clear(c);
        }
      } else if (c.type == FaultType::none && !from_flagged) {
        raise_jump_onset(c, jump, load_before, t);
      }
    };
    const bool first_member = group_decided && c.jump_member;
    const bool late_member = late_decided && c.late_member;
    if (first_member) c.jump_member = false;
    if (late_member) c.late_member = false;
    if (first_member && group_confirmed && late_member && late_confirmed && !c.late_from_flagged) {
      decide(c.jump_size + c.late_jump, c.jump_load_before, c.jump_from_flagged, false);  // both its steps: one onset
    } else if (late_member && late_confirmed && c.late_from_flagged) {
      decide(c.late_jump, c.late_load_before, true, false);  // a flagged member's end is its step back alone
    } else if (first_member && group_confirmed) {
      decide(c.jump_size, c.jump_load_before, c.jump_from_flagged, step_is_gains_load(c, c.jump_load_before));
    } else if (late_member && late_confirmed) {
      decide(c.late_jump, c.late_load_before, false, false);  // a healthy channel's (flagged: above)
    }
    const std::size_t foot = channel_foot_[j];
    if (c.relation_member && relation_group_[foot] == 2) {
      c.relation_member = false;
      if (relation_verdict_[foot] != 0) {
        decide(c.relation_jump_size, c.relation_load_before, c.relation_from_flagged, false);
      } else if (relation_step_known_[foot] == 0 && c.type == FaultType::none && !c.relation_from_flagged &&
                 residual_before_known_ && c.relation_load_before > params_.airborne_threshold_N &&
                 x > params_.airborne_threshold_N) {
        // The plane could not judge it (the foot was not in full contact over the windows): the
        // sum residual does, once the guard is over, against its mean before the guard. Only a
        // step between two loads: one from or to the pad's zero level is its contact coming or
        // going (a sole rolling off or onto it as the feet trade load).
        c.onset_after_guard = true;
        c.guard_onset_jump = c.relation_jump_size;
        c.guard_onset_load = c.relation_load_before;
        c.guard_onset_before = residual_before_touchdown_;
        c.guard_onset_guard_began_s = guard_began_s_;
        c.guard_onset_since_s = t;  // the group's stamp: its foot's candidates decided this tick
        c.guard_onset_plane_group = relation_group_size_[foot];  // every member, qualifying or not
        guard_onsets_clear_ticks_ = 0;
      }
    }
    // Frozen / saturation.
    if (repeat_test_off_ && params_.upper_limit_N > 0.0 && x >= params_.upper_limit_N - repeat_band_N_) {
      // Without the repeat test, a reading at the top of the stated range is saturation on its tick.
      raise(c, FaultType::saturation, t);
    } else if (c.stale_count >= frozen_ticks_) {
      // Saturation: stuck at the top of the range, or at the largest load the channel has shown,
      // or stuck again at the value of its previous stuck episode after moving in between (a
      // clipped load comes back to the same ceiling; a frozen sensor does not leave and return).
      const bool loaded = x > params_.airborne_threshold_N;
      const bool at_limit = params_.upper_limit_N > 0.0 && x >= params_.upper_limit_N - repeat_band_N_;
      const bool at_max = at_limit || (loaded && x >= c.max_seen - repeat_band_N_);
      const bool same_ceiling = loaded && std::abs(x - c.last_stale_value) <= repeat_band_N_;
      if (c.stale_count == frozen_ticks_) {
        c.stale_episodes = same_ceiling ? c.stale_episodes + 1 : 1;
        c.last_stale_value = x;
      }
      raise(c, at_max || c.stale_episodes >= 2 ? FaultType::saturation : FaultType::frozen, t);
      if (c.stale_episodes >= 2 && c.type == FaultType::frozen) c.type = FaultType::saturation;
      if (loaded) c.ceiling_N = x;  // stuck under load: a level it may be clipped at again
    } else if (c.type == FaultType::none && c.stale_count >= 1 && !in_air && std::isfinite(c.ceiling_N) &&
               std::abs(x - c.ceiling_N) <= repeat_band_N_ && std::isfinite(c.last_virtual) &&
               c.last_virtual - x > params_.sum_threshold_N) {
      // Back on the level it was last found stuck at under load, while the total force leaves it more.
      raise(c, FaultType::saturation, t);
    } else if ((c.type == FaultType::frozen || c.type == FaultType::saturation) && c.stale_count == 0 &&
               !c.frozen_by_follow) {
      if (c.clear_since < 0) c.clear_since = t;
      if (t - c.clear_since >= params_.clear_s && t - c.flagged_since >= params_.hold_s) clear(c);
    }
    // Spikes. While the channel is flagged as a noise burst, the spikes seen are that noise's own
    // tails: the noise test alone judges when it ends, and the spike episode ends with it.
    if (c.spikes.running()) {
      if (c.type != FaultType::noise) raise(c, FaultType::spikes, t);
    } else if (c.type == FaultType::spikes) {
      clear(c);
    }
    // Noise burst: most second differences far above their healthy spread (counted as the ring
    // fills), and the window rougher than it moves (summed only then: a rare event).
    const int noisy = c.noisy_count;
    bool rough = false;
    if (noisy * 2 > noise_window_ticks_) {
      double d2_power = 0.0, d1_power = 0.0;
      for (std::size_t i = 0; i < c.second_diff.size(); ++i) {
        d2_power += c.second_diff[i] * c.second_diff[i];
        d1_power += c.first_diff[i] * c.first_diff[i];
      }
      rough = d2_power > d1_power;
    }
    // Not raised while a landing rings in the window: the foot bounces on its pads for tens of
    // milliseconds (a few ticks of a slow log), and the other foot's pads ring with the impact.
    if (noisy * 2 > noise_window_ticks_ && rough && !touching_down) {
      raise(c, FaultType::noise, t);
    } else if (c.type == FaultType::noise && noisy * 4 < noise_window_ticks_) {
      if (c.clear_since < 0) c.clear_since = t;
      if (t - c.clear_since >= params_.clear_s && t - c.flagged_since >= params_.hold_s) {
        clear(c);
        c.spikes.end();
      }
    }
    // Negative reading under load (see the evidence loop).
    if (c.sign_fault && c.type == FaultType::gain) {
      double k = 0.0;
      if (c.positive_ticks >= min_airborne_samples) {
        clear(c);
      } else if (c.negative_fit.negative_slope(k)) {
        c.gain = k;
      }
    } else if (double k = 0.0; c.negative_ticks >= min_airborne_samples && !c.fit_has_air &&
                               c.negative_fit.v_hi - c.negative_fit.v_lo >= params_.sum_threshold_N &&
                               c.negative_fit.negative_slope(k) && priority(c.type) <= priority(FaultType::gain)) {
      raise(c, FaultType::gain, t);
      c.gain = k;
      c.sign_fault = true;
    }
    // Airborne pad: its reading is the fault itself.
    if (c.airborne_count >= min_airborne_samples) {
      const double mean = c.airborne_sum / c.airborne_count;
      if (c.type == FaultType::none && std::abs(mean) > params_.airborne_threshold_N) {
        raise(c, FaultType::offset, t);
        c.fit.clear(t);
        c.fit_has_air = false;
        c.air_block_reads_zero = false;  // a block read before the raise says nothing of the fault
        type_air_onset(c, x, t);
        if (c.type == FaultType::offset) type_sum_onset(c, x, t);
      }
      if (c.type == FaultType::offset || c.type == FaultType::drift) {
        const bool reads_zero = std::abs(mean) < params_.airborne_clear_N;
        const bool settled = c.airborne_count >= 3 * min_airborne_samples;
        if (!c.fit_has_air && reads_zero && !settled) {
          // Raised by a jump and near zero in the air so far: wait until the mean settles before
          // fitting the air as an offset (which would hide a gain fault).
        } else if (!c.fit_has_air && reads_zero) {
          // Raised by a jump, zero in the air: a gain fault if the pad was loaded, else over. A
          // pad that kept under a tenth of its load reads nothing, not a scale of it: its output
          // is dead (frozen near zero) and is substituted; dividing by k would blow it up.
          if (const auto k = onset_gain(c)) {
            if (std::abs(*k) >= kMinGain) {
              take_gain(c, *k);
            } else {
              c.type = FaultType::frozen;
              c.frozen_by_follow = true;  // re-admitted only when the reading follows the load again
            }
          } else {
            clear(c);
          }
        } else if (c.fit_has_air && ((std::abs(mean) < params_.airborne_clear_N && settled) || c.air_block_reads_zero) &&
                   t - c.flagged_since >= params_.hold_s) {
          clear(c);  // reads zero in the air again (this swing, or its latest block): the offset or drift is over
          // Judged healthy from here: the swing's mean, which still holds the fault's readings,
          // starts again (else the raise below would take it back at once).
          c.airborne_sum = c.airborne_u_sum = c.airborne_uu_sum = c.airborne_ux_sum = 0.0;
          c.airborne_count = 0;
          c.air_window_flagged = false;
        } else {
          // The air measures directly: drop the jump's estimate, or the level before a step in flight.
          if (!c.fit_has_air || c.air_refit) c.fit.clear(t);
          c.air_refit = false;
          c.fit_has_air = true;
          c.fit.add(t, x, 1.0);
          double a = c.offset, s = 0.0;
          c.fit.solve(a, s);
          // A drift when the slope stands out of the readings' noise: beyond relation_z_ of its
          // standard errors (the decision is taken again every tick: alpha = T / interval).
          // Until the swing's mean has settled, the type stays as it is (the fit spans the
          // swings before: a drift stays a drift at the start of the next).
          const bool drifting = settled ? std::abs(s) * c.fit.slope_scale() > relation_z_ * reading_sigma_N_
                                        : c.type == FaultType::drift;
          c.type = drifting ? FaultType::drift : FaultType::offset;
          c.offset = drifting ? a : c.fit.sb / c.fit.n;
          c.slope = drifting ? s : 0.0;
        }
      }
    }
  }

  // Recovery and the leave-one-out virtual sensor.
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  const auto fault_estimate = io.out(kFaultEstimate);
  const auto recovered = io.out(kRecovered);
  const auto virtual_force = io.out(kVirtual);
  double known_sum = 0.0;
  int unknown_loaded = 0;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    const bool airborne = height[j] > params_.airborne_height_m;
    double value = x;
    bool unknown = false;
    if (c.type == FaultType::offset || c.type == FaultType::drift) {
      value = airborne ? 0.0 : x - fault_at(c, t);
    } else if (c.type == FaultType::gain) {
      value = airborne ? 0.0 : x / c.gain;
    } else if (c.type == FaultType::noise) {
      value = airborne ? 0.0 : c.smoothed;
    } else if (c.type == FaultType::spikes) {
      value = airborne ? 0.0 : generic::median_of_three(x, c.previous, c.previous2);
    } else if (c.type != FaultType::none) {
      value = 0.0;
      unknown = !airborne;
    }
    recovered[j] = value;
    if (unknown) {
      ++unknown_loaded;
    } else {
      known_sum += value;
    }
  }
  // A noise burst's channel, loaded: its leave-one-out force carries the load's fast moves, which
  // a low-pass of the reading lags by tens of newtons in a step; the low-pass is kept for what
  // that force misses, the slow part of reading - force (complementary: v + LP(x - v)). Only while
  // no loaded channel is substituted: their loads are what the total force leaves, so the noise
  // channel's own share is then unknown, and the low-pass of its reading stands.
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    if (!fz_ok || unknown_loaded > 0 || c.type != FaultType::noise || height[j] > params_.airborne_height_m ||
        !std::isfinite(x)) {
      c.noise_bias_set = false;
      continue;
    }
    const double v = std::max(0.0, fz - (known_sum - recovered[j]));
    c.noise_bias = c.noise_bias_set ? c.noise_bias + smoothing_ * ((x - v) - c.noise_bias) : c.smoothed - v;
    c.noise_bias_set = true;
    known_sum += (v + c.noise_bias) - recovered[j];
    recovered[j] = v + c.noise_bias;
  }
  // Channels that must be substituted carry what the total force leaves, apportioned by the
  // plane of a rigid sole where it holds (unmeasured_contact_loads.hpp); each at least 0, a
  // saturated pad at least its ceiling (its reading, when it reads a load).
  if (fz_ok && unknown_loaded > 0) {
    for (std::size_t f = 0; f < feet_; ++f) plane_usable_[f] = 1;
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      const Channel& c = channels_[j];
      const bool airborne = height[j] > params_.airborne_height_m;
      const bool unknown = c.type != FaultType::none && !own_estimate(c.type) && !airborne;
      unknown_[j] = unknown ? 1 : 0;
      const double x = measured[j];
      lower_bound_[j] = unknown && c.type == FaultType::saturation && std::isfinite(x) &&
                                x > params_.airborne_threshold_N
                            ? x
                            : 0.0;
      // The plane holds in full contact only: every pad on the ground, every known one loaded.
      if (airborne || (!unknown && !(recovered[j] > params_.airborne_threshold_N))) {
        plane_usable_[channel_foot_[j]] = 0;
      }
    }
    // A foot whose readable pads on the ground all read their air level, past its landing's
    // guard, carries next to nothing (its sole is lifting): while another foot not seen unloaded
    // holds an unknown pad too, that pad takes what the total force leaves, and this foot's
    // unknown pads (but a saturated one, which reads its load) carry 0. Else they share as before.
    bool loaded_foot_unknown = false;
    for (std::size_t f = 0; f < feet_; ++f) {
      foot_reads_unloaded_[f] = 0;
      bool holds_unknown = false, shows_load = false;
      for (std::size_t i = 0; i < feet_points_; ++i) {
        const std::size_t j = f * feet_points_ + i;
        if (unknown_[j] != 0) {
          holds_unknown = true;
        } else if (!(height[j] > params_.airborne_height_m)) {
          if (recovered[j] > params_.airborne_threshold_N) shows_load = true;
          foot_reads_unloaded_[f] = 1;
        }
      }
      // A sole landing may stand on its substituted pad alone (a heel first): lifting ones only.
      if (shows_load || foot_landing(f, t)) foot_reads_unloaded_[f] = 0;
      loaded_foot_unknown = loaded_foot_unknown || (holds_unknown && foot_reads_unloaded_[f] == 0);
    }
    for (std::size_t j = 0; j < channels_.size() && loaded_foot_unknown; ++j) {
      if (unknown_[j] != 0 && foot_reads_unloaded_[channel_foot_[j]] != 0 && lower_bound_[j] == 0.0) {
        unknown_[j] = 0;
        recovered[j] = 0.0;
      }
    }
    unmeasured_.solve(recovered, unknown_, lower_bound_, plane_usable_, fz - known_sum);
    // Left the only one to take what the total force leaves, a lifting foot's unknown pad may
    // still carry its foot's last load (a sole rolling off it), but no more than it carried a tick
    // before: a sole that lifts takes on no load. What the total force leaves beyond that is
    // another channel's error (a correction gone wrong elsewhere), left in the sum residual.
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      if (unknown_[j] != 0 && foot_reads_unloaded_[channel_foot_[j]] != 0 && lower_bound_[j] == 0.0 &&
          std::isfinite(channels_[j].recovered)) {
        recovered[j] = std::min(recovered[j], std::max(0.0, channels_[j].recovered));
      }
    }
  }
  double total = known_sum;
  int flagged = 0;  // the gain refit trusts the leave-one-out force only where no other channel is flagged
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const bool airborne = height[j] > params_.airborne_height_m;
    flagged += c.type != FaultType::none ? 1 : 0;
    if (c.type != FaultType::none && !own_estimate(c.type) && !airborne) {
      if (!fz_ok) recovered[j] = c.recovered;
      total += recovered[j];
    }
  }
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const bool airborne = height[j] > params_.airborne_height_m;
    virtual_force[j] = airborne ? 0.0
                       : fz_ok  ? std::max(0.0, fz - (total - recovered[j]))
                                : std::numeric_limits<double>::quiet_NaN();
    follow_test(c, measured[j], virtual_force[j], t);
    fault[j] = c.type != FaultType::none ? 1.0 : 0.0;
    type[j] = fault_code(c.type);
    const double x = measured[j];
    fault_estimate[j] = std::isfinite(x) ? x - recovered[j] : 0.0;
    c.recovered = recovered[j];
    c.recovered_as = c.type;
    c.last_virtual = virtual_force[j];
    if (c.negative_ticks > 0 && std::isfinite(x) && virtual_force[j] > params_.gain_min_load_N) {
      c.negative_fit.add(virtual_force[j], x);
    }
    if (c.type != FaultType::gain || c.sign_fault) {
      if (c.gain_fit.n > 0.0) c.gain_fit = SlopeFit{};  // (most channels most ticks: already empty)
    } else if (flagged == 1 && fz_ok && !touching_down && !airborne && std::isfinite(x) &&
               virtual_force[j] > params_.gain_min_load_N) {
      c.gain_fit.add(virtual_force[j], x);
      refit_gain(c);
    }
    if (std::isfinite(x)) {
      c.smoothed = ticks_since_start > 0 ? c.smoothed + smoothing_ * (x - c.smoothed) : x;
      c.previous2 = ticks_since_start > 0 ? c.previous : x;
      c.previous = x;
    }
  }
  // The corrected sum residual: what no channel explains.
  const double residual = fz_ok ? total - fz : 0.0;
  // The relations' fault-free statistics, for the substituted loads: the sum residual while no
  // channel is flagged, a foot's plane while its pads are all healthy, on the ground and loaded.
  // (and the residual's block means, for a fault the air finds: type_sum_onset).
  bool none_flagged = true;
  for (const Channel& c : channels_) none_flagged = none_flagged && c.type == FaultType::none;
  if (fz_ok && all_finite_readings && none_flagged) unmeasured_.observe_sum(residual);
  // A substituted channel on the ground takes what the total force leaves: the residual is then 0
  // by construction, no reading of the reference's level or of an unflagged fault.
  observe_sum_block(residual, fz_ok && all_finite_readings && unknown_loaded == 0, none_flagged, t);
  if (unmeasured_.relations_per_foot() > 0) {
    for (std::size_t f = 0; f < feet_; ++f) {
      bool full_contact = true;
      for (std::size_t i = 0; i < feet_points_ && full_contact; ++i) {
        const std::size_t j = f * feet_points_ + i;
        full_contact = channels_[j].type == FaultType::none && std::isfinite(measured[j]) &&
                       !(height[j] > params_.airborne_height_m) && measured[j] > params_.airborne_threshold_N;
      }
      if (full_contact) unmeasured_.observe_foot(f, measured.subspan(f * feet_points_, feet_points_));
    }
  }
  // Not within touchdown_guard_s of a touchdown: the impact, unseen by the trunk IMU, moves the
  // residual as the load shifts between the feet, which a gain of the unloading pad would mimic.
  if (fz_ok && !touching_down) {
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      offset_or_gain_test(channels_[j], measured[j], height[j] > params_.airborne_height_m, residual);
    }
  }
  still_reading_test(measured, height, residual, fz_ok && all_finite_readings, any_step, t);
  unread_load_test(height, fz_ok && all_finite_readings && std::isfinite(residual), t);
  gain_regression(measured, recovered, height, residual,
                  fz_ok && all_finite_readings && !touching_down && !uncorrected_loaded, t);
  if (fz_ok && all_finite_readings && touching_down && !uncorrected_loaded) {
    compare_held_gain_in_guard(measured, recovered, height, residual, t);
  }
  // The recovered value within what the physics allows, before (or while) the tests decide. Only
  // the output: the tests judge the reading, and the channel's state keeps its own value.
  // - A pad in the air carries nothing: an unflagged airborne reading beyond airborne_threshold_N
  //   (4 sigma) is no force; its value is 0, its leave-one-out force in the air, while it stays
  //   unflagged (the air test raises it once it has its samples, if their mean is beyond that too).
  // - A pad only pushes: an unflagged reading on the ground below -airborne_threshold_N (a healthy
  //   reading goes there once in about 30,000 ticks) is no force; that tick's value is its
  //   leave-one-out force while it stays unflagged (the negative-reading test types a run of them
  //   once it has the ticks it needs: a sign flip, a negative offset). One such tick is no fault.
  // - An offset raised by a jump under load that may yet be a gain (the offset-or-gain test has not
  //   decided): recovered by whichever model, x - b or x / k, lies nearer its leave-one-out force
  //   by more than jump_confirm_N. The wrong one is taken only where the two lie within about
  //   twice that force's error e of each other, so the error stays within about 2 |e|.
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double x = measured[j];
    if (!std::isfinite(x)) continue;
    const bool airborne = height[j] > params_.airborne_height_m;
    double value = recovered[j];
    if (c.type == FaultType::none && airborne) {
      if (std::abs(x) > params_.airborne_threshold_N) value = 0.0;
    } else if (c.type == FaultType::none) {
      if (x < -params_.airborne_threshold_N && std::isfinite(virtual_force[j])) value = virtual_force[j];
    } else if (c.type == FaultType::offset && !c.fit_has_air && !airborne && std::isfinite(virtual_force[j])) {
      const auto k = onset_gain(c);
      const bool as_gain = k && std::abs(*k) >= kMinGain &&
                           std::abs(x / *k - virtual_force[j]) + params_.jump_confirm_N <
                               std::abs(recovered[j] - virtual_force[j]);
      if (as_gain) value = x / *k;
      // At its air level both models read about 0 and x / k always lies nearer: the choice made
      // above it stands (gain_reads_air_level).
      if (std::abs(x) > params_.airborne_threshold_N) c.reads_as_gain = as_gain;
    }
    if (value != recovered[j]) {
      recovered[j] = value;
      fault_estimate[j] = x - value;
    }
  }
  const double a = -std::expm1(-2.0 * 3.141592653589793 * params_.sum_cutoff_hz * period_s_);
  // Without F_z the residual is unknown, not zero: hold the filter rather than pull it to zero.
  if (fz_ok || !started_) sum_filtered_ = started_ ? sum_filtered_ + a * (residual - sum_filtered_) : residual;
  io.out(kSumResidual)[0] = sum_filtered_;
  io.out(kUnisolated)[0] =
      (!fz_ok || std::abs(sum_filtered_) > params_.sum_threshold_N || gain_unisolated_) ? 1.0 : 0.0;
  io.out(kVirtualReady)[0] = fz_ok ? 1.0 : 0.0;
  // A channel not flagged is judged only while the sum residual can speak for it: not while the
  // total force is unknown, nor while its residual is off with no channel to blame.
  const bool blind = io.out(kUnisolated)[0] != 0.0;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    io.out(kCannotJudge)[j] = blind && channels_[j].type == FaultType::none ? 1.0 : 0.0;
  }
  started_ = true;
}

void ContactForceFdi::relation_jumps(std::span<const double> measured, std::span<const double> height,
                                     double t) noexcept {
  const std::size_t relations = unmeasured_.relations_per_foot();
  if (relations == 0) return;
  const std::size_t ring = static_cast<std::size_t>(2 * jump_window_ticks_);
  const std::size_t w = static_cast<std::size_t>(jump_window_ticks_);
  for (std::size_t f = 0; f < feet_; ++f) {
    if (relation_group_[f] == 2) {  // decided on the last tick
      relation_group_[f] = 0;
      for (std::size_t i = 0; i < feet_points_; ++i) channels_[f * feet_points_ + i].relation_member = false;
    }
    // Full contact: every pad on the ground and carrying load (its reading, corrected), read as
    // it is or corrected (a substituted or noisy pad would put its unmeasured changes in the plane).
    bool full = true;
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const std::size_t j = f * feet_points_ + i;
      const Channel& c = channels_[j];
      const double x = measured[j];
      const double load = c.type == FaultType::gain                                    ? x / c.gain
                          : c.type == FaultType::offset || c.type == FaultType::drift ? x - fault_at(c, t)
                                                                                      : x;
      full = full && std::isfinite(x) && !(height[j] > params_.airborne_height_m) &&
             load > params_.airborne_threshold_N && (c.type == FaultType::none || corrects(c.type));
    }
    full_contact_run_[f] = full ? std::min(full_contact_run_[f] + 1, ring) : 0;
    for (std::size_t r = 0; r < relations; ++r) {
      double value = 0.0;
      for (std::size_t i = 0; i < feet_points_ && full; ++i) {
        const std::size_t j = f * feet_points_ + i;
        const Channel& c = channels_[j];
        // As the jump test's sum takes them: a gain fault's reading corrected, an offset's as read.
        value += unmeasured_.relation_weight(i, r) * (c.type == FaultType::gain ? measured[j] / c.gain : measured[j]);
      }
      relation_ring_[(f * relations + r) * ring + relation_next_] = value;
    }
  }
  relation_next_ = ring_after(relation_next_, ring);
  for (std::size_t f = 0; f < feet_; ++f) {
    // A run of 2 W full ticks also means the ring holds 2 W values written since the reset.
    const bool known = full_contact_run_[f] == ring;
    relation_step_known_[f] = known ? 1 : 0;
    bool healthy = true, candidates = false;
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const Channel& c = channels_[f * feet_points_ + i];
      healthy = healthy && c.type == FaultType::none;
      candidates = candidates || c.relation_pending;
    }
    if (known) {
      for (std::size_t r = 0; r < relations; ++r) {
        const double* values = &relation_ring_[(f * relations + r) * ring];
        double before = 0.0, after = 0.0;
        for (std::size_t i = 0; i < w; ++i) {
          after += values[ring_back(relation_next_, ring, i)];
          before += values[ring_back(relation_next_, ring, w + i)];
        }
        relation_step_[f * relations + r] = (after - before) / static_cast<double>(w);
        relation_before_[f * relations + r] = before / static_cast<double>(w);
      }
      // The steps of a healthy foot: what the plane's departures and the sensors' noise do in a
      // window, the bar a confirmed jump must clear.
      if (healthy && relation_group_[f] == 0 && !candidates) {
        for (std::size_t r = 0; r < relations; ++r) {
          relation_step_square_[f * relations + r] += relation_step_[f * relations + r] * relation_step_[f * relations + r];
        }
        relation_step_count_[f] += 1.0;
      }
    }
    if (relation_group_[f] == 0 && candidates) {
      relation_group_[f] = 1;
      relation_group_age_[f] = 0;
      for (std::size_t r = 0; r < relations; ++r) relation_expect_[f * relations + r] = 0.0;
      for (std::size_t i = 0; i < feet_points_; ++i) {
        Channel& c = channels_[f * feet_points_ + i];
        c.relation_member = c.relation_pending;
        c.relation_reading_before = c.relation_member ? c.relation_candidate_load : measured[f * feet_points_ + i];
        if (!c.relation_member) continue;
        c.relation_load_before = c.relation_candidate_load;
        c.relation_jump_size = c.relation_jump;
        c.relation_from_flagged = c.candidate_flagged;
        const double jump = in_residual(c.type, c.gain, c.relation_jump);
        for (std::size_t r = 0; r < relations; ++r) {
          relation_expect_[f * relations + r] += unmeasured_.relation_weight(i, r) * jump;
        }
      }
    }
    if (relation_group_[f] == 1 && relation_group_age_[f]++ >= jump_window_ticks_ - 1) relation_group_[f] = 2;
  }
  for (auto& c : channels_) c.relation_pending = false;  // this tick's candidates are in their groups
}

bool ContactForceFdi::relation_confirmed(std::size_t foot, std::span<const double> measured, double t) const noexcept {
  const std::size_t relations = unmeasured_.relations_per_foot();
  if (relations == 0 || relation_step_known_[foot] == 0 ||
      relation_step_count_[foot] < UnmeasuredContactLoads::kMinSamples) {
    return false;
  }
  // Relation r's fault-free window step sigma on this foot: the RMS of its healthy steps [N].
  const auto step_sigma = [&](std::size_t r) {
    return std::sqrt(std::max(relation_step_square_[foot * relations + r] / relation_step_count_[foot], 1e-12));
  };
  // In units of each relation's fault-free step sigma: the step and the jumps' expected step both
  // beyond z (the false-alarm target's quantile), alike in sign, and within z or half of it apart.
  double observed = 0.0, expected = 0.0, agreement = 0.0;
  for (std::size_t r = 0; r < relations; ++r) {
    const double sigma = step_sigma(r);
    const double step = relation_step_[foot * relations + r];
    const double e = relation_expect_[foot * relations + r];
    if (std::abs(step - e) > std::max(relation_z_ * sigma, 0.5 * std::abs(e))) return false;
    // The plane held before the jump: a foot whose relation is already off holds a fault no one
    // has found (a frozen pad that keeps its noise), and its steps are no evidence.
    // Offsets and drifts already found count with their corrections (the ring holds them as read).
    double before = relation_before_[foot * relations + r];
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const Channel& c = channels_[foot * feet_points_ + i];
      if (c.type == FaultType::offset || c.type == FaultType::drift) {
        before -= unmeasured_.relation_weight(i, r) * fault_at(c, t);
      }
    }
    const double level = std::max(unmeasured_.relation_rms(foot, r), 1e-6);  // NaN: not learnt, no verdict
    if (!(std::abs(before) <= relation_z_ * level)) return false;
    observed += (step / sigma) * (step / sigma);
    expected += (e / sigma) * (e / sigma);
    agreement += step * e / (sigma * sigma);
  }
  const double z2 = relation_z_ * relation_z_;
  if (!(observed >= z2 && expected >= z2 && agreement > 0.0)) return false;
  // A group of several pads is named only if no member alone explains the step within the noise
  // (z sigma) and beyond z on its own: with fewer relations than members the plane cannot tell
  // which of them stepped. A lifting sole's pads fall as one, and as one of them nears its zero
  // load it no longer presses in proportion and the plane departs by about what that pad's fall
  // alone implies (SURALP at 200 Hz: 19 N, three healthy pads raised together). None of them is
  // named then (the after-guard judgement names no group of several either); a sensor's fault
  // among them waits for another test (the air test at the foot's swing). Not the group test's
  // 50 % model allowance: with it a pad's +60 N beside a neighbour's +25 N was "explained" by
  // the +60 N alone, and both faults went unnamed (a review's probe).
  int members = 0;
  for (std::size_t i = 0; i < feet_points_; ++i) members += channels_[foot * feet_points_ + i].relation_member ? 1 : 0;
  for (std::size_t i = 0; i < feet_points_ && members >= 2; ++i) {
    const Channel& c = channels_[foot * feet_points_ + i];
    if (!c.relation_member) continue;
    const double jump = in_residual(c.type, c.gain, c.relation_jump_size);
    bool fits = true;
    double alone = 0.0;
    for (std::size_t r = 0; r < relations; ++r) {
      const double sigma = step_sigma(r);
      const double e = unmeasured_.relation_weight(i, r) * jump;
      fits = fits && std::abs(relation_step_[foot * relations + r] - e) <= relation_z_ * sigma;
      alone += (e / sigma) * (e / sigma);
    }
    if (fits && alone >= z2) return false;
  }
  // A pad whose offset may yet be a gain moves the plane by (k - 1) times its load's change, which
  // a landing's load transfer makes as large as a sensor's step: on a 48 kg biped, a gain x 1.5
  // was read as its offset's end at the other foot's landing, and its neighbours' load steps as
  // onsets. Read through the gain instead, is the plane's step within its noise?
  bool may_be_gain = false;
  for (std::size_t i = 0; i < feet_points_; ++i) {
    may_be_gain = may_be_gain || offset_may_be_gain(channels_[foot * feet_points_ + i]);
  }
  if (!may_be_gain) return true;
  for (std::size_t r = 0; r < relations; ++r) {
    const double sigma = step_sigma(r);
    double step = relation_step_[foot * relations + r];
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const std::size_t j = foot * feet_points_ + i;
      const Channel& c = channels_[j];
      const auto k = offset_may_be_gain(c) ? onset_gain(c) : std::nullopt;
      if (!k || !std::isfinite(measured[j]) || !std::isfinite(c.relation_reading_before)) continue;
      step -= unmeasured_.relation_weight(i, r) * (measured[j] - c.relation_reading_before) * (1.0 - 1.0 / *k);
    }
    if (std::abs(step) > relation_z_ * sigma) return true;  // not its load alone: a sensor stepped
  }
  return false;
}

void ContactForceFdi::still_reading_test(std::span<const double> measured,
                                         std::span<const double> height, double residual, bool usable,
                                         bool stepped, double t) noexcept {
  usable = usable && std::isfinite(residual);  // readings too large to sum leave it unknown
  if (usable) {
    residual_smoothed_ = residual_smoothed_started_ ? residual_smoothed_ + smoothing_ * (residual - residual_smoothed_)
                                                    : residual;
    residual_smoothed_started_ = true;
  }
  // The windows restart, once the smoothers have settled, when the residual is unknown, a channel
  // steps (a jump is the jump test's), a flag changes (the corrected residual changes meaning), or
  // a loaded channel's correction follows its load (gain) or replaces it (substituted, noise): a
  // wrong k or share moves the residual as that load moves, which a still neighbour would take.
  bool restart = !usable || stepped;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const bool airborne = height[j] > params_.airborne_height_m;
    restart = restart || c.type != c.still_window_type;
    c.still_window_type = c.type;
    // An offset raised by a jump under load and not yet told from a gain (offset_or_gain_test) is
    // corrected as x - b while it may scale with its load: not additive until decided.
    const bool undecided = c.type == FaultType::offset && !c.fit_has_air && onset_gain(c).has_value();
    const bool additive =
        (c.type == FaultType::offset && !undecided) || c.type == FaultType::drift || c.type == FaultType::spikes;
    restart = restart || (c.type != FaultType::none && !additive && !airborne);
  }
  if (restart) {
    for (StillWindow& w : still_windows_) w.active = false;
    still_window_settle_until_s_ = t + smoother_settle_s_;
    next_short_window_s_ = still_window_settle_until_s_ + short_window_stagger_s_;
    return;
  }
  if (t < still_window_settle_until_s_) return;
  const std::size_t n = channels_.size();
  for (std::size_t j = 0; j < n; ++j) {
    const Channel& c = channels_[j];
    smoothed_[j] = c.smoothed;
    judgeable_[j] = c.type == FaultType::none && !(height[j] > params_.airborne_height_m) && std::isfinite(measured[j]);
  }
  // A window opened on this tick (start_s == t) holds this tick's values only: judged from the next.
  const auto open = [&](std::size_t w) {
    StillWindow& window = still_windows_[w];
    window.active = true;
    window.start_s = t;
    window.residual_lo = window.residual_hi = residual_smoothed_;
    for (std::size_t j = 0; j < n; ++j) {
      const double x = smoothed_[j];
      still_lo_[w * n + j] = still_hi_[w * n + j] = x;
      since_low_min_[w * n + j] = since_low_max_[w * n + j] = x;
      since_high_min_[w * n + j] = since_high_max_[w * n + j] = x;
      still_grounded_[w * n + j] = channels_[j].type == FaultType::none && !(height[j] > params_.airborne_height_m);
    }
  };
  if (!still_windows_[kLongStillWindow].active) open(kLongStillWindow);
  if (t >= next_short_window_s_) {
    open(next_short_window_);
    next_short_window_ = next_short_window_ + 1 == kShortStillWindows ? 0 : next_short_window_ + 1;
    next_short_window_s_ = t + short_window_stagger_s_;
  }
  for (std::size_t w = 0; w < still_windows_.size(); ++w) {
    StillWindow& window = still_windows_[w];
    if (!window.active || window.start_s == t) continue;
    window.residual_lo = std::min(window.residual_lo, residual_smoothed_);
    window.residual_hi = std::max(window.residual_hi, residual_smoothed_);
    double* lo = still_lo_.data() + w * n;
    double* hi = still_hi_.data() + w * n;
    char* grounded = still_grounded_.data() + w * n;
    for (std::size_t j = 0; j < n; ++j) {
      lo[j] = std::min(lo[j], smoothed_[j]);
      hi[j] = std::max(hi[j], smoothed_[j]);
      grounded[j] = static_cast<char>(grounded[j] & judgeable_[j]);
    }
    if (w == kLongStillWindow) continue;  // judged by the whole range alone
    // Each reading's range since the residual was last near each extreme (within a quarter of
    // its bound: its noise does not take the start back into what happened before it moved).
    const bool near_low = residual_smoothed_ <= window.residual_lo + residual_near_N_;
    const bool near_high = residual_smoothed_ >= window.residual_hi - residual_near_N_;
    const auto track = [&](std::vector<double>& min, std::vector<double>& max, bool restart_range) {
      double* const lo_since = min.data() + w * n;
      double* const hi_since = max.data() + w * n;
      if (restart_range) {
        std::copy_n(smoothed_.data(), n, lo_since);
        std::copy_n(smoothed_.data(), n, hi_since);
        return;
      }
      for (std::size_t j = 0; j < n; ++j) {
        lo_since[j] = std::min(lo_since[j], smoothed_[j]);
        hi_since[j] = std::max(hi_since[j], smoothed_[j]);
      }
    };
    track(since_low_min_, since_low_max_, near_low);
    track(since_high_min_, since_high_max_, near_high);
  }
  // The long window first, then the short ones; a raise restarts them all on the next tick.
  for (std::size_t k = 0; k < still_windows_.size(); ++k) {
    const std::size_t w = k == 0 ? kLongStillWindow : k - 1;
    StillWindow& window = still_windows_[w];
    if (!window.active || window.start_s == t) continue;
    const double residual_span = window.residual_hi - window.residual_lo;
    // A window shorter than the smoother's settling measures the smoother, not the signals.
    if (residual_span < params_.sum_threshold_N || t - window.start_s < smoother_settle_s_) continue;
    // The residual has moved beyond the total force's error: one still reading explains it (its
    // load moved by that much unread); two or more cannot be told apart (cannot judge), none: some
    // other fault or the reference, left to the other tests.
    // A short window is a tenth of a second: slow loads barely move in it, and a reading that
    // sticks inside it (a saturation's ceiling reached) moved before the residual did. So it rules
    // a reading out only when it spanned beyond twice what a stuck one shows (still_band_N_) since
    // the residual was last near the extreme it moved away from (while it moved), and it names
    // one only when that one stayed within the band over the whole window.
    const bool short_window = w != kLongStillWindow;
    const double bar = short_window ? std::max(params_.follow_ratio * residual_span, 2.0 * still_band_N_)
                                    : params_.follow_ratio * residual_span;
    const bool fell = residual_smoothed_ - window.residual_lo < window.residual_hi - residual_smoothed_;
    std::size_t candidates = 0, culprit = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const Channel& c = channels_[j];
      const std::size_t i = w * n + j;
      const double moved = !short_window ? still_hi_[i] - still_lo_[i]
                           : fell        ? since_high_max_[i] - since_high_min_[i]   // from its high
                                         : since_low_max_[i] - since_low_min_[i];    // from its low
      // Under "j is stuck" its load is its leave-one-out force, x_j - r (both smoothed): a pad only
      // pushes, so one that would carry less than -airborne_threshold_N cannot be the one (a pad
      // reading 0 while the pads' sum reads too much); one stuck where its load came to 0 (a foot
      // about to lift) can.
      if (still_grounded_[i] != 0 && moved < bar &&
          c.smoothed - residual_smoothed_ > -params_.airborne_threshold_N) {
        ++candidates;
        culprit = j;
      }
    }
    window.active = false;  // judged: the long one opens afresh, a short one waits for its turn
    // A landing foot's pads take their loads each in its turn as the sole rolls on (a toe still at
    // its air level beside a loaded heel): such a pad may be the one, but is not named while its
    // foot lands (counted, it keeps any other from being named).
    if (candidates == 1 && !foot_landing(channel_foot_[culprit], t) &&
        (!short_window || still_hi_[w * n + culprit] - still_lo_[w * n + culprit] <= still_band_N_)) {
      raise_stuck(channels_[culprit], t);
      break;
    }
  }
}

void ContactForceFdi::unread_load_test(std::span<const double> height, bool usable, double t) noexcept {
  // The pads read short of the total force by more than a reading at the air level can hide
  // (zero_evidence_above_N_: the total force's error bound, plus a driver's zero clamp), and on
  // one foot one healthy pad on the ground reads its air level while another healthy one carries
  // load: under "that pad reads nothing of its load" it carries the shortfall. Substituted or
  // gain-corrected loaded channels absorb or scale the residual: judged only without them, and
  // not while the gain test has a fit it cannot isolate (a gain elsewhere short of the load).
  if (usable && residual_smoothed_started_ && std::abs(residual_smoothed_) <= params_.sum_threshold_N) {
    residual_within_bound_s_ = t;
  }
  for (Channel& c : channels_) {
    if (c.smoothed > params_.airborne_threshold_N) c.loaded_at_s = t;
  }
  bool judged = usable && residual_smoothed_started_ && residual_smoothed_ < -zero_evidence_above_N_ &&
                !gain_unisolated_;
  for (std::size_t j = 0; j < channels_.size() && judged; ++j) {
    const Channel& c = channels_[j];
    const bool additive = c.type == FaultType::offset || c.type == FaultType::drift || c.type == FaultType::spikes;
    judged = c.type == FaultType::none || additive || height[j] > params_.airborne_height_m;
  }
  // Candidates of two strengths: a pad at its air level since its foot landed (a dead pad that
  // lands), and one that has read nothing since the residual was last within its bound and was
  // handed load since it last read any (its foot's healthy neighbours stepped together while the
  // sum fell, a group the jump test left unnamed for it: a pad that rolled off within the stance,
  // died there and takes its load back unread). The weaker are counted only where no stronger one
  // stands.
  std::size_t candidates = 0, culprit = channels_.size();
  std::size_t weak_candidates = 0, weak_culprit = channels_.size();
  for (std::size_t f = 0; f < feet_ && judged; ++f) {
    bool loaded = false;
    std::size_t since_landing = 0, since_bound = 0, last = channels_.size(), weak_last = channels_.size();
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const std::size_t j = f * feet_points_ + i;
      const Channel& c = channels_[j];
      if (c.type != FaultType::none || height[j] > params_.airborne_height_m) continue;
      if (c.smoothed > params_.airborne_threshold_N) {
        loaded = true;
      } else if (c.smoothed > -params_.airborne_threshold_N && c.loaded_at_s < last_touchdown_s_[f]) {
        ++since_landing;
        last = j;
      } else if (c.smoothed > -params_.airborne_threshold_N && c.loaded_at_s < residual_within_bound_s_ &&
                 c.handed_load_s > c.loaded_at_s) {
        ++since_bound;
        weak_last = j;
      }
    }
    // The shortfall began after this foot landed (the residual was within its bound since), and
    // the landing's guard is over (an impact's error in F_z outlasts the smoother's settling).
    const bool landed = residual_within_bound_s_ >= last_touchdown_s_[f] &&
                        t - last_touchdown_s_[f] >= params_.touchdown_guard_s;
    if (loaded && landed) {
      candidates += since_landing;
      culprit = since_landing > 0 ? last : culprit;
      weak_candidates += since_bound;
      weak_culprit = since_bound > 0 ? weak_last : weak_culprit;
    }
  }
  if (candidates == 0) {
    candidates = weak_candidates;
    culprit = weak_culprit;
  }
  // Two or more cannot be told apart (a sole landing on its heel leaves both toe pads unloaded).
  if (candidates != 1) {
    unread_candidate_ = channels_.size();
    return;
  }
  if (culprit != unread_candidate_) {
    unread_candidate_ = culprit;
    unread_since_s_ = t;
    return;
  }
  // Held for the smoother's settling, past the guard: the residual's lag is not the evidence.
  if (t - unread_since_s_ < smoother_settle_s_) return;
  raise_stuck(channels_[culprit], t);
  unread_candidate_ = channels_.size();
}

bool ContactForceFdi::unread_landing_may_explain(std::span<const double> height, double jump_sum) noexcept {
  const bool fell = jump_sum < 0.0;  // the pads now read less than the total force
  bool explained = false;
  for (std::size_t f = 0; f < feet_; ++f) {
    bool loaded = false, unread_load = false;
    int members = 0, onsets = 0;
    bool gain_takes_load = false;
    for (std::size_t i = 0; i < feet_points_; ++i) {
      const std::size_t j = f * feet_points_ + i;
      const Channel& c = channels_[j];
      members += c.jump_pending ? 1 : 0;
      onsets += c.jump_pending && !c.candidate_flagged ? 1 : 0;
      gain_takes_load = gain_takes_load || (c.jump_pending && c.type == FaultType::gain &&
                                            !(height[j] > params_.airborne_height_m) &&
                                            std::abs(c.candidate_load) <= params_.airborne_threshold_N);
    }
    // A held gain on the ground that takes its load from its air level may have ended in the air
    // (its reading there is its fault's end as much as its going on): its correction then errs by
    // (1/k - 1) of the load, the group's step. One fault's end is fewer faults than two healthy
    // sensors' onsets; the stance comparison judges the gain. (A gain still right, beside two
    // true onsets on that tick, loses them to the other tests: the stated limit.)
    explained = explained || (onsets >= 2 && gain_takes_load);
    for (std::size_t i = 0; i < feet_points_ && members > 0; ++i) {
      const std::size_t j = f * feet_points_ + i;
      const Channel& c = channels_[j];
      if (height[j] > params_.airborne_height_m) continue;
      loaded = loaded || (c.type == FaultType::none && c.smoothed > params_.airborne_threshold_N);
      unread_load = unread_load || (!c.jump_pending && may_hold_unread_load(c, f, fell, onsets >= 2));
    }
    if (members > 0 && loaded && unread_load) {
      explained = true;
      // Two or more healthy sensors of this foot stepped while the sum fell, beside a pad at its
      // air level: the load they handed it is the unread-load test's evidence for that pad.
      for (std::size_t i = 0; i < feet_points_ && onsets >= 2 && fell; ++i) {
        const std::size_t j = f * feet_points_ + i;
        Channel& c = channels_[j];
        if (!(height[j] > params_.airborne_height_m) && !c.jump_pending && c.type == FaultType::none &&
            std::abs(c.smoothed) <= params_.airborne_threshold_N) {
          c.handed_load_s = last_tick_s_;
        }
      }
    }
  }
  return explained;
}

bool ContactForceFdi::may_hold_unread_load(const Channel& c, std::size_t f, bool fell,
                                           bool several_onsets) const noexcept {
  if (c.type == FaultType::none) {
    // Its landing unread: on the ground at its air level, unloaded since the foot landed. Or, where
    // the jump would name two or more healthy sensors of its foot at once, at its air level now
    // (a pad that rolled off within the stance, died there and takes its load back unread): one
    // dead pad is the fewer faults. Not against one sensor's step or a fault's end, which are one
    // fault or none.
    return fell && std::abs(c.smoothed) <= params_.airborne_threshold_N &&
           (several_onsets || c.loaded_at_s < last_touchdown_s_[f]);
  }
  if (!own_estimate(c.type) && c.type != FaultType::invalid) {
    // A stuck reading in the residual as read: load coming onto it reads nothing, and load
    // leaving it (while it carries some) nothing either.
    return fell || c.recovered > params_.airborne_threshold_N;
  }
  // An offset the air measured, not yet seen to follow its load: a reading frozen at a load reads
  // as that offset in the air, and on the ground its correction then says nothing of what it
  // carries (load may come or go unread).
  return (c.type == FaultType::offset || c.type == FaultType::drift) && c.fit_has_air && !c.follows_load;
}

double ContactForceFdi::landing_step_bar(double floor_N) const noexcept {
  return std::max(floor_N, guard_z_ * std::sqrt(guard_step_square_ / std::max(guard_step_count_, 1)));
}

void ContactForceFdi::raise_stuck(Channel& c, double t) noexcept {
  raise(c, FaultType::frozen, t);
  c.frozen_by_follow = true;
  c.following = false;
}

std::size_t ContactForceFdi::air_levels_of_window(const Channel& c, double drop_reading, double drop_time,
                                                  std::span<generic::LevelPoint> out) const noexcept {
  // A mean of n readings is off by the readings' sigma^2 / n and by the quantiser's bias, which no
  // n removes where the noise does not dither it: (q / 2) exp(-2 pi^2 sigma_n^2 / q^2), q / 2
  // without noise, and above the first harmonic's amplitude (q / pi) exp(...) that dominates once
  // the noise dithers (0.007 N for 1 N of noise on 2 N steps, 1.1 N on 5 N steps). It is one
  // bias for the window, shared by its two levels: each carries it twice over, so that their
  // mean carries it whole.
  const bool drop = !std::isnan(drop_reading);
  const double u_drop = drop ? drop_time - c.air_origin_s : 0.0;
  const double n = c.airborne_count - (drop ? 1.0 : 0.0);
  if (!(n >= 1.0)) return 0;
  const double sum_x = c.airborne_sum - (drop ? drop_reading : 0.0);
  const double sum_u = c.airborne_u_sum - u_drop;
  const double mean_u = sum_u / n, mean_x = sum_x / n;
  const double suu = c.airborne_uu_sum - (drop ? u_drop * u_drop : 0.0) - n * mean_u * mean_u;
  const double sux = c.airborne_ux_sum - (drop ? u_drop * drop_reading : 0.0) - n * mean_u * mean_x;
  const double bias_sq = quantiser_bias_N_ * quantiser_bias_N_;  // the mean's; a level's is twice it
  const double reading_var = reading_sigma_N_ * reading_sigma_N_;
  const double t_mean = c.air_origin_s + mean_u;
  if (!(n >= 3.0 && suu > 0.0)) {
    out[0] = {t_mean, mean_x, reading_var / n + bias_sq};
    return 1;
  }
  const double slope = sux / suu;
  const double d = std::sqrt(suu / n);
  out[0] = {t_mean - d, mean_x - slope * d, 2.0 * (reading_var / n + bias_sq)};
  out[1] = {t_mean + d, mean_x + slope * d, 2.0 * (reading_var / n + bias_sq)};
  return 2;
}

void ContactForceFdi::close_air_window(Channel& c) noexcept {
  if (c.type != FaultType::none || c.air_window_flagged || c.airborne_count < min_airborne_samples_) return;
  std::array<generic::LevelPoint, 2> levels{};
  const std::size_t count = air_levels_of_window(c, std::numeric_limits<double>::quiet_NaN(), 0.0, levels);
  for (std::size_t i = 0; i < count; ++i) c.air_levels.push(levels[i]);
}

void ContactForceFdi::type_air_onset(Channel& c, double x, double t) noexcept {
  std::array<generic::LevelPoint, generic::LevelHistory::kCapacity + 2> points{};
  const std::size_t healthy = c.air_levels.ordered(points);
  c.air_levels.clear();
  if (healthy == 0) return;
  // This swing's window without the tick's reading (the air's fit takes that one itself).
  const std::size_t m =
      healthy + air_levels_of_window(c, x, t, std::span(points.data() + healthy, 2));
  if (m == healthy) return;
  const generic::OnsetShape shape = generic::onset_shape(std::span(points.data(), m), relation_z_);
  // A ramp that begins within this swing is this swing's alone: a step inside it under
  // jump_threshold_N (one level between, one full) fits that ramp exactly. The swings before
  // must show the fault growing.
  if (!shape.ramp || shape.first_faulty >= healthy) return;
  start_drift_from_levels(c, t, std::span(points.data() + shape.first_faulty, m - shape.first_faulty), 0.0, {});
}

void ContactForceFdi::start_drift_from_levels(Channel& c, double t, std::span<const generic::LevelPoint> history,
                                              double healthy_level,
                                              std::span<const generic::LevelPoint> swing) noexcept {
  // The fit weighs a reading 1: a level counts as the readings its variance is worth.
  const double reading_variance = reading_sigma_N_ * reading_sigma_N_;
  c.type = FaultType::drift;
  c.fit.clear(t);
  for (const generic::LevelPoint& p : history) c.fit.add(p.t_s, p.level - healthy_level, reading_variance / p.variance);
  for (const generic::LevelPoint& p : swing) c.fit.add(p.t_s, p.level, reading_variance / p.variance);
  c.fit_has_air = true;
  c.air_refit = false;
}

void ContactForceFdi::observe_sum_block(double residual, bool usable, bool clean, double t) noexcept {
  if (usable) {
    sum_block_sum_ += residual;
    sum_block_t_sum_ += t;
    ++sum_block_count_;
  }
  sum_block_clean_ = sum_block_clean_ && clean;
  if (++sum_block_ticks_ < sum_block_target_ticks_) return;
  // A block's mean scatters by the reference's error over the block (correlated over a stride, so
  // not sigma^2 / n). It is measured on the blocks' second differences, d = m_k - 2 m_{k-1} +
  // m_{k-2}, of three full blocks in a row in which no channel was flagged: d ~ N(0, 6 v) for
  // independent means of variance v, and the reference's bias, a constant or a ramp in it (an
  // unflagged drift: what type_sum_onset looks for) adds nothing. A step (an unflagged offset)
  // adds to two of them: so v is read from the median of the latest kCapacity d^2, which one step
  // does not move and which forgets (standing and walking scatter differently).
  const bool full = sum_block_clean_ && sum_block_count_ == sum_block_target_ticks_;
  const double mean = sum_block_count_ > 0 ? sum_block_sum_ / sum_block_count_ : 0.0;
  if (full && sum_block_full_run_ >= 2) {
    const double d = mean - 2.0 * sum_block_last_means_[1] + sum_block_last_means_[0];
    sum_block_d2_[sum_block_d2_next_] = d * d;
    sum_block_d2_next_ = (sum_block_d2_next_ + 1) % sum_block_d2_.size();
    sum_block_d2_count_ = std::min(sum_block_d2_count_ + 1, sum_block_d2_.size());
  }
  sum_block_full_run_ = full ? std::min(sum_block_full_run_ + 1, 2) : 0;
  sum_block_last_means_[0] = sum_block_last_means_[1];
  sum_block_last_means_[1] = mean;
  // A block with under half its ticks usable is dropped (its mean is another, shorter average).
  // Its variance is kept relative to a full block's (type_sum_onset scales it by v).
  if (2 * sum_block_count_ >= sum_block_target_ticks_) {
    sum_levels_.push({sum_block_t_sum_ / sum_block_count_, mean,
                      static_cast<double>(sum_block_target_ticks_) / sum_block_count_});
  }
  sum_block_ticks_ = sum_block_count_ = 0;
  sum_block_sum_ = sum_block_t_sum_ = 0.0;
  sum_block_clean_ = true;
}

void ContactForceFdi::type_sum_onset(Channel& c, double x, double t) noexcept {
  const auto variance = sum_block_variance();
  if (!variance || !(c.airborne_count >= 1.0)) return;
  const double block_variance = *variance;
  std::array<generic::LevelPoint, generic::LevelHistory::kCapacity + 1> points{};
  const std::size_t blocks = sum_levels_.ordered(points);
  if (blocks < 3) return;
  for (std::size_t i = 0; i < blocks; ++i) points[i].variance *= block_variance;
  // The blocks alone must rise along a ramp; then the ramp must go on to the level the air reads:
  // the air's mean, at its mean time, joins them as one more level (on the residual's healthy
  // level c, as the blocks' fit gives it: the air test's premise is that a healthy pad reads 0 in
  // the air), and the ramp must still win. A step inside a block leaves c, c + f b, c + b, which a
  // ramp fits exactly for f <= 1/2 (a block is a mean, not its line), but the air then reads c + b, not the
  // ramp's level further on (a review's finding); and the ramp must beat a step inside one block
  // (step_within_a_point_chi2) by z^2 as it beats the plain step: with the step's block partway
  // and one or two full ones after it, the ramp still fits better than the plain step.
  const generic::OnsetShape blocks_shape = generic::onset_shape(std::span(points.data(), blocks), relation_z_);
  if (!blocks_shape.ramp) return;
  const double n = c.airborne_count;
  const double air_mean = c.airborne_sum / n;
  const double air_time = c.air_origin_s + c.airborne_u_sum / n;
  const double reading_variance = reading_sigma_N_ * reading_sigma_N_;
  const double air_variance = reading_variance / n + quantiser_bias_N_ * quantiser_bias_N_;
  if (!(air_time > points[blocks - 1].t_s)) return;
  points[blocks] = {air_time, blocks_shape.healthy_level + air_mean, air_variance};
  const generic::OnsetShape shape = generic::onset_shape(std::span(points.data(), blocks + 1), relation_z_);
  // The ramp must have begun before this swing (the swing's own readings are the air's) and be the
  // channel's fault: of the air's sign, and by this swing's mean time at the level the air reads
  // above 0, within z of the two's noise (a block's and the air mean's).
  if (!shape.ramp || !(shape.onset_s < c.air_origin_s) || shape.first_faulty == 0) return;
  // A block is a mean: a step may fall inside one, and the ramp must beat that shape too.
  if (!(generic::step_within_a_point_chi2(std::span(points.data(), blocks + 1)) - shape.ramp_chi2 >
        relation_z_ * relation_z_)) {
    return;
  }
  const double ramp_level = shape.slope * (air_time - shape.onset_s);
  const double bound = relation_z_ * std::sqrt(block_variance + air_variance);
  if (!(ramp_level * air_mean > 0.0) || !(std::abs(ramp_level - air_mean) <= bound)) return;
  std::size_t ramp_end = shape.first_faulty;  // the ramp's blocks before this swing
  while (ramp_end < blocks && points[ramp_end].t_s < c.air_origin_s) ++ramp_end;
  std::array<generic::LevelPoint, 2> levels{};
  const std::size_t count = air_levels_of_window(c, x, t, levels);
  start_drift_from_levels(c, t, std::span(points.data() + shape.first_faulty, ramp_end - shape.first_faulty),
                          shape.healthy_level, std::span(levels.data(), count));
}

void ContactForceFdi::raise_jump_onset(Channel& c, double jump, double load_before, double t) noexcept {
  c.onset_load = load_before;  // the load the onset jump left (onset_gain)
  c.reads_as_gain = false;
  raise(c, FaultType::offset, t);
  c.fit.clear(t);
  c.fit.add(t, jump, 1.0);
  c.offset = jump;
  c.slope = 0.0;
}

void ContactForceFdi::follow_test(Channel& c, double reading, double virtual_force, double t) noexcept {
  const bool judged = c.type == FaultType::offset || c.type == FaultType::drift ||
                      (c.type == FaultType::frozen && c.frozen_by_follow);
  // The span is the fault's own output's: it starts once the smoothed reading has settled after
  // the step that raised the flag (a frozen output that jumped to 150 N would otherwise span the
  // smoother's rise to it).
  if (!judged || t - c.flagged_since < smoother_settle_s_) {
    c.following = false;
    return;
  }
  if (!std::isfinite(reading) || !std::isfinite(virtual_force)) return;
  const double smoothed = c.smoothed;
  if (!c.following) {
    c.following = true;
    c.offset_power = c.gain_power = 0.0;
    c.load_move_from_onset = 0.0;
    c.virtual_smoothed = virtual_force;
    c.reading_lo = c.reading_hi = smoothed;
    c.virtual_lo = c.virtual_hi = virtual_force;
    return;
  }
  c.virtual_smoothed += smoothing_ * (virtual_force - c.virtual_smoothed);
  c.reading_lo = std::min(c.reading_lo, smoothed);
  c.reading_hi = std::max(c.reading_hi, smoothed);
  c.virtual_lo = std::min(c.virtual_lo, c.virtual_smoothed);
  c.virtual_hi = std::max(c.virtual_hi, c.virtual_smoothed);
  const double load_span = c.virtual_hi - c.virtual_lo;
  const double reading_span = c.reading_hi - c.reading_lo;
  // A frozen output whose own reading moves by sum_threshold_N again, half as much as its load at
  // least, follows a load: a stuck sensor's noise never spans that, so the load's move need not
  // first exceed the force's error twice over.
  if (c.frozen_by_follow && reading_span >= params_.sum_threshold_N && reading_span >= 0.5 * load_span) {
    clear(c);
    return;
  }
  if (load_span < 2.0 * params_.sum_threshold_N) return;  // the load has not moved beyond the force's error
  if (!c.frozen_by_follow) {
    if (reading_span >= params_.follow_ratio * load_span) {
      c.follows_load = true;  // seen to follow: an offset's reading (unread_landing_may_explain)
    } else {
      c.type = FaultType::frozen;
      c.frozen_by_follow = true;
      c.following = false;  // judge re-admission on a fresh span
    }
  } else {
    // Judged on each load move of its own, not on the span since the flag: a reading that has
    // followed again since the fault ended must not have to match every move it missed.
    if (reading_span >= 0.5 * load_span) {
      clear(c);  // the reading follows the load again
    } else {
      c.following = false;  // a fresh span from the next tick
    }
  }
}

void ContactForceFdi::offset_or_gain_test(Channel& c, double reading, bool airborne, double residual) noexcept {
  // Raised by a jump on a loaded pad and not yet seen in the air: x = L + b and x = k L, with
  // k = 1 + b / L0 (L0 the load before the jump), fit the onset alike; they part as the load moves.
  if (c.type != FaultType::offset || c.fit_has_air || !c.following || !std::isfinite(reading)) return;
  const auto k = onset_gain(c);
  if (!k || std::abs(*k) < kMinGain) return;  // none, or a dead output (not a scale): left to the air test
  // The residual takes this channel as x - b; taken as x / k instead it moves by x / k - (x - b).
  const double as_gain = airborne ? residual : residual - (reading - c.offset) + reading / *k;
  c.offset_power += residual * residual;
  c.gain_power += as_gain * as_gain;
  // Judged once the load has moved from L0, where both models meet, by twice the total force's
  // own error bound (not the span since the smoother settled: the load may have moved most of
  // the way within that settling); the gain must leave under half the offset's residual power (a
  // clear win, not a tie on noise).
  c.load_move_from_onset = std::max(c.load_move_from_onset, std::abs(c.virtual_smoothed - c.onset_load));
  if (c.load_move_from_onset < 2.0 * params_.sum_threshold_N) return;
  if (gain_leads(c)) take_gain(c, *k);
}

bool ContactForceFdi::gain_leads(const Channel& c) const noexcept {
  return c.following && offset_may_be_gain(c) && c.gain_power < 0.5 * c.offset_power;
}

bool ContactForceFdi::step_is_gains_load(const Channel& c, double load_before) const noexcept {
  if (!c.jump_gain_led) return false;
  // An offset at the jump, taken for the gain since (the offset-or-gain test may decide on the tick
  // before the group is decided, within its window): the same step, judged with the gain it has.
  const bool taken = c.type == FaultType::gain;
  if (!taken && !offset_may_be_gain(c)) return false;
  const double k = taken ? c.gain : *onset_gain(c);
  return residual_steps_by(c.last_virtual - c.jump_virtual_before, (c.previous - load_before) / k,
                           params_.jump_confirm_N);
}

bool ContactForceFdi::offset_may_be_gain(const Channel& c) const noexcept {
  if (c.type != FaultType::offset || c.fit_has_air) return false;
  const auto k = onset_gain(c);
  return k && std::abs(*k) >= kMinGain;
}

std::optional<double> ContactForceFdi::onset_gain(const Channel& c) const noexcept {
  if (!(c.onset_load > params_.gain_min_load_N) || !(std::abs(c.offset) > 0.1 * c.onset_load)) {
    return std::nullopt;
  }
  return 1.0 + c.offset / c.onset_load;
}

void ContactForceFdi::refit_gain(Channel& c) noexcept {
  const SlopeFit& fit = c.gain_fit;
  if (fit.n < stance_min_ticks_ || fit.v_hi - fit.v_lo < params_.sum_threshold_N || !(fit.svv > 0.0)) return;
  const double k = fit.sxv / fit.svv;
  const double standard_error = std::sqrt(std::max(0.0, fit.sxx - k * fit.sxv) / ((fit.n - 1.0) * fit.svv));
  if (!(k >= kMinGain) || std::abs(k - c.gain) <= relation_z_ * standard_error ||
      std::abs(k / c.gain - 1.0) <= 0.5 * params_.gain_threshold) {
    return;
  }
  c.gain = k;
  // The gain test's window holds residuals computed with the old k (as when it refines k).
  restart_gain_window();
}

void ContactForceFdi::take_gain(Channel& c, double k) noexcept {
  c.type = FaultType::gain;
  c.gain = k;
  c.sign_fault = k < 0.0;  // re-admitted when it reads right side up under load
  // The stance regression's window holds residuals computed with this channel taken as x - b;
  // refining k on them would fit the change of correction, not the sensor. Start a new one.
  restart_gain_window();
}

void ContactForceFdi::gain_regression(std::span<const double> measured, std::span<const double> recovered,
                                      std::span<const double> height, double residual, bool usable,
                                      double t) noexcept {
  if (!usable) {  // the window keeps what it has; impacts and substitutions add nothing
    usable_ticks_in_a_row_ = 0;
    return;
  }
  // A channel re-typed on this tick after the recovered values and the residual were computed
  // with its correction before: the tick belongs to neither model, in any of the sums below (an
  // offset's 384 N correction on the tick it was taken as a gain was the new gain's first tick in
  // its stance comparison, and its weight alone made the reading win 49 ticks later: a x2 gain
  // dropped as its pad lifted; the joint test of all gains took it alike). A re-typing restarts
  // the window (take_gain) or the channel's stance sums (a new type); they start on the next tick.
  for (const Channel& c : channels_) {
    if (c.type != c.recovered_as) return;
  }
  // The sum residual as the jump test takes it (this tick's, the ring's newest), and its level
  // before this tick once settled over 2 clear_s of usable ticks (for a drift's end at once),
  // with that level's variance in units of the residual's (seeded_low_pass_variance).
  const double ring_now = residual_ring_[ring_back(residual_next_, residual_ring_.size(), 0)];
  const double a = residual_level_gain_;
  const bool settled = usable_ticks_in_a_row_ >= 2 * stance_min_ticks_;
  const double level_before = settled ? residual_level_ : std::numeric_limits<double>::quiet_NaN();
  const double seed_weight = residual_level_seed_weight_;  // before this tick's update
  if (!std::isfinite(ring_now) || !std::isfinite(residual)) {
    usable_ticks_in_a_row_ = 0;  // a residual too large to hold: the level starts again
  } else if (usable_ticks_in_a_row_ == 0) {
    residual_level_ = ring_now;
    corrected_level_ = residual;
    residual_level_seed_weight_ = 1.0;
    usable_ticks_in_a_row_ = 1;
  } else {
    residual_level_ += a * (ring_now - residual_level_);
    corrected_level_ += a * (residual - corrected_level_);
    residual_level_seed_weight_ *= 1.0 - a;
    usable_ticks_in_a_row_ = std::min(usable_ticks_in_a_row_ + 1, kCountCap);
  }
  const double f = gain_forgetting_;
  if (!gain_window_.add(recovered, height, params_.airborne_height_m, residual, f)) {
    restart_gain_window();
    return;
  }
  // The window since an unexplained residual's onset: opened on a usable tick while no channel is
  // flagged and the residual is off (as `unisolated` says), closed by any flag and after 3 windows,
  // not when the residual returns within its bound (a gain's does in every swing). So an earlier
  // excursion that resolved itself keeps the stances after it in the window (the 2 s window then
  // judges as before, or this one once 3 windows have passed).
  const bool none_flagged =
      std::all_of(channels_.begin(), channels_.end(), [](const Channel& c) { return c.type == FaultType::none; });
  if (since_unexplained_open_ && (!none_flagged || since_unexplained_.ticks >= 3 * gain_window_ticks_)) {
    since_unexplained_open_ = false;
  }
  if (!since_unexplained_open_ && none_flagged && std::abs(sum_filtered_) > params_.sum_threshold_N) {
    since_unexplained_.restart();
    since_unexplained_open_ = true;
  }
  if (since_unexplained_open_ && !since_unexplained_.add(recovered, height, params_.airborne_height_m, residual, f)) {
    since_unexplained_open_ = false;
  }
  // Every channel held as a gain, read as it is together with the others (the joint test below).
  {
    double joint_raw = residual;
    int gains = 0;
    bool same_set = true;
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      const bool gain = channels_[j].type == FaultType::gain;
      if (gain) {
        joint_raw += measured[j] - recovered[j];
        ++gains;
      }
      same_set = same_set && (joint_gain_set_[j] != 0) == gain;
      joint_gain_set_[j] = gain ? 1 : 0;
    }
    if (!same_set || gains < 2) {
      joint_raw_rr_ = joint_held_rr_ = 0.0;
      joint_gain_ticks_ = 0;
    }
    if (gains >= 2) {
      joint_raw_rr_ = f * joint_raw_rr_ + joint_raw * joint_raw;
      joint_held_rr_ = f * joint_held_rr_ + residual * residual;
      joint_gain_ticks_ = std::min(joint_gain_ticks_ + 1, kCountCap);
    }
  }
  // What the residual would be if a channel held as a gain fault were read as it is, against what
  // it is with the correction, both over the ticks since the correction was last set.
  // In stance, the same comparison for a gain and for an offset: an offset whose end stepped
  // under jump_threshold_N (no jump test sees it) leaves its correction in the residual while its
  // foot stays down, and the air test would only drop it at the next swing. For a drift, not by
  // that alone: its slope, fitted on a swing's readings, is extrapolated through the stance, and a
  // correction grown wrong by that is no sign the fault is over (a 12 N/s drift at 200 Hz was
  // dropped while 30 N, in a try). A drift's reading must also have stayed flat where the drift
  // would have shown (StancePowers::trend): a pad that stays loaded to the end of a log (a robot
  // that stops and stands) has no next swing, and its correction grew without bound. Only while
  // it is the one correction the residual carries: with two, the
  // one that ended and the one that did not both move it, and the one still faulty could win
  // first (a +48 N offset beside a +60 N one fading out). A pad in the air carries none (it is
  // recovered as 0, what it carries there).
  const double stance_bound = params_.gain_min_load_N * params_.gain_min_load_N;
  const int corrections = corrections_in_residual(height);
  for (std::size_t j = 0; j < gain_raw_rr_.size(); ++j) {
    const Channel& c = channels_[j];
    const bool on_ground = !(height[j] > params_.airborne_height_m);  // unknown: on the ground, as it is corrected
    const bool judged =
        (c.type == FaultType::gain || c.type == FaultType::offset || c.type == FaultType::drift) && on_ground;
    StancePowers& stance = stance_powers_[j];
    StancePowers& run = stance_cusum_[j];
    // A new stance, or sums taken for another correction (not rewritten when already fresh: most
    // channels most ticks).
    if (!judged) channels_[j].still_load_drift = false;  // its foot lifted: the stance it rose in is over
    if ((!judged || stance.type != c.type) && !(stance.fresh_for(c.type) && run.fresh_for(c.type))) {
      stance = run = StancePowers{.type = c.type};
      // Raised from the residual's ramp on a still load: the drift rose in this stance already.
      stance.rose_with_drift = c.type == FaultType::drift && c.still_load_drift;
    }
    const double raw = residual + measured[j] - recovered[j];
    if (c.type != FaultType::gain) {
      gain_raw_rr_[j] = gain_held_rr_[j] = 0.0;
      gain_held_ticks_[j] = 0;
    } else {
      gain_raw_rr_[j] = f * gain_raw_rr_[j] + raw * raw;
      gain_held_rr_[j] = f * gain_held_rr_[j] + residual * residual;
      gain_held_ticks_[j] = std::min(gain_held_ticks_[j] + 1, kCountCap);
    }
    if (!judged) {
      if (guard_powers_[j].ticks > 0) guard_powers_[j] = StancePowers{};
      continue;
    }
    // The guard's ticks, judged alone once it is over (compare_held_gain_in_guard).
    if (guard_powers_[j].ticks > 0) {
      const bool fresh = t - guard_powers_last_s_ < (jump_window_ticks_ + 0.5) * period_s_;
      const bool reading_won = fresh && c.type == FaultType::gain && corrections == 1 &&
                               guard_powers_[j].reading_wins(stance_min_ticks_, stance_bound);
      guard_powers_[j] = StancePowers{};
      if (reading_won) {
        clear(channels_[j]);
        restart_gain_window();
        return;
      }
    }
    // Two explanations of the stance, the correction and the reading as it is: the reading wins
    // when the correction leaves 4 times its residual power (twice its RMS), over clear_s of
    // usable ticks in which the correction itself moved the reading by gain_min_load_N RMS or
    // more (a smaller correction is within what the residual's own error can mimic: as a pad
    // unloads, the sum residual's error is as large as a gain's effect on its few newtons). An
    // offset that may yet be a gain must leave a quarter of that model's power too.
    // Over the stance so far; for an offset also over the ticks since the CUSUM of the reading's
    // lead was last at 0: its sums start again whenever the correction has won so far, so a
    // fault that ends late in a long stance is judged on the ticks since its end, not against
    // the stance it was right in. (Not for a gain: its stance so far judges it, as before.)
    // Summed only over ticks with this one correction in the residual: sums that held another's
    // would be judged once that one lifts or ends (a true +48 N offset, leading while a +60 N
    // one beside it had ended, was dropped the tick that one's foot lifted).
    if (corrections != 1) {
      const bool rose = stance.rose_with_drift;
      stance = run = StancePowers{.type = c.type};
      stance.rose_with_drift = rose;
      continue;
    }
    const double correction = measured[j] - recovered[j];
    stance.add(raw, residual, correction, t, period_s_);
    run.add(raw, residual, correction, t, period_s_);
    if (c.type == FaultType::offset && !c.fit_has_air) {
      if (const auto k = onset_gain(c); k && std::abs(*k) >= kMinGain) {
        const double as_gain = residual - recovered[j] + measured[j] / *k;
        const double gain_correction = measured[j] - measured[j] / *k;
        stance.add_gain_model(as_gain, gain_correction);
        run.add_gain_model(as_gain, gain_correction);
      }
    }
    if (!run.reading_leads()) run = StancePowers{.type = c.type};
    // A drift that ended at once (its cause gone, its sensor re-zeroed) steps its reading and its
    // foot's summed reading back by its size, on a tick within a jump window before it began to
    // lead (c.stepped_back_s: load moving between the foot's pads leaves that sum alone), and the
    // sum residual by as much: its level before, and its mean since (StancePowers::stepped_back;
    // load moving between feet leaves the residual alone).
    if (c.type == FaultType::drift && run.ticks == 1) {
      const bool reading_stepped = t - c.stepped_back_s < (jump_window_ticks_ + 0.5) * period_s_;
      run.level_before = reading_stepped ? level_before : std::numeric_limits<double>::quiet_NaN();
      run.level_variance = seeded_low_pass_variance(a, seed_weight);
      run.correction_before = correction;
    }
    if (c.type == FaultType::drift && run.ticks > 0) run.level_sum += ring_now;
    // A drift, only since the reading last led and only where the reading stayed flat: its slope
    // extrapolated through a stance may grow wrong while the drift goes on. A window that shows a
    // slope is closed and the next one judged afresh (the load's own moves in a walking stance
    // before the robot stood still are no drift after it).
    bool flat = false;
    if (c.type == FaultType::drift) {
      const StancePowers::Trend trend = run.trend(c.slope * period_s_, relation_z_);
      flat = trend == StancePowers::Trend::flat;
      if (trend == StancePowers::Trend::sloped) {
        run.trend_window.restart();
        run.level_before = std::numeric_limits<double>::quiet_NaN();  // the reading has moved since
      }
      // The reading as it is, flat over the stance where the drift would have shown, after a window
      // of the same stance in which it rose with the drift (its slope the fitted drift's sign),
      // and off the load by more than the residual's own error can mimic (gain_min_load_N): the
      // drift went on into this stance and stopped there, leaving its level, which the reading
      // keeps (a plateau). An offset at that level (the window's mean lead of the reading, over
      // clear_s at least) from here on: the slope extrapolated would grow past it until the
      // reading, still that far off, won the comparison and was re-admitted. A drift that ended
      // by fading out fell before its flat window (the reading's lead then is the total force's
      // own bias, not a fault: left to the comparison). Over the stance's own window, not the
      // one since the reading last led: while the correction is still about right the reading
      // does not lead.
      const StancePowers::Trend stance_trend = stance.trend(c.slope * period_s_, relation_z_);
      if (stance_trend == StancePowers::Trend::sloped) {
        stance.rose_with_drift = stance.trend_window.slope() * c.slope > 0.0;
        stance.trend_window.restart();
      }
      // (A still-load drift's lead is taken from the residual's healthy level it was raised on:
      // the total force's bias, which a walking stance averages out, stays in a standing one.)
      const double lead = stance.trend_window.mean() - (c.still_load_drift ? c.still_load_healthy_level : 0.0);
      if (stance_trend == StancePowers::Trend::flat && stance.rose_with_drift && corrections == 1 &&
          stance.trend_window.count() >= stance_min_ticks_ && std::abs(lead) > plateau_bar(c, stance.trend_window.count())) {
        hold_as_offset(channels_[j], lead);
        restart_gain_window();  // its window holds residuals taken with the drift's correction
        continue;
      }
    }
    // A drift whose reading stepped back to the load: that step, with the reading on the load since
    // (its mean lead within gain_min_load_N, what the residual's own error can mimic) is enough,
    // with the comparison. A drift regrowing after a fade never stepped.
    const auto ended_by_step = [&] {
      return std::abs(run.trend_window.mean()) <= params_.gain_min_load_N && run.stepped_back(relation_z_);
    };
    const bool wins = c.type == FaultType::drift
                          ? run.reading_wins(stance_min_ticks_, stance_bound) && (flat || ended_by_step())
                          : stance.reading_wins(stance_min_ticks_, stance_bound) ||
                                (c.type == FaultType::offset && run.reading_wins(stance_min_ticks_, stance_bound));
    if (wins && corrections == 1) {
      clear(channels_[j]);
      restart_gain_window();
      return;
    }
  }
  // Judge once per 10 ticks, and only over a full window; then the window since an unexplained
  // residual's onset, while no channel is flagged.
  if (gain_window_.ticks >= gain_window_ticks_ && gain_window_.ticks % 10 == 0 && gain_window_.rr > 0.0) {
    judge_gain_window(t);
  }
  if (since_unexplained_open_ && since_unexplained_.ticks % 10 == 0 &&
      std::all_of(channels_.begin(), channels_.end(), [](const Channel& c) { return c.type == FaultType::none; })) {
    judge_since_unexplained(t);
  }
}

void ContactForceFdi::compare_held_gain_in_guard(std::span<const double> measured, std::span<const double> recovered,
                                                 std::span<const double> height, double residual,
                                                 double t) noexcept {
  // A gain that ended while its pad was in the air lands reading its load again, its correction
  // x / k now wrong by d = x (1 / k - 1) in the sum residual. Judged only on the ticks after the
  // landing's guard, it was still held when the jump test resumed there, and that test took the
  // wrong correction's moves for its neighbours' jumps (a x0.5 gain that ended in the air: three
  // healthy pads raised as offsets 10 ms after the guard). So the ticks of its own foot's guard
  // get the stance comparison of their own, judged on the first usable tick after the guards
  // (within a jump window of the last: sums kept across a gap of unusable ticks would judge a
  // stance long over), before a group the jump test forms there has had its jump window. Apart
  // from the stance's: a gain that ends within the guard, after ticks on which it was right, is
  // judged after the guard as before. Only its own foot's landing: another foot's is no new
  // evidence of this pad, and its impact error would be judged against a gain held right.
  // Not judged inside the guard: the impact's error e of the total force enters both
  // explanations alike (the correction leaves e, or e + d where the gain has ended; the reading
  // leaves e - d, or e), but a pulse of e of d's sign and size, early in the guard, can make a
  // gain still right look ended over clear_s (a 300 N impact fading over 20 ms against
  // d = 150 N). Over the whole guard such a pulse is diluted by the ticks after it, where only d
  // remains; an error of d's sign and two thirds of its size that lasts the guard is not (the
  // reading wins where e > 2 |e - d|), as it would not be over clear_s after the guard.
  guard_powers_last_s_ = t;
  const int corrections = corrections_in_residual(height);
  bool retyped = false;
  for (const Channel& c : channels_) retyped = retyped || c.type != c.recovered_as;
  if (retyped) return;  // re-typed this tick: the tick belongs to neither model
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    const Channel& c = channels_[j];
    StancePowers& guard = guard_powers_[j];
    // Only while it is the one correction in the residual (as judged), on the ground.
    if (c.type != FaultType::gain || corrections != 1 || height[j] > params_.airborne_height_m) {
      if (guard.ticks > 0) guard = StancePowers{};
      continue;
    }
    if (!foot_landing(channel_foot_[j], t)) continue;  // another foot's guard
    const double correction = measured[j] - recovered[j];
    guard.add(residual + correction, residual, correction, t, period_s_);
  }
}

int ContactForceFdi::corrections_in_residual(std::span<const double> height) const noexcept {
  int corrections = 0;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    corrections += corrects(channels_[j].type) && !(height[j] > params_.airborne_height_m) ? 1 : 0;
  }
  return corrections;
}

void ContactForceFdi::GainWindow::resize(std::size_t channels) {
  xx.assign(channels, 0.0);
  xr.assign(channels, 0.0);
  x.assign(channels, 0.0);
  stance.assign(channels, StanceSums{});
  restart();
}

void ContactForceFdi::GainWindow::restart() noexcept {
  std::fill(xx.begin(), xx.end(), 0.0);
  std::fill(xr.begin(), xr.end(), 0.0);
  std::fill(x.begin(), x.end(), 0.0);
  std::fill(stance.begin(), stance.end(), StanceSums{});
  r = rr = weight = 0.0;
  ticks = 0;
}

bool ContactForceFdi::GainWindow::add(std::span<const double> recovered, std::span<const double> height,
                                      double airborne_height_m, double residual, double f) noexcept {
  for (std::size_t j = 0; j < xx.size(); ++j) {
    const double v = recovered[j];
    // A tick of unknown height is in no stance and closes none: neither on the ground nor in
    // the air (a foot pose lost for a few ticks splits no stance and is no air after one).
    const bool known = !std::isnan(height[j]);
    const bool on_ground = known && height[j] <= airborne_height_m;
    xx[j] = f * xx[j] + v * v;
    xr[j] = f * xr[j] + v * residual;
    x[j] = f * x[j] + v;
    // The same fit within each stance of the channel's point (each centred on its own means):
    // the current stance's sums, and the centred sums of the stances closed before it.
    StanceSums& g = stance[j];
    g.w *= f, g.x *= f, g.r *= f, g.xx *= f, g.xr *= f, g.closed_xx *= f, g.closed_xr *= f;
    g.air_after_stance *= f;
    if (on_ground) {
      g.w += 1.0, g.x += v, g.r += residual, g.xx += v * v, g.xr += v * residual;
    } else if (known) {
      if (g.w > 0.0) {
        g.closed_xx += centred(g.xx, g.x, g.x, g.w);
        g.closed_xr += centred(g.xr, g.x, g.r, g.w);
        g.w = g.x = g.r = g.xx = g.xr = 0.0;
        g.stance_closed = true;
      }
      if (g.stance_closed) g.air_after_stance += 1.0;
    }
  }
  r = f * r + residual;
  rr = f * rr + residual * residual;
  weight = f * weight + 1.0;
  // Saturates by whole windows of 10, so the judging cadence and a full window both hold.
  ticks = ticks < kCountCap ? ticks + 1 : ticks - 10 * (kCountCap / 20) + 1;
  return std::isfinite(rr);
}

bool ContactForceFdi::fits_a_gain_from_the_air(const GainWindow& w, std::size_t j, double slope) const noexcept {
  // A gain k > 0 of a reading that is positive on the whole has beta = 1 - 1/k < 1 (beyond: a
  // reading of the opposite sign, a sign flip, which reads negative). One that began in the air,
  // where its pad read its air level, took no step: r = beta N^_j, its residual at zero load
  // (the fit's intercept) within the residual's bound.
  const double zero_load_residual = (w.r - slope * w.x[j]) / w.weight;
  return !(slope >= 1.0 && w.x[j] > 0.0) && std::abs(zero_load_residual) <= params_.sum_threshold_N;
}

ContactForceFdi::GainFit ContactForceFdi::best_gain_fit(const GainWindow& w, double min_power,
                                                         bool only_gains_from_the_air) const noexcept {
  // The channel whose fit r ~ b + beta_j N^_j explains the most of the residual's variation.
  // With the intercept b, an offset anywhere (a constant r) is b, not a gain: through the origin
  // it would be fitted by beta_j N^_j of any pad that is loaded most of the time.
  GainFit fit{.best = w.xx.size()};
  const double r_mean = w.r / w.weight;
  fit.r_variation = w.rr - w.r * r_mean;
  if (!(fit.r_variation > 0.0)) return fit;
  for (std::size_t j = 0; j < w.xx.size(); ++j) {
    const Channel& c = channels_[j];
    // Hardly loaded: not blamed, but its share still counts against the best one's isolation (at
    // the end of a stance every pad of the foot unloads alike, and a loaded neighbour was blamed
    // for what such a pad explained better).
    const bool loaded = w.xx[j] >= min_power;
    const double x_variation = centred(w.xx[j], w.x[j], w.x[j], w.weight);
    const double covariation = w.xr[j] - w.x[j] * r_mean;
    if (!(x_variation > 0.0)) continue;
    const double explained = covariation * covariation / (x_variation * fit.r_variation);
    const double slope = covariation / x_variation;
    // A fit that is no gain begun in the air is no candidate there, but it explains the residual
    // all the same (a load shifting between the feet with the total force's error): a rival.
    if (only_gains_from_the_air && !fits_a_gain_from_the_air(w, j, slope)) {
      fit.second_explained = std::max(fit.second_explained, explained);
      continue;
    }
    const bool judged = c.type == FaultType::none || c.type == FaultType::gain;  // others: by their own evidence
    if (loaded && judged && explained > fit.explained) {
      fit.second_explained = std::max(fit.second_explained, fit.explained);
      fit.best = j;
      fit.explained = explained;
      fit.beta = slope;
      fit.x_variation = x_variation;
      fit.covariation = covariation;
    } else {
      fit.second_explained = std::max(fit.second_explained, explained);
    }
  }
  return fit;
}

bool ContactForceFdi::stances_confirm(const GainWindow& w, const GainFit& fit, double threshold) noexcept {
  const GainWindow::StanceSums& g = w.stance[fit.best];
  const double x_variation = g.closed_xx + (g.w > 0.0 ? centred(g.xx, g.x, g.x, g.w) : 0.0);
  const double covariation = g.closed_xr + (g.w > 0.0 ? centred(g.xr, g.x, g.r, g.w) : 0.0);
  const double stance_beta = x_variation > 0.0 ? covariation / x_variation : 0.0;
  return stance_beta * fit.beta > 0.0 && std::abs(stance_beta) > threshold;
}

void ContactForceFdi::judge_gain_window(double t) noexcept {
  GainWindow& w = gain_window_;
  // Re-admission by model comparison, once the correction has held for a window: a channel held
  // as a gain fault that carried load and whose reading, taken as it is, leaves no more residual
  // power than its correction does is healthy again (this needs no isolation: the pads of one
  // foot are fitted alike, so a small gain error on a healthy pad might never stand out).
  const double min_power = params_.gain_min_load_N * params_.gain_min_load_N * w.weight;
  bool readmitted = false;
  for (std::size_t j = 0; j < gain_raw_rr_.size(); ++j) {
    if (channels_[j].type == FaultType::gain && gain_held_ticks_[j] >= gain_window_ticks_ &&
        w.xx[j] >= min_power && gain_raw_rr_[j] <= gain_held_rr_[j]) {
      clear(channels_[j]);
      readmitted = true;
    }
  }
  // Two or more gains, none of which wins alone: each is judged with the others' corrections
  // still in the residual, so two wrong ones hold each other (a heel's chatter at 200 Hz swapped
  // load between two pads within a tick; taken for two jumps, they were typed gains once their
  // pads read zero in the air, and held for 15 s). Taken as they are together, their readings
  // leave a quarter of the residual power of all their corrections (the stance comparison's
  // margin): every one is healthy again. Not at equal powers: a true gain among them may leave
  // less than the wrong ones' corrections, and true gains whose errors cancel in the sum leave
  // the two alike.
  if (!readmitted && joint_gain_ticks_ >= gain_window_ticks_ && joint_held_rr_ > kReadingWinsPowerRatio * joint_raw_rr_) {
    bool loaded = true;
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      if (joint_gain_set_[j] != 0) loaded = loaded && w.xx[j] >= min_power;
    }
    for (std::size_t j = 0; j < channels_.size() && loaded; ++j) {
      if (joint_gain_set_[j] != 0) {
        clear(channels_[j]);
        readmitted = true;
      }
    }
  }
  if (readmitted) {
    restart_gain_window();
    return;
  }
  const GainFit fit = best_gain_fit(w, min_power);
  // The pads of one foot load together, so a gain fault on one is fitted almost as well by its
  // neighbours (the sum residual cannot see moments): blame a channel only when its fit stands out.
  // A strong fit that does not stand out is a fault that cannot be isolated: reported as such
  // (`unisolated`) until a window shows no strong fit or an isolated one.
  if (fit.best == w.xx.size() || fit.explained < params_.gain_explained) {
    gain_unisolated_ = false;
    return;
  }
  Channel& c = channels_[fit.best];
  const double threshold = c.type == FaultType::none ? params_.gain_threshold : 0.5 * params_.gain_threshold;
  if (std::abs(fit.beta) <= threshold) {
    gain_unisolated_ = false;
    return;
  }
  gain_unisolated_ = fit.explained - fit.second_explained < params_.gain_isolation_margin;
  if (gain_unisolated_) return;
  // A new gain must hold within each stance too: a fault that begins as the pad lands (an offset
  // b: r = 0 with N^ = 0 in the air before, r = b with N^ = N + b after) lies on a line across the
  // landing, but within a stance r stays b while N^ moves. Only a confirmation: within a stance
  // the limb dynamics follow the loads, too weak a test to raise a flag by itself.
  if (c.type == FaultType::none && !stances_confirm(w, fit, threshold)) return;
  // A gain reads its load N k times, so k is told from an additive error only where the load
  // moved. A new flag whose implied load N^ = x - r stayed within gain_min_load_N RMS over the
  // window (a robot standing while a pad drifts: r and x rise together, beta near 1, k = 10 from
  // the clamp below) is an additive fault, typed and sized from the sum residual's history.
  if (c.type == FaultType::none) {
    const double load_variation = fit.x_variation - 2.0 * fit.covariation + fit.r_variation;
    if (load_variation < min_power) {
      raise_still_load_fault(c, (w.x[fit.best] - w.r) / w.weight, t);
      restart_gain_window();
      return;
    }
  }
  // recovered_new = recovered (1 - beta): k_new = k / (1 - beta).
  double gain = (c.type == FaultType::gain ? c.gain : 1.0) / (1.0 - std::clamp(fit.beta, -5.0, 0.9));
  if (std::abs(gain) < kMinGain) gain = std::copysign(kMinGain, gain);  // the recovery divides by it
  if (c.type == FaultType::gain && std::abs(1.0 - 1.0 / gain) < 0.5 * params_.gain_threshold) {
    clear(c);  // the reading is its force again
  } else {
    raise(c, FaultType::gain, t);
    c.gain = gain;
  }
  // The window's residuals were computed with the old correction: start a new one.
  restart_gain_window();
}

void ContactForceFdi::judge_since_unexplained(double t) noexcept {
  // The same tests as the gain window's for a new flag, on the ticks since the residual left its
  // bound (clear_s of them at least), the best among the fits a gain begun in the air makes
  // (through zero load, k > 0) standing out of every other channel's fit. A gain reads its
  // load k times, so its residual follows the load to 0 in the air, where an additive fault's
  // stays: once the best channel's point has closed a stance within the window and been in the
  // air clear_s since, that is settled; before, a still reading on the ground (below) may be a
  // stuck sensor the fit mistakes. Still loads are left to the gain window (their type is the
  // residual's history, which this window does not hold).
  const GainWindow& w = since_unexplained_;
  if (w.ticks < stance_min_ticks_) return;
  const double min_power = params_.gain_min_load_N * params_.gain_min_load_N * w.weight;
  const GainFit fit = best_gain_fit(w, min_power, true);
  if (fit.best == w.xx.size() || fit.explained < params_.gain_explained ||
      std::abs(fit.beta) <= params_.gain_threshold ||
      fit.explained - fit.second_explained < params_.gain_isolation_margin) {
    return;
  }
  // Before its pad has been in the air after a stance (where a gain reads 0 as its load does and
  // an additive fault's residual stays), a reading that stayed still on the ground within the
  // window (its power about each stance's own mean, over the ticks its point was on the ground)
  // may be a stuck one whose load is the residual: its neighbour's fit is then a load shift
  // between them, not a gain. (Every channel is healthy while this window is judged.)
  if (w.stance[fit.best].air_after_stance < stance_min_ticks_) {
    const double still = params_.follow_ratio * params_.follow_ratio * fit.r_variation;
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      const GainWindow::StanceSums& g = w.stance[j];
      if (j == fit.best || !(g.w > 0.0 || g.stance_closed)) continue;  // never on the ground in the window
      const double power = g.closed_xx + (g.w > 0.0 ? centred(g.xx, g.x, g.x, g.w) : 0.0);
      if (!(power >= still)) return;
    }
  }
  if (!stances_confirm(w, fit, params_.gain_threshold)) return;
  if (fit.x_variation - 2.0 * fit.covariation + fit.r_variation < min_power) return;
  Channel& c = channels_[fit.best];
  double gain = 1.0 / (1.0 - std::clamp(fit.beta, -5.0, 0.9));
  if (std::abs(gain) < kMinGain) gain = std::copysign(kMinGain, gain);  // the recovery divides by it
  raise(c, FaultType::gain, t);
  c.gain = gain;
  since_unexplained_open_ = false;
  gain_unisolated_ = false;  // isolated now: the gain window, restarted below, judges again in a window
  // The gain window's residuals were computed without the correction: start a new one.
  restart_gain_window();
}

std::optional<double> ContactForceFdi::sum_block_variance() const noexcept {
  // v from fewer second differences is not known well enough to weigh a shape by.
  constexpr std::size_t kMinSecondDifferences = 8;
  // The median of chi-square with 1 degree of freedom: d^2 / (6 v)'s, for d ~ N(0, 6 v).
  constexpr double kChiSquare1Median = 0.45493642311957283;
  if (sum_block_d2_count_ < kMinSecondDifferences) return std::nullopt;
  std::array<double, generic::LevelHistory::kCapacity> d2 = sum_block_d2_;
  const auto middle = d2.begin() + static_cast<std::ptrdiff_t>(sum_block_d2_count_ / 2);
  std::nth_element(d2.begin(), middle, d2.begin() + static_cast<std::ptrdiff_t>(sum_block_d2_count_));
  return *middle / (6.0 * kChiSquare1Median);
}

void ContactForceFdi::raise_still_load_fault(Channel& c, double implied_load, double t) noexcept {
  // Beside another flagged channel nothing is raised: a drift raised there could not be judged
  // at its plateau (the stance comparison holds a plateau only as the one correction), and its
  // extrapolated slope would run away; and that channel's correction, right or not, is in the
  // residual the blocks read.
  for (const Channel& o : channels_) {
    if (&o != &c && o.type != FaultType::none) return;
  }
  // The sum residual's blocks since the last flag change (a change moves the residual partway
  // through), and the open block: a step a few tenths of a second old has no closed block yet.
  std::array<generic::LevelPoint, generic::LevelHistory::kCapacity + 1> all{};
  std::size_t count = sum_levels_.ordered(all);
  if (sum_block_count_ > 0) {  // its variance as a short block's
    all[count++] = {sum_block_t_sum_ / sum_block_count_, sum_block_sum_ / sum_block_count_,
                    static_cast<double>(sum_block_target_ticks_) / sum_block_count_};
  }
  const double half_block = 0.5 * sum_block_target_ticks_ * period_s_;
  std::size_t first = 0;
  while (first < count && all[first].t_s - half_block < last_flag_change_s_) ++first;
  const std::span<generic::LevelPoint> points(all.data() + first, count - first);
  // Without a measured noise or a healthy level before the fault, nothing is raised: the window
  // restarts and the next one judges (a level taken as healthy at 0 would absorb the total
  // force's bias into the offset).
  const auto v = sum_block_variance();
  if (!v || points.size() < 3) return;
  for (auto& p : points) p.variance *= *v;
  const generic::OnsetShape shape = generic::onset_shape(points, relation_z_);
  if (shape.first_faulty == 0) return;  // no healthy block since the last flag change
  // The fault's size now: the corrected residual's level (a low-pass of time constant clear_s, as
  // the jump test's residual_level_ is) from its healthy level. Its noise: the residual taken as
  // white of the variance that gives a block's mean v (a block's ticks times v per tick;
  // correlated error makes that an upper bound for a short mean), times the low-pass's factor
  // (seeded_low_pass_variance: its first value's remaining weight counted), plus the healthy
  // level's, v at most. A fault the gain test saw in its window but that has ended within its
  // noise is none now: nothing is raised (a drift that came and went while the robot stood).
  const double present_variance =
      *v * (sum_block_target_ticks_ * seeded_low_pass_variance(residual_level_gain_, residual_level_seed_weight_) + 1.0);
  const double present = corrected_level_ - shape.healthy_level;
  const double bound = relation_z_ * std::sqrt(present_variance);
  if (!(std::abs(present) > bound)) return;
  if (shape.ramp) {
    // A drift from where the ramp left the healthy level, sized by its fitted line.
    raise(c, FaultType::drift, t);
    c.onset_load = 0.0;
    c.reads_as_gain = false;
    start_drift_from_levels(c, t, points.subspan(shape.first_faulty), shape.healthy_level, {});
    double level = 0.0, slope = 0.0;
    c.fit.solve(level, slope);
    c.offset = level;
    c.slope = slope;
    c.still_load_drift = true;
    c.still_load_healthy_level = shape.healthy_level;
    return;
  }
  // A step: an offset of its size now, from the load it had, told from a gain as any jump's.
  raise_jump_onset(c, present, implied_load + shape.healthy_level, t);
}

double ContactForceFdi::plateau_bar(const Channel& c, int ticks) const noexcept {
  if (!c.still_load_drift) return params_.gain_min_load_N;
  // The mean of `ticks` residuals, as a white residual's of the variance that gives a block's mean
  // v (v at least: a longer mean of a correlated error need not scatter less), and the healthy
  // level's, v: beyond z of that, within gain_min_load_N at most.
  const auto v = sum_block_variance();
  if (!v) return params_.gain_min_load_N;
  const double block_ratio = static_cast<double>(sum_block_target_ticks_) / std::max(ticks, 1);
  const double variance = *v * (std::max(1.0, block_ratio) + 1.0);
  return std::min(params_.gain_min_load_N, relation_z_ * std::sqrt(variance));
}

void ContactForceFdi::hold_as_offset(Channel& c, double level) noexcept {
  c.still_load_drift = false;
  c.type = FaultType::offset;
  c.offset = level;
  c.slope = 0.0;
  c.fit.clear(last_tick_s_);
  c.air_refit = c.fit_has_air;  // the air's next reading fits afresh, not on the drift's swings
  c.end_pending = false;        // an end judged by the drift's size: the next step is judged anew
}

void ContactForceFdi::restart_gain_window() noexcept {
  std::fill(joint_gain_set_.begin(), joint_gain_set_.end(), 0);
  joint_raw_rr_ = joint_held_rr_ = 0.0;
  joint_gain_ticks_ = 0;
  gain_window_.restart();
  std::fill(gain_raw_rr_.begin(), gain_raw_rr_.end(), 0.0);
  std::fill(gain_held_rr_.begin(), gain_held_rr_.end(), 0.0);
  std::fill(gain_held_ticks_.begin(), gain_held_ticks_.end(), 0);
  std::fill(stance_powers_.begin(), stance_powers_.end(), StancePowers{});
  std::fill(stance_cusum_.begin(), stance_cusum_.end(), StancePowers{});
  std::fill(guard_powers_.begin(), guard_powers_.end(), StancePowers{});
}

}  // namespace ftsense::biped
