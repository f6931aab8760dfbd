#pragma once
// A run's output and its ground truth, loaded whole for scoring.
//
// The output of `ftsense run` is read by the monitor column table (ftsense/monitor_columns.hpp):
// `time_s`, then per channel every column of kMonitorColumns and optional extras. The truth is
// a log with, per channel c, `truth/c/force_<unit>` (the true value) and `truth/c/fault` (the
// injected fault's type code while it is active), and contact columns found by the channel's
// path: for c = "l_foot/p1" the first of `truth/l_foot/p1/contact`, `truth/l_foot/contact`
// (1 while that contact touches the ground). The simulator and `ftsense inject` write these.

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "ftsense/monitor_columns.hpp"
#include "ftsense/report/metrics.hpp"

namespace ftsense::report {

// A whole CSV log in memory, column by column.
struct LogTable {
  std::string path;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;

  // Throws io::LogError on a malformed file.
  [[nodiscard]] static LogTable load(const std::string& path);
  [[nodiscard]] const std::vector<double>* find(const std::string& name) const;
  // The column, or ConfigError naming the file and the closest existing name.
  [[nodiscard]] const std::vector<double>& at(const std::string& name) const;
  [[nodiscard]] std::size_t rows() const { return columns.empty() ? 0 : columns[0].size(); }
};

struct RunChannel {
  std::string name;
  std::array<const std::vector<double>*, kMonitorColumnCount> columns{};  // null: an optional one absent
  const std::vector<double>* raw_fault_estimate = nullptr;  // extra `fault_estimate_raw`, if written
  // From the truth, when given and present for this channel; else null.
  const std::vector<double>* true_force = nullptr;
  const std::vector<double>* true_fault = nullptr;
  const std::vector<double>* contact = nullptr;

  // A required column (always there); an optional one may be absent: see has().
  [[nodiscard]] const std::vector<double>& operator[](MonitorColumn c) const {
    const std::vector<double>* column = columns[static_cast<std::size_t>(c)];
    if (column == nullptr) {
      throw std::out_of_range("run channel " + name + " has no " + std::string(monitor_column_info(c).key) + " column");
    }
    return *column;
  }
  [[nodiscard]] bool has(MonitorColumn c) const { return columns[static_cast<std::size_t>(c)] != nullptr; }
  // The spans metrics take (truth spans empty when absent).
  [[nodiscard]] ChannelSeries series() const;
};

struct ScoredRun {
  LogTable run;
  LogTable truth;  // empty when none
  std::string unit;  // of the measured signal
  const std::vector<double>* time = nullptr;
  std::vector<RunChannel> channels;  // in the order of the run's columns

  [[nodiscard]] bool has_truth() const { return !truth.names.empty(); }
};

// Loads a run output and (if truth_path is not empty) its truth. Throws ConfigError when the run
// is not an output of `ftsense run` or the truth is not the log the run was made from, and
// io::LogError on malformed files.
[[nodiscard]] ScoredRun load_scored_run(const std::string& run_path, const std::string& truth_path);

// The truth's contact column for `channel` (see above); null when it has none.
[[nodiscard]] const std::vector<double>* contact_column(const LogTable& truth, const std::string& channel);

}  // namespace ftsense::report
