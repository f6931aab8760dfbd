#pragma once
// Isolation by the shape a gain gives a shared residual over time.
//
// Channels that share one residual (the pads of a robot on the ground, whose leave-one-out
// residuals are all the group's sum residual) cannot be told apart by the residual's level on
// any tick: a fault of size f on any of them moves it by f. A gain can: it moves the sum residual
// by what its channel reads. With the readings x_i of group G summing to the reference R_G,
//
//   e(t) = sum_{i in G} x_i(t) - R_G(t)          (input `sum_residual`, sum_constraint_residual's)
//
// and channel j reading k times its load L_j from an onset t0 on (x_j = k L_j; k = -1 a sign flip),
//
//   e(t) = c + beta x_j(t) [t >= t0] + n(t),     beta = 1 - 1/k,
//
// c the reference's slow error (and any constant fault of the group: an offset is constant in
// e, whoever carries it), n its noise. The channels of a loaded foot carry loads of different
// shapes over a stance (heel, then toe), so the channel whose reading explains e's course is the
// gain's, where no tick's level could say. Per group, on block means (blocks of b = `block_s`,
// the last `history_s` of them), whenever a block ends while the group's alarm is up (any of its
// channels' input `alarm`), each channel j is fitted with its onset o searched over the blocks
// (least squares with the intercept c):
//
//   GLR_j = max_o [S_ez - S_e S_z / N]^2 / [S_zz - S_z^2 / N] / s^2,    z_b = x_jb [b >= o],
//
// sums over the window's N usable blocks, s^2 = q^2 / b the variance of a block mean of fault-free
// e (q its noise density, `residual_noise_density`, which `ftsense calibrate` measures). Channel j
// is named (output `fault` 1, `fault_type` gain) when all of these hold, with alpha =
// b / false_alarm_interval_s (one decision per block) and m = chi^2_1(1 - alpha / (g K)), K the
// onsets searched (the decision takes the best of g K fits: Bonferroni):
//   - GLR_j >= m                  (the gain explains more of e than its noise would by chance);
//   - GLR_j - GLR_i >= m, i != j  (no other channel's reading explains it nearly as well: the
//                                  runner-up, as signature_isolator's margin);
//   - GLR_j - GLR_0 >= m          (GLR_0 the best of a step and a ramp from an onset, fitted the
//                                  same way: an offset's or a drift's course, nobody's gain);
//   - SSE_j / s^2 <= chi^2_{N-3}(1 - alpha)  (what the fit leaves is noise: a drift, a second
//                                  fault or a gain that ended leaves more, and nobody is named);
//   - the onset leaves at least `min_fault_s` of blocks after it (a fit on one or two blocks
//                                  would take a reading's noise in the air for a huge gain).
// With `substituted` on (input `substituted`, 1 where a channel's reading stands for nothing:
// fault_recovery's output of that name, one tick late through previous_tick), a channel
// substituted on any tick of a block (frozen, clipped, invalid, not yet typed: its reading is not
// its load) leaves an unknown course in e there, which its neighbours' loads follow: the block is
// left out of the fit. Except where, with `loadable` on, the channel could carry load on none of
// the block's ticks: its load there is zero, so the block is kept with the channel taken at it
// (e_b less its reading's mean x_jb, and x_jb = 0). Why not left out too: a gain's pad in the air
// reads twice its noise, which a detector on the air rows may flag and the recovery substitute on
// a few ticks of every swing, and then no block of its stances was judged; why not kept as read: a
// pad frozen at 200 N reads it through its swings too, a step in e there that a loaded
// neighbour's reading (zero in its own swing) explains as a gain. The channel this part named
// last is kept as it reads: its recovery stands for nothing while it is typed, and its own course
// is the gain's. Where that window names nobody, each channel j that stood for nothing on a block
// of it (flagged by another test and not yet typed: a step found in its stance, so substituted as
// unclassified) is judged once more on the window with its own blocks kept as it reads too (under
// "j's gain", e = c + beta x_j there as anywhere), and named only if it is the best there and
// passes every test below; any other best names nobody. The margin counts these windows' fits
// too (2 g K tries instead of g K).
// With `flagged` on (input `flagged`, 1 where another part isolated a channel on the tick before:
// the merged isolators' flags through previous_tick), the lead over the runner-up channel is
// waived for a best channel on which another part raised its flag (0 -> 1) on the fitted onset's
// block or the next, in time (a step isolator's name at a gain's onset in stance): the lead says
// which channel, and two tests that name the same channel at the same time have said it. A flag
// held since earlier says nothing about this onset. Every other test holds, the lead over a step
// or a ramp too. This part's own names (its `fault` of the tick before) are not another part's
// word. The hold's refutation keeps the margin of one window of fits. Why: co-loaded pads of one
// sole carry alike loads over a stance, so the lead grows a few units a stance (a x0.6 gain found
// by its step on SURALP's gains_bursts was named 3.3 s after its onset), and meanwhile the step
// isolator re-admits the pad when the sum's alarm falls as its foot unloads, which leaves its
// gain uncorrected for whole stances.
// With `loadable` on (input `loadable`, 1 while a channel can carry load, by kinematics), a
// reading stuck while its channel is loaded is ruled out as the cause first: it makes e follow its
// own load (e = x_j(t0) - L_j(t)), which a co-loaded neighbour's reading explains as a gain. So
// nobody is named while another channel's reading, over the blocks after the named onset on which
// it could carry load (min_fault_s of them at least), moved by less than `follow_ratio` of what e
// moved over those blocks (root mean square about the mean of each: signal_validator's follow
// test, on the sum residual).
// The name holds while the group's alarm holds (re-judged at every block's end), and drops with
// it: the detector's state, not this part's, says when the fault is over. With
// `hold_until_refuted` it holds past the alarm's fall, and past a block's judgement that names
// nobody while the alarm is up, until the blocks since show the gain is over: a gain moves e by
// beta x_j, nothing while its pad carries nothing, so the alarm falls with every swing while the
// fault stays, and an unloading stance's blocks may fit no one. On the usable blocks since (none
// of the others standing for nothing), with an intercept each,
//   RSS_0 = sum (e_b - mean e)^2,   RSS_1 = sum (u_b - mean u)^2,   u_b = e_b - beta x_jb,
// beta the one fitted at the last naming, and the name drops when (RSS_1 - RSS_0) / s^2 >= m:
// the gain, had it stayed, would have moved e by the margin, and e did not follow. A pad in the
// air (x_j constant) refutes nothing; a stance where e follows beta x_j raises the alarm again,
// and the group is judged afresh. The name also drops once the pad could carry load (input
// `loadable`; every block without it) over min_fault_s of blocks since the fall with the alarm
// still down: a gain that stayed would have raised it (where a neighbour standing for nothing
// leaves no block to fit, this bounds the hold). A block is usable when
// at least half its ticks have e and every reading of the group finite.
//
// What it is not for: a fault that does not scale with the reading (an offset, a drift, a frozen
// output: the intercept absorbs a constant, and the fit test refuses the others), nor channels
// whose loads keep one shape (then the runner-up ties and nobody is named). It names the channel;
// fault_classifier types the fault and estimates k from the channel's own leave-one-out force.
// Units: any, e and x share one. Allocation-free per tick; the work of a decision, O(N g) per
// group, falls on a block's last tick.

