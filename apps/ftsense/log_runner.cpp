#include "log_runner.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <limits>
#include <sstream>

namespace ftsense::cli {

ColumnMap ColumnMap::make(const Pipeline& pipeline, const io::CsvLogReader& log) {
  ColumnMap map;
  Diagnostics diag;
  for (const auto& input : pipeline.inputs()) {
    for (std::size_t c = 0; c < input.columns.size(); ++c) {
      const auto index = log.find_column(input.columns[c]);
      if (!index) {
        // The log may have hundreds of columns: name the closest one, not all of them.
        const std::string closest = closest_match(input.columns[c], log.columns());
        diag.error(json_pointer_append(json_pointer_append("/inputs", input.name) + "/columns", c),
                   "column '" + input.columns[c] + "' is not in " + log.path() + "; " +
                       (closest.empty() ? std::string() : "did you mean '" + closest + "'? ") +
                       "map the input to the log's column names in the config");
        continue;
      }
      map.log_column.push_back(*index);
    }
  }
  diag.throw_if_errors();
  return map;
}

std::vector<std::string> monitor_columns(const Monitor& monitor) {
  std::vector<std::string> columns{"time_s"};
  for (const auto& ch : monitor.channels) {
    for (const MonitorColumnInfo& column : kMonitorColumns) columns.push_back(monitor_column_name(ch, column, monitor.unit));
    for (const auto& e : monitor.extra) columns.push_back(extra_column_name(ch, e.name, e.unit));
  }
  return columns;
}

namespace {

// Reads up to `count` rows ahead and checks that their median time step is the config's T.
std::deque<std::vector<double>> read_ahead_and_check_rate(io::CsvLogReader& log, double period,
                                                          std::size_t count) {
  std::deque<std::vector<double>> rows;
  std::vector<double> row;
  while (rows.size() < count && log.next(row)) rows.push_back(row);
  if (rows.empty()) {
    throw io::LogError(io::LogError::Kind::bad_row,
                       log.path() + ":2: the log has a header but no data rows; nothing to run");
  }
  if (rows.size() < 3) return rows;
  std::vector<double> steps;
  for (std::size_t k = 1; k < rows.size(); ++k) steps.push_back(rows[k][0] - rows[k - 1][0]);
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  const double median = steps[steps.size() / 2];
  if (std::abs(median - period) > 0.1 * period) {
    std::ostringstream message;
    message << log.path() << ": the log is sampled every " << median << " s (" << 1.0 / median
            << " Hz, median of the first " << rows.size() << " rows) but the config's sample_period_s is "
            << period << " s (" << 1.0 / period << " Hz); set sample_period_s to " << median
            << " or resample the log (the filters' time constants are per tick)";
    throw io::LogError(io::LogError::Kind::bad_row, message.str());
  }
  return rows;
}


// Parses the rest of a log on a second thread, a block of rows ahead, so that parsing overlaps
// the pipeline and the output writing (a replay is about half parsing). Rows come out in order
// with their line numbers; an error of the reader (a malformed row) comes out where it happened,
// after every row before it. Only this object touches the reader once it has started.
class RowPrefetcher {
 public:
  explicit RowPrefetcher(io::CsvLogReader& log) : log_(log), worker_([this] { produce(); }) {}
  RowPrefetcher(const RowPrefetcher&) = delete;
  RowPrefetcher& operator=(const RowPrefetcher&) = delete;
  ~RowPrefetcher() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    space_.notify_all();
    worker_.join();
  }

  // The next row and its line number; false at the end of the log. Rethrows the reader's error.
  bool next(std::vector<double>& row, std::size_t& line) {
    if (taken_ == current_.rows.size()) {
      if (current_.error) std::rethrow_exception(current_.error);
      if (current_.last) return false;
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [this] { return !blocks_.empty(); });
      std::swap(current_, blocks_.front());
      blocks_.pop_front();
      lock.unlock();
      space_.notify_one();
      taken_ = 0;
      return next(row, line);
    }
    row.swap(current_.rows[taken_]);
    line = current_.lines[taken_];
    ++taken_;
    return true;
  }

 private:
  struct Block {
    std::vector<std::vector<double>> rows;
    std::vector<std::size_t> lines;
    std::exception_ptr error;
    bool last = false;
  };
  static constexpr std::size_t kBlockRows = 256;
  static constexpr std::size_t kMaxBlocks = 8;

  void produce() {
    bool done = false;
    while (!done) {
      Block block;
      try {
        std::vector<double> row;
        while (block.rows.size() < kBlockRows) {
          if (!log_.next(row)) {
            block.last = true;
            break;
          }
          block.rows.push_back(row);
          block.lines.push_back(log_.line());
        }
      } catch (...) {
        block.error = std::current_exception();
      }
      done = block.last || block.error != nullptr;
      std::unique_lock lock(mutex_);
      space_.wait(lock, [this] { return stop_ || blocks_.size() < kMaxBlocks; });
      if (stop_) return;
      blocks_.push_back(std::move(block));
      lock.unlock();
      ready_.notify_one();
    }
  }

