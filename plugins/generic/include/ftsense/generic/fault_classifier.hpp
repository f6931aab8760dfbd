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
// `history_s` seconds of blocks are kept. A fault that starts at block i0 makes the blocks i >= i0 follow one of
//
//   offset   e_i = b                      (y = x + b)
//   drift    e_i = s (t_i - t_i0)         (y = x + s (t - t0))
//   gain     e_i = (k - 1) v_i            (y = k x)
//   frozen   x_i = c                      (y = c: also a dead output, c = 0, and saturation)
//
// and e_i = 0 before i0. Each model is fitted by least squares over the blocks since the channel
// was last re-admitted, with its onset i0 searched over every block up to the one where the
// channel was first flagged (input `fault`, e.g. from signature_isolator); RSS_m is what the
// best fit leaves, sum over blocks of the squared misfit in e. With block means of noise density
// q, (RSS_m - RSS_best) block_s / q^2 is the log-likelihood ratio 2 ln(L_best / L_m) of the two
// fits; every model has two free parameters (its size and onset), so the best one is named when
// each other model leaves at least chi^2_1(confidence) more:
//
//   LR_m = (RSS_m - RSS_best) block_s / q^2 >= chi^2_1(confidence)     for every m != best.
//
// The margin is a heuristic, not a calibrated confidence: the models are not nested, each onset
// is the best of many, and a reference error that repeats with the gait (measured out of q,
// whose windows average it away) stays in the block means, where a model may fit part of it.
// Until then the type is unclassified. A named type stays while the channel is flagged unless
// another model overtakes it by the same margin. An episode ends when the flag drops (the channel
// is re-admitted) and stays down `same_episode_s`; a flag back sooner continues it (a detector's
// chatter does not throw the evidence away), a later one starts a new fit after the re-admission. A gain whose k is within its own uncertainty of
// 0 (|k| < sqrt(chi^2_1(confidence)) q / sqrt(block_s sum v_i^2)) is the frozen-at-zero
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
  static constexpr std::string_view example_params = R"({"residual_noise_density": [1.0]})";

  // `ftsense calibrate` measures the noise density of the fault-free measured - virtual.
  // [snippet:calibrated_params]
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"residual_noise_density", "measured", FaultFreeStatistic::noise_density, "virtual"},
  });
  // [end-snippet]

  struct Params {
    std::vector<double> residual_noise_density{1.0};
    double block_s = 0.1;
    double history_s = 30.0;
    double same_episode_s = 1.0;
    double confidence = 0.999;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kFault, kMeasured, kVirtual };
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
  std::vector<double> weight_;  // 1 / q^2 per channel, times block_s
  // Block history, channel-major rings: [channel * capacity + (block % capacity)].
  std::vector<double> block_x_, block_v_;
  std::vector<double> block_time_;  // mean tick time of block % capacity (shared by all channels)
  long blocks_ = 0;                 // blocks completed
  int tick_in_block_ = 0;
  double block_time_sum_ = 0.0;     // sum of the tick times of the block being filled
  std::vector<Channel> channels_;
};

}  // namespace ftsense::generic
