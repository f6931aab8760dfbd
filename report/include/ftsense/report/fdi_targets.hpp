#pragma once
// The targets a fault detection is held to, checked on scored runs (their metrics.json), with
// every miss listed by its measured value: the shortfall a report shows rather than hides.
//
// The defaults are issue 13's acceptance 2, for force sensors in newtons:
//   - offsets of at least offset_min (40 N) and frozen channels: detected within detect_loaded_s
//     (0.25 s) of loaded time (metrics.hpp: loaded delay, the time in contact from the onset);
//   - drifts within the earlier limits: a drift of at least 15 N/s within 2 s, one of at least
//     5 N/s within 5 s (the first limit whose rate the drift's |slope| reaches; slower drifts
//     have none and are not checked);
//   - the type shown right for at least type_right_share (95 %) of the faulty channels;
//   - recovered RMSE at most recovered_rmse (15 N) on every faulty channel;
//   - re-admitted within readmission_s (0.5 s) after every detected fault that ends before the
//     log does;
//   - no false alarm on any fault-free run (and, listed apart, none on the faulty runs).
// A run is {name, its metrics.json}; a fault-free run may carry its summary alone, and a run
// whose summary has no false-alarm count (not scored: no truth) counts for no target.

#include <string>
#include <vector>

#include "ftsense/params.hpp"
#include "ftsense/report/document.hpp"

namespace ftsense::report {

struct DriftLimit {
  double min_slope_per_s = 0.0;  // drifts at least this fast (|slope|, the run's unit per s) ...
  double delay_s = 0.0;          // ... detected within this long
};

struct FdiTargets {
  std::string unit = "N";  // the runs' unit, for the labels
  double offset_min = 40.0;
  double detect_loaded_s = 0.25;
  std::vector<DriftLimit> drift_limits{{15.0, 2.0}, {5.0, 5.0}};  // fastest first
  double type_right_share = 0.95;
  double recovered_rmse = 15.0;
  double readmission_s = 0.5;
};

struct ScoredRunMetrics {
  std::string name;
  Json metrics;  // as metrics_json writes it: "channels" (may be absent) and "summary"
};

struct TargetCheck {
  std::string target;                   // what is asked, with its numbers
  int checked = 0;                      // faults (or runs) it applies to
  int met = 0;                          // of which meet it
  bool passed = true;                   // the target holds (for the type share: met / checked)
  std::vector<std::string> shortfalls;  // "run channel (fault): measured" for each miss
};

[[nodiscard]] std::vector<TargetCheck> check_targets(const std::vector<ScoredRunMetrics>& runs,
                                                     const FdiTargets& targets = {});

// The misses, "; "-separated; "-" for none.
[[nodiscard]] std::string shortfall_text(const TargetCheck& check);

// One row per target: target, checked, met, held, shortfall (shortfall_text).
[[nodiscard]] Table targets_table(const std::vector<TargetCheck>& checks);

}  // namespace ftsense::report