  io::CsvLogReader& log_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::condition_variable space_;
  std::deque<Block> blocks_;
  bool stop_ = false;
  Block current_;
  std::size_t taken_ = 0;
  std::thread worker_;  // last: starts after every other member exists
};

}  // namespace

RunSummary run_over_log(Pipeline& pipeline, io::CsvLogReader& log, const ColumnMap& map,
                        io::CsvLogWriter* out, const std::function<void(double)>& after_step,
                        const std::vector<SignalRef>& recorded, const ClockPolicy& clock) {
  const Monitor& m = pipeline.monitor();
  const std::size_t channels = m.channels.size();
  RunSummary summary;
  summary.first_fault_time_s.assign(channels, std::numeric_limits<double>::quiet_NaN());
  summary.fault_types_seen.assign(channels, 0);
  summary.unjudged_ticks.assign(channels, 0);
  summary.longest_unjudged_start_s.assign(channels, std::numeric_limits<double>::quiet_NaN());
  summary.longest_unjudged_ticks.assign(channels, 0);
  std::vector<double> stretch_start_s(channels, 0.0);
  std::vector<std::size_t> stretch_ticks(channels, 0);
  std::vector<double> row;
  const std::size_t per_channel = kMonitorColumnCount + m.extra.size();
  std::size_t recorded_values = 0;
  for (const SignalRef& r : recorded) recorded_values += r.dim;
  std::vector<double> out_row(1 + per_channel * channels + recorded_values);
  const double period = pipeline.sample_period_s();
  double last_time = std::numeric_limits<double>::quiet_NaN();
  pipeline.reset();
  std::deque<std::vector<double>> ahead = read_ahead_and_check_rate(log, period, clock.rate_check_rows);
  std::size_t line = 1;  // of the row being stepped (the header is line 1)
  // The rate is checked again on every block of steps: a log whose rate changes after its first
  // rows would otherwise run with every time constant off by the ratio.
  std::vector<double> block_steps;
  block_steps.reserve(clock.rate_block_steps);
  std::size_t block_first_line = 0;
  RowPrefetcher rest(log);  // the rows after the read-ahead, parsed on a second thread
  while (true) {
    if (!ahead.empty()) {
      row = std::move(ahead.front());
      ahead.pop_front();
      ++line;
    } else if (!rest.next(row, line)) {
      break;
    }
    const double t = row[0];
    if (!std::isnan(last_time)) {
      const double dt = t - last_time;
      if (dt > clock.gap_reset_periods * period) {
        pipeline.reset();
        if (summary.gap_resets++ == 0) {
          summary.first_gap_line = line;
          summary.first_gap_s = dt;
        }
      } else {
        if (std::abs(dt - period) > 0.1 * period && summary.irregular_steps++ == 0) {
          summary.first_irregular_line = line;
          summary.first_irregular_dt = dt;
        }
        if (block_steps.empty()) block_first_line = line;
        block_steps.push_back(dt);
        if (block_steps.size() == clock.rate_block_steps) {
          const auto middle = block_steps.begin() + static_cast<std::ptrdiff_t>(block_steps.size() / 2);
          std::nth_element(block_steps.begin(), middle, block_steps.end());
          if (std::abs(*middle - period) > 0.1 * period) {
            std::ostringstream message;
            message << log.path() << ":" << block_first_line << ": from this line the log is sampled every " << *middle
                    << " s (median of " << block_steps.size() << " steps), not the config's sample_period_s = "
                    << period << " s: its rate changed mid-log; resample it, or cut it where the rate changes";
            throw io::LogError(io::LogError::Kind::bad_row, message.str());
          }
          block_steps.clear();
        }
      }
    }
    last_time = t;
    std::size_t k = 0;
    for (std::size_t i = 0; i < pipeline.inputs().size(); ++i) {
      for (double& v : pipeline.input_values(i)) v = row[map.log_column[k++]];
    }
    pipeline.step(t);
    std::array<std::span<const double>, kMonitorColumnCount> columns;
    for (std::size_t i = 0; i < kMonitorColumnCount; ++i) columns[i] = pipeline.values(m.columns[i]);
    const auto fault = pipeline.values(m[MonitorColumn::fault]);
    const auto fault_type = pipeline.values(m[MonitorColumn::fault_type]);
    out_row[0] = t;
    for (std::size_t c = 0; c < channels; ++c) {
      double* o = &out_row[1 + per_channel * c];
      for (std::size_t i = 0; i < kMonitorColumnCount; ++i) o[i] = columns[i][c];
      for (std::size_t e = 0; e < m.extra.size(); ++e) o[kMonitorColumnCount + e] = pipeline.values(m.extra[e].signal)[c];
      if (fault[c] != 0.0) {
        if (std::isnan(summary.first_fault_time_s[c])) summary.first_fault_time_s[c] = t;
        if (const auto type = fault_type_from_code(fault_type[c])) summary.fault_types_seen[c] |= fault_type_bit(*type);
      }
      if (columns[static_cast<std::size_t>(MonitorColumn::cannot_judge)][c] == 0.0) {
        stretch_ticks[c] = 0;
      } else {
        summary.unjudged_ticks[c]++;
        if (stretch_ticks[c]++ == 0) stretch_start_s[c] = t;
        if (stretch_ticks[c] > summary.longest_unjudged_ticks[c]) {
          summary.longest_unjudged_ticks[c] = stretch_ticks[c];
          summary.longest_unjudged_start_s[c] = stretch_start_s[c];
        }
      }
    }
    std::size_t at = 1 + per_channel * channels;
    for (const SignalRef& r : recorded) {
      for (double v : pipeline.values(r)) out_row[at++] = v;
    }
    if (out != nullptr) out->write_row(out_row);
    if (after_step) after_step(t);
    ++summary.ticks;
  }
  if (out != nullptr) out->flush();
  return summary;
}

