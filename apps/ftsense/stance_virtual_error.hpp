#pragma once
// The error of a virtual force sensor per foot while the foot is on the ground: over the ticks
// where the simulator's true contact is 1,
//
//   e_k = v_k - N_k    (v: the virtual force of `ftsense run --record`, N: the true normal force)
//
// RMS sqrt(mean e_k^2) and the 95th percentile of |e_k| [N]; ticks whose v is NaN (virtual
// sensor not ready) are counted apart, not scored. The run's rows are the log's rows, in order.

#include <string>
#include <vector>

namespace ftsense::cli {

struct StanceVirtualError {
  std::string channel;
  long stance_ticks = 0;     // true contact
  long not_ready_ticks = 0;  // of those, v NaN
  double rms_N = 0.0;
  double p95_N = 0.0;
};

/// Per channel i of `channels`: the run's column `<virtual_signal>/<i>_N` (a recorded signal)
/// against the log's `truth/<channel>/force_N` where `truth/<channel>/contact` is 1. Throws
/// std::runtime_error naming the file and column when a column is missing or the row counts
/// differ.
[[nodiscard]] std::vector<StanceVirtualError> stance_virtual_error(const std::string& run_csv,
                                                                   const std::string& virtual_signal,
                                                                   const std::string& log_csv,
                                                                   const std::vector<std::string>& channels);

}  // namespace ftsense::cli
