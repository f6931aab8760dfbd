#pragma once
// Metrics of a run against the ground truth, figures (gnuplot) and a Markdown report.
//
// Inputs: the output of `ftsense run` (per channel measured, virtual, fault_estimate,
// recovered, fault, fault_type, optional fault_estimate_raw) and, optionally, the simulator's
// log with truth/<channel>/force_N, truth/<channel>/fault (type code while a fault is injected)
// and truth/contact_l, truth/contact_r.
//
// Per channel (definitions; docs/results.md repeats them):
//   - fault onset/end: first/last sample with truth fault != 0; injected fault = measured - truth;
//   - detection delay: first flag at or after onset, minus onset (missed: none before the end);
//   - type shown: the fault type the channel shows most while the fault is active and flagged;
//   - fault estimate error: RMS of (fault_estimate - injected) from onset + settle_s to the end
//     of the fault (settle_s = 5 s = 5 time constants of the paper's filter);
//   - recovered RMSE: RMS of (recovered - truth) from onset to the end of the fault, or over the
//     whole run after warm-up for a healthy channel;
//   - re-admission: seconds from the end of a fault that ends before the log does until the flag
//     clears (the goal is under 1 s);
//   - false alarms: rising edges of the flag after warm-up outside [onset, end + readmit_s];
//     false-alarm time: seconds flagged there;
//   - VFS error: RMS and 95th percentile of |virtual - truth| while the foot is in contact
//     (truth/contact_l or _r; every sample when the log has no contact column).

#include <string>
#include <vector>

#include "ftsense/params.hpp"

namespace ftsense::cli {

struct ReportOptions {
  double warmup_s = 2.0;
  double settle_s = 5.0;
  double readmit_s = 1.0;
  std::string title = "ftsense run";
  bool figures = true;
};

struct ChannelMetrics {
  std::string channel;
  int injected_type = 0;          // truth fault code at onset (0: healthy)
  double onset_s = 0.0, end_s = 0.0;
  double detection_delay_s = 0.0;  // NaN: missed
  int detected_type = 0;           // fault_type output at detection
  int shown_type = 0;              // the type shown most while the fault is active and flagged
  double fault_estimate_rmse = 0.0;
  double recovered_rmse = 0.0;
  double readmission_s = 0.0;     // NaN: the fault lasts to the end, or the flag never clears
  int false_alarms = 0;
  double false_alarm_time_s = 0.0;
  double vfs_rmse = 0.0, vfs_p95 = 0.0;
  double measured_rmse = 0.0;      // |measured - truth| over the same window as recovered_rmse
};

struct Report {
  std::vector<ChannelMetrics> channels;
  Json json;                      // everything, as written to metrics.json
  std::string table;              // the terminal summary
};

// Computes the metrics; with out_dir non-empty also writes metrics.json, report.md and (if
// options.figures) the four figures there. Throws io::LogError / ConfigError on bad files.
Report make_report(const std::string& run_path, const std::string& truth_path, const std::string& out_dir,
                   const ReportOptions& options);

int report_command(const std::vector<std::string>& args);

}  // namespace ftsense::cli