std::string clock_warnings(const std::string& input_path, const RunSummary& summary, double period_s,
                           const ClockPolicy& clock) {
  std::ostringstream text;
  if (summary.gap_resets > 0) {
    text << "warning: " << input_path << ": " << summary.gap_resets << " time gap"
         << (summary.gap_resets == 1 ? "" : "s") << " longer than " << clock.gap_reset_periods
         << " T = " << clock.gap_reset_periods * period_s << " s (first at line " << summary.first_gap_line
         << ": " << summary.first_gap_s << " s); the pipeline was reset at each: filters restarted and "
         << "the detectors' warm-up ran again\n";
  }
  if (summary.irregular_steps > 0) {
    text << "warning: " << input_path << ": " << summary.irregular_steps << " rows are not T = " << period_s
         << " s after the previous one (first at line " << summary.first_irregular_line
         << ", dt = " << summary.first_irregular_dt << " s); the filters assume the configured fixed tick\n";
  }
  return text.str();
}

std::vector<std::string> apply_thresholds(Json& config, const Json& thresholds, const std::string& thresholds_path) {
  Diagnostics diag;
  std::vector<std::string> set;
  const auto stages = thresholds.find("stages");
  if (!thresholds.is_object() || stages == thresholds.end() || !stages->is_object()) {
    throw ConfigError(thresholds_path + ":/stages", "missing; a thresholds file (from ftsense calibrate) has "
                                                     "\"stages\": {\"<stage>\": {\"thresholds\": [...]}}");
  }
  // Statistics measured at one rate do not hold at another (a window step spans fewer ticks, a
  // filtered residual's peak is another): a file that states its rate must match the config's.
  if (const auto period = thresholds.find("sample_period_s"); period != thresholds.end()) {
    const double config_period = config.is_object() ? config.value("sample_period_s", 0.0) : 0.0;
    if (!period->is_number() || !(period->get<double>() > 0.0)) {
      diag.error(thresholds_path + ":/sample_period_s", "is not a positive number of seconds");
    } else if (config_period > 0.0 && std::abs(period->get<double>() - config_period) > 1e-9 * config_period) {
      diag.error(thresholds_path + ":/sample_period_s",
                 "= " + format_number(period->get<double>()) + " s, but the config runs at " +
                     format_number(config_period) + " s: statistics measured at one rate do not hold at another; "
                     "calibrate on a fault-free log at " + format_number(config_period) + " s");
    }
  }
  for (const auto& [name, entry] : stages->items()) {
    const std::string stage_path = thresholds_path + ":" + json_pointer_append("/stages", name);
    const bool has_thresholds = entry.is_object() && entry.contains("thresholds");
    const bool has_params = entry.is_object() && entry.contains("params");
    if (!has_thresholds && !has_params) {
      diag.error(stage_path, "has neither \"thresholds\" nor \"params\"; calibrate with ftsense calibrate");
      continue;
    }
    if (has_thresholds && !entry["thresholds"].is_array()) {
      diag.error(stage_path + "/thresholds", "not an array of numbers");
      continue;
    }
    if (has_params && !entry["params"].is_object()) {
      diag.error(stage_path + "/params", "not an object of parameter values");
      continue;
    }
    bool found = false;
    if (config.contains("stages") && config["stages"].is_array()) {
      for (std::size_t i = 0; i < config["stages"].size(); ++i) {
        Json& stage = config["stages"][i];
        if (stage.is_object() && stage.value("name", "") == name) {
          const std::string params_pointer = "/stages/" + std::to_string(i) + "/params/";
          if (has_thresholds) {
            stage["params"]["thresholds"] = entry["thresholds"];
            set.push_back(params_pointer + "thresholds");
            // A band calibration also sets each channel's centre; a plain one resets it to 0.
            if (entry.contains("centers")) {
              stage["params"]["centers"] = entry["centers"];
              set.push_back(params_pointer + "centers");
            } else if (stage["params"].contains("centers")) {
              stage["params"].erase("centers");
            }
          }
          // Measured statistics replace the config's values (the plugin checks them as any).
          if (has_params) {
            for (const auto& [key, value] : entry["params"].items()) {
              stage["params"][key] = value;
              set.push_back(params_pointer + json_pointer_append("", key).substr(1));
            }
          }
          found = true;
        }
      }
    }
    if (!found) diag.error(stage_path, "the config has no stage named '" + name + "'; calibrate with the same config");
  }
  diag.throw_if_errors();
  return set;
}

}  // namespace ftsense::cli
