#pragma once
// Runs a built pipeline over a CSV log, row by row, and writes the monitored channels.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ftsense/fault_type.hpp"
#include "ftsense/io/csv_log.hpp"
#include "ftsense/pipeline.hpp"

namespace ftsense::cli {

// Where each pipeline input value comes from in the log. Throws ConfigError listing every
// pipeline column missing from the log (with the closest existing names).
struct ColumnMap {
  std::vector<std::size_t> log_column;  // per pipeline input value, in input order
  static ColumnMap make(const Pipeline& pipeline, const io::CsvLogReader& log);
};

// The output header of `ftsense run` (design.md): time_s, then per channel the columns of
// kMonitorColumns (monitor_columns.hpp) and the monitor's extra signals.
std::vector<std::string> monitor_columns(const Monitor& monitor);

// The log's time column as the config declares it ("time": {"column", "unit"}).
[[nodiscard]] inline io::TimeColumn time_column_of(const Pipeline& pipeline) {
  return io::TimeColumn{pipeline.time_column(), pipeline.time_unit(), pipeline.time_seconds_per_unit()};
}

struct RunSummary {
  std::size_t ticks = 0;
  std::size_t irregular_steps = 0;  // rows whose time step differs from T by more than 10 %
  std::size_t first_irregular_line = 0;
  double first_irregular_dt = 0.0;
  std::size_t gap_resets = 0;       // time steps longer than the gap limit: the pipeline was reset
  std::size_t first_gap_line = 0;
  double first_gap_s = 0.0;
  std::vector<double> first_fault_time_s;  // per channel; NaN when never flagged
  // Per channel: the fault types shown while flagged, one bit per type (fault_type_bit).
  std::vector<std::uint32_t> fault_types_seen;
  // Per channel: ticks whose cannot_judge column was not 0 (the virtual sensor not ready, or a
  // fault no channel could be singled out for: "no fault" says nothing there), and the longest
  // unbroken stretch of them (its first time and length; the first one of that length).
  std::vector<std::size_t> unjudged_ticks;
  std::vector<double> longest_unjudged_start_s;
  std::vector<std::size_t> longest_unjudged_ticks;
};

// The bit of a fault type in RunSummary::fault_types_seen.
[[nodiscard]] constexpr std::uint32_t fault_type_bit(FaultType type) noexcept {
  return std::uint32_t{1} << static_cast<unsigned>(type);
}
static_assert(kFaultTypes.size() <= 32, "fault_types_seen holds one bit per fault type");

// How the runner treats the log's clock (documented in docs/reliability.md):
// - the median time step of the first rows (up to `rate_check_rows`) must be within 10 % of the
//   config's T, else LogError: the log and the config disagree on the sample rate and every
//   filter time constant would be off by their ratio;
// - a time step longer than `gap_reset_periods` T (lost samples, a paused logger) resets the
//   pipeline before that row: filters restart from their initial state and the detectors' warm-up
//   runs again, rather than one predict step pretending to bridge the gap; counted and reported;
// - smaller irregularities (jitter, a dropped sample or two) are counted and reported only.
// Rows not after the previous one are rejected by the reader (io::LogError).
// - after that, the median step of every block of `rate_block_steps` steps (gaps left out) must
//   be within 10 % of T too, else LogError at the block's first line: the rate changed mid-log.
struct ClockPolicy {
  double gap_reset_periods = 10.0;
  std::size_t rate_check_rows = 50;
  std::size_t rate_block_steps = 100;
};

// Steps the pipeline once per log row, writes the monitored channels to `out` (if given) and
// calls `after_step(t)` after each tick (if given). Throws io::LogError on a malformed row, a log
// with no data rows, or a sample rate that is not the config's. `recorded` signals are appended
// to each output row after the monitored channels.
RunSummary run_over_log(Pipeline& pipeline, io::CsvLogReader& log, const ColumnMap& map,
                        io::CsvLogWriter* out, const std::function<void(double)>& after_step = {},
                        const std::vector<SignalRef>& recorded = {}, const ClockPolicy& clock = {});

// Warnings about the log's clock (irregular steps, gap resets) for stderr; empty when none.
std::string clock_warnings(const std::string& input_path, const RunSummary& summary, double period_s,
                           const ClockPolicy& clock);

// A calibration written by `ftsense calibrate`: sets params.thresholds (and centers) and the
// measured params of each named stage in `config`. Throws ConfigError naming the file and the
// stage when one does not fit.
// Returns the JSON pointers into `config` of the values it set ("/stages/<i>/params/<key>"), so
// that a problem with one of them can be reported where the value came from.
std::vector<std::string> apply_thresholds(Json& config, const Json& thresholds, const std::string& thresholds_path);

}  // namespace ftsense::cli
