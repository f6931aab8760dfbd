#pragma once
// Isolation of a sensor fault that begins (or ends) as a step, by the one channel whose reading
// and own residual row stepped together while what the relation says it should read did not
// (analytical redundancy in time: a step, not a level, tells loaded channels apart).
//
// Model. Channel j reads x_j and has one residual row r_j that its reading enters one for one
// (d r_j / d x_j = 1: sum_constraint_residual's rows, whose loaded rows are all the group's sum
// residual; a leave-one-out fit's residual). v_j = x_j - r_j is then what the relation says x_j
// should read (its virtual sensor). A fault that starts as a step b at tick t (an offset, a gain
// or a sign flip on a loaded channel, a spike's edge) moves x_j within one tick and r_j with it,
// and leaves v_j; a load that moves between channels moves each x_i with its v_i and leaves the
// sum; a reference that steps moves every r_i and v_i of its rows, no reading. So, with
// W = step_window_ticks(T) = round(10 ms / T) and the window step of a signal s at tick n
//
//   D s(n) = mean(s[n-W+1 .. n]) - mean(s[n-2W+1 .. n-W]),     t = n - W + 1 the step's tick,
//
//   jumped     e_j = x_j(t) - 2 x_j(t-1) + x_j(t-2),  |e_j| > z sqrt(6 sigma_j^2 + q_j^2 / 2)
//              (its second difference beyond white noise sigma_j and quantisation q_j), and by
//              what its row stepped: |e_j - D r_j(n)| <= z sqrt(6 sigma_j^2 + q_j^2 / 2 + s_r,j^2)
//              (a spike of a few ticks jumps by W / width times what the window's mean moves;
//              the bound adds the two variances as if independent, though e_j and D r_j share
//              the step's tick: at W <= 2 the bound is a little loose, which only lets a short
//              spike pass more easily to the other rules)
//   stepped    |D r_i(n)| > z s_r,i                     (row i moved: R, the rows that did)
//   cost       c_i = (D v_i(n) / s_v,i)^2               (how far i's virtual sensor moved)
//
// channel j is named, with step b = D r_j(n), when j is in R, jumped, costs the least of R with
// c_j <= z^2, and every other row of R costs at least c_j + z^2 (told apart as surely as the
// false-alarm target asks: the margin chi^2_1(1 - alpha) = z^2 of signature_isolator.hpp).
// z = Phi^-1(1 - alpha / 2), alpha = T / false_alarm_interval_s; s_r and s_v are the fault-free
// window steps of r and of x - r (window_step_noise.hpp, measured by `ftsense calibrate`). A row
// is judged only on ticks whose last max(2W, W + 2) samples of x and r are finite and unguarded
// (input `guard` nonzero: a landing's transient, which moves readings and the reference within
// a tick as no model of them says), and a channel named within the last W ticks is not named
// again (the jump's second difference returns -b one tick later).
//
// Verdict. A named channel is blamed when its step takes its row away from zero (|mean r after| >
// |mean r before|: a step towards zero ends a fault nobody named, or another channel's, and
// begins none; a new fault against a larger unnamed one is missed rather than a healthy channel
// blamed; zero is taken as the row's fault-free level, so a row with a calibrated centre c misses
// a step towards zero smaller than 2 |c|, and a step against a fault already named on the same
// row, which also takes it towards zero, is missed too), and when its row's detector was down
// on the tick before the step or some channel is
// blamed here (a row raised with no named cause holds a fault nobody can place: a step may begin
// a second fault or end that one, and the signature isolator judges it; with `judge_raised_rows`
// that rule is off, for rows of readings corrected for the faults already found, whose level is
// then their fault-free one whatever the alarm says); the steps named on it
// add up to its size b_j (output fault_estimate). It is re-admitted when
//   - a step named on it brings b_j back within z sqrt(2) s_r,j (the fault ended as it began);
//   - the detector on its row (input `alarm`, e.g. a cusum_detector on r) falls after it rose:
//     the residual no longer holds a fault;
//   - that detector has not risen within confirm_s of the naming: no lasting change followed
//     the step (a transient), so nothing is held on one step's word.
// A step inside a guard (`guard_step_std` s_g > 0, calibrated as how much a fault-free row moves
// across a guard: guard_step_noise.hpp) is judged once the guard is over. Inside it, loads move
// fast (a landing foot rolls onto its pads), so a row's cost tells less than the tick's jump, and
// the candidate is not the least costly row but the one row whose windows hold a guarded tick, with
// c_j <= z^2 and a jump that matches its step (`jumped` above), when no other row within that
// cost bound matches, no other reading's second difference exceeds its jump bound on the step's
// tick or the next (nor lacks a value there: a foot's pads that jump together are its load
// shifting, which leaves no one jump to judge; at W = 1 only the step's tick is seen), and the
// channel is not blamed. The latest candidate of a row wins; a new guard drops one still pending.
// Once W unguarded ticks have followed (input guard 0), its row's move,
//
//   Delta = mean(r[n-W+1 .. n]) - mean(r over the W usable ticks before the guard began)
//           (for a step on one of the W - 1 ticks before the guard began, whose windows complete
//           inside it: less mean(r over the W ticks before the step) instead),
//
// must be beyond the guards' own, |Delta| > z s_g, and be the jump: |Delta - e_j| <= min(z sqrt(6
// sigma_j^2 + q_j^2 / 2 + s_g^2), |e_j| / 2) (a move twice the jump holds something else too, a
// second fault's onset or a gain's load, which the z bound alone lets pass when s_g is large).
// The landing's transient, which the guard hides, moves the row by about s_g and leaves no lasting
// step. The candidate is then blamed with b_j = Delta, under the verdict's rules (above: away from
// zero, the row's detector down on the tick before the step, or some channel blamed here). With
// s_g = 0 (the default) a step inside a guard is not judged. With input `correction`
// (the corrections the rows' readings carry, e.g. the recovery's of the tick before), a channel
// whose reading is corrected (nonzero or NaN) is not blamed by a step: its row holds a fault
// already found, and its step is that fault changing or ending (a drift's end steps a corrected
// row away from zero), which the part that found it judges.
//
// Known limits: two channels that step on one tick leave each other's virtual sensors moving
// (neither is named; the isolator and validators judge them); a step inside a guard without s_g
// is not seen;
// a fault without a step (a drift, a frozen output, a gain begun in the air) is left to the
// signature isolator and the classifier. Units: any; a channel's reading and residual share one.
// Allocation-free: the rings are sized at construction; a tick costs O(n W).

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/calibration.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class StepIsolator {
 public:
  static constexpr std::string_view name = "step_isolator";
  static constexpr std::string_view summary =
      "blames the channel whose reading and own residual stepped while its virtual sensor did not";
  // For the config reference's port table and the schema (plugin.hpp): input guard is optional.
  static constexpr std::string_view example_params = R"([{}, {"guard": true, "correction": true}])";

  // `ftsense calibrate` measures each reading's white noise and quantisation step, and the
  // fault-free window steps of each residual row and of each virtual sensor x - r.
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
      {"residual_step_std", "residual", FaultFreeStatistic::window_step},
      {"virtual_step_std", "signal", FaultFreeStatistic::window_step, "residual"},
      {"guard_step_std", "residual", FaultFreeStatistic::guard_step, {}, "guard"},
  });

  struct Params {
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    std::vector<double> residual_step_std{1.0};
    std::vector<double> virtual_step_std{1.0};
    std::vector<double> guard_step_std{0.0};
    double false_alarm_interval_s = 86400.0;
    double confirm_s = 0.5;
    bool guard = false;
    bool judge_raised_rows = false;
    bool correction = false;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kSignal, kResidual, kAlarm, kGuard, kCorrection };
  enum Output : std::size_t { kFault, kFaultType, kFaultEstimate };

  StepIsolator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  [[nodiscard]] std::size_t window_ticks() const noexcept { return window_; }
  // z of the header.
  [[nodiscard]] double z() const noexcept { return z_; }

 private:
  void release(std::size_t j) noexcept;

  Ports ports_;
  bool guard_wired_;
  bool correction_wired_;
  bool judge_raised_rows_;
  std::size_t window_;       // W
  std::size_t span_;         // max(2W, W + 2): the samples a judgement rests on
  std::size_t confirm_ticks_;
  double z_;
  std::vector<double> jump_bound_;      // z sqrt(6 sigma^2 + q^2 / 2), per channel
  std::vector<double> jump_match_bound_;  // z sqrt(6 sigma^2 + q^2 / 2 + s_r^2)
  std::vector<double> residual_bound_;  // z s_r
  std::vector<double> release_bound_;   // z sqrt(2) s_r
  std::vector<double> inv_virtual_step_;
  // Steps inside a guard (the header's s_g > 0 on some row).
  bool judge_in_guard_ = false;
  std::vector<double> guard_bar_;          // z s_g (infinite where s_g = 0: not judged)
  std::vector<double> guard_match_bound_;  // z sqrt(6 sigma^2 + q^2 / 2 + s_g^2)
  std::vector<std::size_t> finite_run_;    // ticks in a row with x, r finite, guarded or not, up to span_
  std::vector<char> was_guarded_;          // the guard on the tick before
  std::vector<double> guard_before_;       // the row's mean over the W usable ticks before the guard (NaN: unknown)
  std::vector<char> pending_;              // a candidate named inside the guard, to judge after it
  std::vector<char> pending_raised_;       // its row's alarm on the tick before its step
  std::vector<double> pending_jump_;       // its jump e_j
  std::vector<double> pending_before_;     // the row's level its move is measured from
  std::vector<std::size_t> guard_age_;     // ticks since the present (or last) guard began, up to span_
  std::vector<double> level_before_;       // work: mean(r[n-2W+1 .. n-W])
  // Rings of span_ ticks, channel-major: reading and residual.
  std::vector<double> x_ring_, r_ring_;
  std::vector<char> raised_ring_;  // the alarm on each row, 1 raised
  std::size_t next_ = 0;                  // the ring slot this tick writes
  std::vector<std::size_t> usable_run_;   // ticks in a row with x, r finite and unguarded, up to span_
  std::vector<std::size_t> since_named_;  // ticks since the channel was last named, up to window_
  std::vector<char> blamed_, alarm_seen_;
  std::vector<double> size_;
  std::vector<std::size_t> age_;
  std::vector<double> step_, cost_;  // work: this tick's D r and c per channel (NaN: not judged)
  std::vector<double> level_;        // work: mean(r[n-W+1 .. n])
};

}  // namespace ftsense::generic
