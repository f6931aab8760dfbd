#pragma once
// Classification of an isolated fault by fitting the fault models to the channel's recent
// history, onset included (method.md section 4, generic over channels and units).
//
// Model. Channel j reads x (input `measured`) and has a reference v (input `virtual`: a virtual
// sensor's estimate of the same quantity), e = x - v. On fault-free data e is zero-mean with
// low-frequency noise density q_j (`residual_noise_density`, unit sqrt(s): the mean of e over a
// window of w seconds has standard deviation q / sqrt(w); for white noise of standard deviation
// sigma sampled every T seconds, q = sigma sqrt(T)). Samples are averaged into blocks of
// `block_s` seconds (x_i, v_i, e_i at t_i, the mean tick time of the block) and the last
// `history_s` seconds of blocks are kept. A fault that starts within block i0 makes the blocks
// i > i0 follow one of
//
//   offset   e_i = b                      (y = x + b)
//   drift    e_i = s (t_i - t_i0)         (y = x + s (t - t0))
//   gain     e_i = (k - 1) v_i            (y = k x)
//   frozen   x_i = c                      (y = c: also a dead output, c = 0, and saturation)
//
// and e_i = 0 before i0; block i0 holds the fault for an unknown share of its ticks (a step there
// makes its mean a ramp's first point), so no model is asked to explain it, and of two onsets
// that fit alike the later is kept. Each model is fitted by weighted least squares over the blocks since the
// channel was last re-admitted, with its onset i0 searched over every block up to the one where
// the channel was first flagged (input `fault`, e.g. from signature_isolator); RSS_m is what the
// best fit leaves, sum over blocks of w_i times the squared misfit in e, with w_i = 1 / Var(e_i)
// the block mean's weight. Some references are exact on some ticks: a channel that carries no
// load reads zero, up to the sensor's own noise. With input `exact_residual` wired (x - v_e,
// finite on those ticks: unloaded_reading_residual), v_e stands in for v on them, and a block of
// n finite ticks, n_e of them exact, has
//
//   Var(e_i) = (n_r q^2 / T + n_e s_e^2) / n^2,     n_r = n - n_e, T the sample period,
//   s_e^2    = max(q_e^2 / T, the sample variance of the block's exact residuals)  (n_e >= 2),
//
// q_e the low-frequency noise density of the fault-free exact residual (`exact_noise_density`;
// for white noise of deviation sigma, q_e = sigma sqrt(T)); without it, or with n_e = 0, w_i =
// n T / q^2 (= block_s / q^2 for a whole block). A block whose exact samples spread more than
// the sensor's noise (a noise burst, spikes, a gain that scales the noise) weighs as its own
// spread, so a disturbance no model describes does not name one of them by its sheer weight.
// A foot's pad in swing thus weighs as its noise
// (a 2 N sensor at 1 kHz: about 3000 times a stance block, whose reference carries the total
// force's error): where a fault passes through the air, its air levels decide its type and size
// (an offset's constant level, a drift's ramp, a gain's zero). (RSS_m - RSS_best) is the
// log-likelihood ratio 2 ln(L_best / L_m) of the two fits; every model has two free parameters
// (its size and onset), so the best one is named when each other model leaves at least
// chi^2_1(confidence) more:
//
//   LR_m = RSS_m - RSS_best >= chi^2_1(confidence)     for every m != best.
//
// The margin is a heuristic, not a calibrated confidence: the models are not nested, each onset
// is the best of many, and a reference error that repeats with the gait (measured out of q,
// whose windows average it away) stays in the block means, where a model may fit part of it.
// Until then the type is unclassified. A named type stays while the channel is flagged unless
// another model overtakes it by the same margin; where another fits better by that margin but
// none stands apart yet (an offset and a frozen output, alike on a reading stuck in the air), the
// named type is refuted and the channel is unclassified again. An episode ends when the flag drops (the channel
// is re-admitted) and stays down `same_episode_s`; a flag back sooner continues it (a detector's
// chatter does not throw the evidence away), a later one starts a new fit after the re-admission. A gain whose k is within its own uncertainty of
// 0 (|k| < sqrt(chi^2_1(confidence) / sum w_i v_i^2)) is the frozen-at-zero
// explanation, not a competitor of frozen; a gain so named is reported frozen. Noise bursts,
// spikes, invalid values and saturation at a known range are what the signal validators judge
// from the raw samples; block means hide them, so this part does not name them.
//
// Outputs per channel while flagged: fault_type (the code of the named model, unclassified
// before), fault_estimate in x's unit: b (offset), s (t - t0) (drift), x (1 - 1/k) (gain, so that
// x - estimate = x / k), x - v (frozen and unclassified: the recovered value is the reference).
// Both are none / 0 while the channel is not flagged.
//
// Cost: O(1) per tick, plus the fits: O(history_s / block_s) per flagged channel and block (the
// onset search runs over suffix sums), spread over the block's ticks, at most ceil(channels /
// ticks per block) on one tick, so a fit lands within a block of the data it uses.
// Allocation-free: the block history is sized at construction.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/fault_type.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class FaultClassifier {
 public:
  static constexpr std::string_view name = "fault_classifier";
  static constexpr std::string_view summary =
      "names a flagged channel's fault (offset, drift, gain, frozen) by fitting each model and its onset";
  static constexpr std::string_view example_params =
      R"([{"residual_noise_density": [1.0]}, {"residual_noise_density": [1.0], "exact_residual": true}])";

  // `ftsense calibrate` measures the noise density of the fault-free measured - virtual.
  // [snippet:calibrated_params]
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"residual_noise_density", "measured", FaultFreeStatistic::noise_density, "virtual"},
      {"exact_noise_density", "exact_residual", FaultFreeStatistic::noise_density},
  });
  // [end-snippet]

  struct Params {
    std::vector<double> residual_noise_density{1.0};
    bool exact_residual = false;
    std::vector<double> exact_noise_density{1.0};
    double block_s = 0.1;
    double history_s = 30.0;
    double same_episode_s = 1.0;
    double confidence = 0.999;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kFault, kMeasured, kVirtual, kExactResidual };
  enum Output : std::size_t { kFaultType, kFaultEstimate };

  // The fitted explanation of one channel's history (exposed for tests and reports).
  struct Fit {
    FaultType type = FaultType::unclassified;  // the named model, unclassified while undecided
    double size = 0.0;      // b [unit], s [unit/s], k [1] or c [unit] of the named model
    double onset_s = 0.0;   // t0: the onset block's time (its mean tick time)
  };

  FaultClassifier(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  [[nodiscard]] const Fit& fit(std::size_t channel) const noexcept { return channels_[channel].fit; }
  // chi^2_1(confidence): how much more every other model must leave.
  [[nodiscard]] double margin() const noexcept { return margin_; }

 private:
  struct Channel {
    // The block being filled.
    double sum_x = 0.0, sum_v = 0.0;
    int count = 0;
    int exact_count = 0;  // of which the exact reference's
    double sum_exact = 0.0, sum_exact2 = 0.0;  // their exact residuals and its squares
    bool flagged_in_block = false;
    // The window of the fit: from the first block after the last re-admission.
    long window_start = 0;
    long first_flagged = -1;  // block index of the episode's first flagged block, -1: none yet
    long cleared_at = -1;     // block in which the flag last dropped
    bool flagged = false;
    bool due = false;  // a block ended while flagged: its fit is waiting for its tick
    Fit fit;
  };
  void classify(std::size_t channel) noexcept;

  Ports ports_;
  std::size_t channels_count_;
  int ticks_per_block_;
  double block_s_;
  std::size_t capacity_;  // blocks kept
  long same_episode_blocks_;
  std::size_t fits_per_tick_;  // ceil(channels / ticks per block)
  std::size_t next_due_ = 0;   // where the round over the due channels goes on
  double margin_;
  bool exact_wired_;
  double sample_period_s_;
  std::vector<double> density2_, exact_density2_;  // q^2 and q_e^2 per channel
  // Block history, channel-major rings: [channel * capacity + (block % capacity)]; w is the
  // block's weight 1 / Var(mean e).
  std::vector<double> block_x_, block_v_, block_w_;
  std::vector<double> block_time_;  // mean tick time of block % capacity (shared by all channels)
  long blocks_ = 0;                 // blocks completed
  int tick_in_block_ = 0;
  double block_time_sum_ = 0.0;     // sum of the tick times of the block being filled
  std::vector<Channel> channels_;
};

}  // namespace ftsense::generic
