#pragma once
// Per-channel threshold detector (paper eq. 33):
//
//   fault_j = 1  when |s_j - c_j| > tr_j has held for on_delay_s,
//   fault_j = 0  again when |s_j - c_j| <= tr_j has held for off_delay_s.
//
// s is the evaluated signal (typically the low-passed fault estimate), tr_j > 0 in the unit of s,
// c_j the centre of channel j's fault-free band (default 0: the paper's |s_j| > tr_j). A virtual
// sensor with a systematic per-channel bias leaves the fault-free s_j in a band [lo_j, hi_j] that
// is not centred on 0; `ftsense calibrate --band` sets c_j = (lo_j + hi_j) / 2 and
// tr_j = margin (hi_j - lo_j) / 2, so a fault of either sign is judged against the same margin.
// The threshold cannot tell fault types apart, so a raised flag has type code 1 (unclassified);
// a non-finite s_j raises the flag at once with type code 8 (invalid). During the first
// `warmup_s` seconds after reset (the estimators' initialisation transient) no threshold flag is
// raised; invalid values are still flagged.
//
// With `check_measured`, the detector also reads the monitored sensor itself (input `measured`):
// a NaN or Inf reading flags its channel invalid (8) on that very tick, whatever s says (a fault
// filter holds its estimate on such a tick, so s alone would never show it).

#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class ThresholdDetector {
 public:
  static constexpr std::string_view name = "threshold_detector";
  static constexpr std::string_view summary =
      "fault when |signal| > threshold (paper eq. 33), with optional on/off delays";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"({"thresholds": [100.0], "warmup_s": 2.0, "check_measured": true})";

  struct Params {
    std::vector<double> thresholds{1.0};
    std::vector<double> centers{0.0};
    double on_delay_s = 0.0;
    double off_delay_s = 0.0;
    double warmup_s = 0.0;
    bool check_measured = false;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kSignal, kMeasured };
  enum Output : std::size_t { kFault, kFaultType };

  ThresholdDetector(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  std::vector<double> thresholds_;
  std::vector<double> centers_;
  double sample_period_s_;
  double on_delay_s_;
  double off_delay_s_;
  double warmup_s_;
  double start_time_s_ = 0.0;
  bool started_ = false;
  bool check_measured_ = false;
  std::vector<double> above_for_s_;
  std::vector<double> below_for_s_;
  std::vector<unsigned char> raised_;
};

}  // namespace ftsense::generic
