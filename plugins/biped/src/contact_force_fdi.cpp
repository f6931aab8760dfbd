// The biped robust detector's construction and its tick: `step` calls the tick's phases in order
// (observe_evidence, judge_jump_groups, decide_channels, recover), then computes the virtual
// sensor, runs the tests that need this tick's corrected sum residual and writes the outputs.
// Each phase and each test that judges a stance or more lives in a file of its own beside this
// one: contact_force_fdi_evidence, _jump_groups, _channel_decisions, _recovery, _still_reading,
// _unread_load, _onset_shape, _gain and _plane_jumps; the class's state is one
// (contact_force_fdi.hpp). Issue 13 replaces it with the generic FDI layer (signal validators,
// constraint residuals, change detection, classification, recovery).
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>

#include "contact_force_fdi_detail.hpp"
#include "ftsense/biped/frames.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/generic/level_run.hpp"
#include "ftsense/generic/median_of_three.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

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
    const double alpha = std::min(0.5, context.sample_period_s() / params.false_alarm_interval_s);
    const double run = generic::healthy_level_run_ticks(params.resolution_N, params.noise_std_N, alpha);
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
  sum_gain_ = -std::expm1(-2.0 * 3.141592653589793 * params_.sum_cutoff_hz * period_s_);
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
  unmeasured_ = generic::UnmeasuredContactLoads(params.points, feet_points_, feet_);
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
  ticks_since_ceiling_ = kCountCap;
  ceiling_read_s_ = -1e300;
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

  // Pad heights from kinematics (unknown, NaN, is taken as on the ground: every test, in this
  // file and the others, compares a height with "greater than").
  const auto height = io.in(kPointHeight);

  // Evidence, channel by channel.
  const TickEvidence ev = observe_evidence(measured, height, fz_ok, ticks_since_start, t);
  // The jump groups, judged once their windows are complete; then the decisions.
  const GroupDecisions groups = judge_jump_groups(measured, height, fz, ev, t);
  decide_channels(measured, height, groups, ev.touching_down, t);

  // Recovery and the leave-one-out virtual sensor.
  const auto fault = io.out(kFault);
  const auto type = io.out(kFaultType);
  const auto fault_estimate = io.out(kFaultEstimate);
  const auto recovered = io.out(kRecovered);
  const auto virtual_force = io.out(kVirtual);
  int unknown_loaded = 0;
  const double known_sum = recover(measured, height, fz, t, recovered, unknown_loaded);
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
    } else if (flagged == 1 && fz_ok && !ev.touching_down && !airborne && std::isfinite(x) &&
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
  if (fz_ok && ev.all_finite_readings && none_flagged) unmeasured_.observe_sum(residual);
  // A substituted channel on the ground takes what the total force leaves: the residual is then 0
  // by construction, no reading of the reference's level or of an unflagged fault.
  observe_sum_block(residual, fz_ok && ev.all_finite_readings && unknown_loaded == 0, none_flagged, t);
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
  if (fz_ok && !ev.touching_down) {
    for (std::size_t j = 0; j < channels_.size(); ++j) {
      offset_or_gain_test(channels_[j], measured[j], height[j] > params_.airborne_height_m, residual);
    }
  }
  still_reading_test(measured, height, residual, fz_ok && ev.all_finite_readings, ev.any_step, t);
  unread_load_test(height, fz_ok && ev.all_finite_readings && std::isfinite(residual), t);
  gain_regression(measured, recovered, height, residual,
                  fz_ok && ev.all_finite_readings && !ev.touching_down && !groups.uncorrected_loaded, t);
  if (fz_ok && ev.all_finite_readings && ev.touching_down && !groups.uncorrected_loaded) {
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
  // Without F_z the residual is unknown, not zero: hold the filter rather than pull it to zero.
  if (fz_ok || !started_) sum_filtered_ = started_ ? sum_filtered_ + sum_gain_ * (residual - sum_filtered_) : residual;
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

}  // namespace ftsense::biped