#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "ftsense/calibration.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class GainIsolator {
 public:
  static constexpr std::string_view name = "gain_isolator";
  static constexpr std::string_view summary =
      "names the channel whose reading explains a shared sum residual's course (a gain or a sign flip)";
  // For the config reference's port table and the schema (plugin.hpp): input substituted is optional.
  static constexpr std::string_view example_params =
      R"([{"residual_noise_density": [1.0]}, {"residual_noise_density": [1.0], "substituted": true, "loadable": true, "flagged": true}])";

  // `ftsense calibrate` measures the noise density of the fault-free sum residual.
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"residual_noise_density", "sum_residual", FaultFreeStatistic::noise_density},
  });

  struct Params {
    int group_size = 0;
    std::vector<double> residual_noise_density{1.0};
    double block_s = 0.1;
    double history_s = 3.0;
    double min_fault_s = 0.3;
    double false_alarm_interval_s = 86400.0;
    bool substituted = false;
    bool loadable = false;
    double follow_ratio = 0.25;
    bool hold_until_refuted = false;
    bool flagged = false;
    static void describe(ParamSchema<Params>& schema);
  };

  // Inputs substituted, loadable and flagged follow the three, in that order, when their params are on.
  enum Input : std::size_t { kSignal, kSumResidual, kAlarm, kSubstituted };
  enum Output : std::size_t { kFault, kFaultType };

  GainIsolator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // chi^2_1(1 - alpha): the least GLR, and the least lead over the runner-up.
  [[nodiscard]] double margin() const noexcept { return margin_; }

 private:
  // Block `slot`'s e with the channels that spent it in the air taken at their load there, zero
  // (e less their readings); false when the block is not usable or a channel other than `keep`
  // stood for nothing on it while it could carry load (its course in e is unknown).
  // `candidate` (-1 none) is kept as it reads, as `keep` is.
  [[nodiscard]] bool block_residual(std::size_t group, std::size_t slot, long keep, double& e,
                                    long candidate = -1) const noexcept;
  // Judges group `group` on the window of blocks; returns the named channel (in the group), or -1.
  [[nodiscard]] long judge(std::size_t group) noexcept;
  // One judgement: on the blocks no channel but the one named last and `candidate` stood for
  // nothing on; with a candidate, only it may be named.
  [[nodiscard]] long judge_window(std::size_t group, long candidate) noexcept;
  // Whether a channel other than `named` read still while loaded from the named onset on (over
  // the window's n blocks), by follow_ratio of e's move: a stuck reading could be e's cause.
  [[nodiscard]] bool stuck_neighbour(long named, std::size_t n) const noexcept;
  // With hold_until_refuted: takes the block just completed into the held channel's sums; whether
  // they now refute its gain (header).
  [[nodiscard]] bool held_refuted(std::size_t group, bool alarm_down) noexcept;

  Ports ports_;
  std::size_t channels_ = 0;
  std::size_t group_size_ = 0;
  std::size_t groups_ = 0;
  int ticks_per_block_ = 1;
  std::size_t capacity_ = 0;         // blocks in the window
  std::size_t min_fault_blocks_ = 1;
  double margin_ = 0.0;
  double hold_margin_ = 0.0;  // the hold's refutation: chi^2_1 over one window's fits
  std::vector<double> fit_bound_;    // chi^2_{N-3}(1 - alpha) for N = 0 .. capacity
  std::vector<double> inv_block_var_;  // 1 / s^2 per group
  // The block being filled, per group: sums over its usable ticks.
  std::vector<double> sum_e_, sum_x_;  // groups; channels
  std::vector<int> usable_ticks_;      // groups
  std::vector<char> substituted_now_;  // channels: substituted on a tick of the block being filled
  std::vector<char> unloaded_now_;     // channels: unable to carry load on every tick of it so far
  // What a channel's reading was on a block: its load, nothing while it could carry load, or
  // nothing while it spent the whole block in the air (its load zero there).
  static constexpr char kStoodForSomething = 0, kStoodForNothing = 1, kStoodForNothingInAir = 2;
  int tick_in_block_ = 0;
  // The window: rings of block means, [group * capacity + slot] and [channel * capacity + slot];
  // a slot's usable flag per group.
  std::vector<double> block_e_, block_x_;
  std::vector<char> block_usable_;
  std::vector<char> block_substituted_;  // [channel * capacity + slot]: kStoodFor...
  bool substituted_ = false;
  bool loadable_ = false;
  double follow_ratio_ = 0.25;
  std::size_t substituted_input_ = kSubstituted, loadable_input_ = kSubstituted;
  std::vector<char> loaded_now_;        // channels: loadable on every tick of the block so far
  std::vector<char> block_loaded_;      // [channel * capacity + slot]
  std::vector<char> window_loaded_;     // [j * capacity + n]
  // With `flagged`: another part raised its flag on a tick of the block being filled, per channel;
  // per block [channel * capacity + slot].
  bool flagged_wired_ = false;
  std::size_t flagged_input_ = kSubstituted;
  std::vector<char> flagged_now_, block_flagged_;
  std::vector<char> flagged_before_;  // per channel: the input `flagged` of the tick before (a raise is 0 -> 1)
  std::vector<char> shown_before_;  // per channel: this part's own `fault` of the tick before
  std::vector<std::size_t> onset_;      // per channel of the group judged: its best onset
  std::size_t blocks_ = 0;  // blocks completed
  std::vector<long> named_;  // per group: the named channel in the group, -1 none
  // Per group: the channel last named (its own substituted blocks judge on after a decision
  // named nobody), -1 none yet.
  std::vector<long> last_named_;
  // With hold_until_refuted, per group: the channel named when the alarm fell (-1 none), the
  // gain's beta = 1 - 1/k fitted at its last naming, and sums over the usable blocks since the
  // alarm fell of e and u = e - beta x_j (n, sum e, sum e^2, sum u, sum u^2).
  bool hold_ = false;
  std::vector<long> held_;
  std::vector<double> beta_;
  std::vector<double> held_n_, held_e_, held_ee_, held_u_, held_uu_;
  std::vector<std::size_t> held_loaded_blocks_;  // per group: blocks since the fall the held pad could carry load
  // Scratch for a decision (sized once): the window's usable blocks in order.
  std::vector<double> window_e_, window_t_, window_x_;
};

}  // namespace ftsense::generic
