#pragma once
// Runs a built pipeline over a CSV log, row by row, and writes the monitored channels.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "ftsense/io/csv_log.hpp"
#include "ftsense/pipeline.hpp"

namespace ftsense::cli {

// Where each pipeline input value comes from in the log. Throws ConfigError listing every
// pipeline column missing from the log (with the closest existing names).
struct ColumnMap {
  std::vector<std::size_t> log_column;  // per pipeline input value, in input order
  static ColumnMap make(const Pipeline& pipeline, const io::CsvLogReader& log);
};

// The output header of `ftsense run` (design.md): time_s, then per channel
// measured/virtual/fault_estimate/recovered (with the unit suffix), fault, fault_type.
std::vector<std::string> monitor_columns(const Monitor& monitor);

struct RunSummary {
  std::size_t ticks = 0;
  std::size_t irregular_steps = 0;  // rows whose time step differs from T by more than 10 %
  std::size_t first_irregular_line = 0;
  double first_irregular_dt = 0.0;
  std::vector<double> first_fault_time_s;  // per channel; NaN when never flagged
};

// Steps the pipeline once per log row, writes the monitored channels to `out` (if given) and
// calls `after_step(t)` after each tick (if given). Throws io::LogError on a malformed row.
// `recorded` signals are appended to each output row after the monitored channels.
RunSummary run_over_log(Pipeline& pipeline, io::CsvLogReader& log, const ColumnMap& map,
                        io::CsvLogWriter* out, const std::function<void(double)>& after_step = {},
                        const std::vector<SignalRef>& recorded = {});

// Thresholds written by `ftsense calibrate`: sets params.thresholds of each named stage in
// `config`. Throws ConfigError naming the file and the stage when one does not fit.
void apply_thresholds(Json& config, const Json& thresholds, const std::string& thresholds_path);

}  // namespace ftsense::cli
