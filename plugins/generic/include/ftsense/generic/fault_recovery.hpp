#pragma once
// Recovery: the signal to hand downstream, per channel j (method.md section 5).
//
//   recovered_j = measured_j - fault_estimate_j       (offset, drift: the paper's N_meas - eta_hat)
//   recovered_j = virtual_j                           when the channel's fault type is one of
//                                                     `substitute_types` (default: frozen,
//                                                     invalid), or measured_j is not finite
//                                                     (a fault_type value that is not one of
//                                                     fault_type.hpp's codes counts as invalid)
//   recovered_j = virtual_j + LP(measured_j - virtual_j)   when the type is one of `blend_types`
//                                                     (default: none; a noise burst)
//   recovered_j = max(measured_j, the value above)    when the type is also one of
//                                                     `lower_bound_types` (default: none;
//                                                     saturation at the top of a range: the
//                                                     true value is at least the clipped
//                                                     reading, and where the reading is the
//                                                     larger it stands for itself, not
//                                                     substituted: a relation's other channels
//                                                     take that bound, which a virtual value
//                                                     that cannot part two unknowns lacks).
//                                                     List a type here only where it means the
//                                                     top of the range: a clip at the bottom
//                                                     bounds from above, and signal_validator
//                                                     also types saturation a reading stuck
//                                                     twice at one value (its clip rule)
//   recovered_j = median(x_t, x_{t-1}, x_{t-2})       when the type is one of `median_types`
//                                                     (default: none; spikes), the last three
//                                                     finite readings in a row (a gap restarts
//                                                     them: until two more, the reading itself)
//
// Why the median for spikes: between its spikes the reading is the sensor's own, better than any
// virtual value; a spike is one reading off both neighbours, and the median of three drops it on
// its own tick (while the detector, which needs the next reading, sees it one tick late, so the
// channel must already be flagged: signal_validator holds the flag through a spike episode). On a
// ramp the median lags by one tick, two next to a spike.
// LP is a first-order low-pass at blend_cutoff_hz [Hz] (low_pass.hpp's recursion), run on every
// tick where both values are finite, so at a fault's onset it holds the fault-free difference.
// Why: a noise burst's reading still carries the load, but a low-pass of it lags a walking load
// (at 10 Hz, 15.9 ms of a 3 N-per-tick ramp is 48 N), and the virtual value alone carries its own
// error. The virtual value carries the load's fast moves; the low-pass of the difference keeps what
// the virtual value misses (its error below f_c) and passes the noise reduced to
// sqrt(a / (2 - a)) of its RMS (white noise, a the smoothing factor: a = 0.061 and the factor
// 0.18 at 10 Hz and 1 kHz; 0.27 and 0.39 at 200 Hz). Neither mode uses fault_estimate: a blended
// or median channel's recovery is its own reading's, not the classifier's estimate.
// With correction = "when_flagged", measured_j passes through unchanged while fault_j = 0.
//
// Output `correction`: what a relation's other channels subtract from this reading
// (sum_constraint_residual's input `correction`, read one tick late through previous_tick), so
// that a corrected fault leaves their virtual values:
//   c_j = measured_j - recovered_j   where the recovered value is the reading less an offset,
//                                    drift or gain estimate (a correction that lasts);
//   0                                else (healthy, blended, median: the reading as it is;
//                                    substituted: see below).
// Output `substituted`: 1 where the recovered value is the virtual one (substituted, a fallback
// on it, or fault_classifier's x - v for a fault not yet named): the reading stands for nothing,
// and the relation's other channels cannot be judged by it while it carries load
// (sum_constraint_residual's input `substituted`, one tick late).
// Not x - v: the virtual value v_j is the others' readings, and fed back it would give each of
// them its own reading as its virtual value. Not a median's x - median: that is its own tick's
// spike, and read a tick late it would put the spike into the others' virtual values on the tick
// after. (Both were seen on an unseen walk, each flagging a healthy neighbour.)
// `recovered` is never NaN: if the chosen value is not finite, the other one is used, and if
// neither is, the last recovered value is held.
// Bounded by the physics: while a channel is flagged its recovered value is held within
// [floor_j, ceiling_j] (`floor`, `ceiling`: what the measured quantity can take, e.g. 0 N for a
// pad that is pressed, never pulled; either may be left out), whichever way it was recovered (a
// fallback on a reading below the floor, a correction that overshoots it, a virtual value that
// does). A channel not flagged passes its reading unchanged, noise and all. The output
// `correction` is the model's (measured - the unbounded value): a bound is no fault estimate.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/fault_type.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class FaultRecovery {
 public:
  static constexpr std::string_view name = "fault_recovery";
  static constexpr std::string_view summary =
      "recovered = measured - fault estimate, the virtual value (frozen, invalid), or the virtual "
      "value plus a low-pass of measured - virtual (blend_types), or the median of the last three "
      "readings (median_types)";

  enum class Correction { always, when_flagged };

  struct Params {
    Correction correction = Correction::always;
    std::vector<std::string> substitute_types{std::string(to_string(FaultType::frozen)),
                                              std::string(to_string(FaultType::invalid))};
    std::vector<std::string> blend_types;
    std::vector<std::string> median_types;
    std::vector<std::string> lower_bound_types;
    double blend_cutoff_hz = 10.0;
    std::vector<double> floor{};
    std::vector<double> ceiling{};
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kMeasured, kFaultEstimate, kVirtual, kFault, kFaultType };
  enum Output : std::size_t { kRecovered, kCorrection, kSubstituted };

  FaultRecovery(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  // How a channel flagged with a type is recovered (the type lists, one mode per type).
  enum class Mode : unsigned char { correct, substitute, blend, median };

  Ports ports_;
  Correction correction_;
  std::array<Mode, kFaultTypes.size()> mode_by_type_{};  // indexed by the type's code
  std::array<bool, kFaultTypes.size()> lower_bound_{};   // the reading bounds the value from below
  double blend_gain_ = 0.0;                   // a = 1 - exp(-2 pi f_c T)
  std::vector<double> difference_lp_;         // LP(measured - virtual), per channel
  std::vector<unsigned char> difference_seen_;  // a finite difference has initialised the LP
  std::vector<std::array<double, 2>> previous_readings_;  // x_{t-1}, x_{t-2} (finite ones)
  std::vector<unsigned char> previous_count_;             // how many of them are set, up to 2
  std::vector<double> last_;
  std::vector<double> floor_, ceiling_;  // per channel; -inf, +inf: none
};

}  // namespace ftsense::generic
