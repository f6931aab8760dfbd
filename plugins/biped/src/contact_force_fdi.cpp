// The biped robust detector's construction and its tick: the evidence loop whose tests (jump,
// frozen, noise, airborne, sum residual) share each channel's state tick by tick, the decisions
// and the recovery. The tests that are functions of their own live beside it, one file per
// concept (contact_force_fdi_gain, _still_reading, _unread_load, _onset_shape, _plane_jumps);
// the class's state is one (contact_force_fdi.hpp). Issue 13 replaces it with the generic FDI
// layer (signal validators, constraint residuals, change detection, classification, recovery).
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

}  // namespace ftsense::biped
