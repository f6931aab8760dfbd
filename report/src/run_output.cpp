#include "ftsense/report/run_output.hpp"

#include <algorithm>
#include <cmath>

#include "ftsense/diagnostics.hpp"
#include "ftsense/io/csv_log.hpp"

namespace ftsense::report {

LogTable LogTable::load(const std::string& path) {
  io::CsvLogReader reader(path);
  LogTable t;
  t.path = path;
  t.names = reader.columns();
  t.columns.resize(t.names.size());
  std::vector<double> row;
  while (reader.next(row)) {
    for (std::size_t c = 0; c < row.size(); ++c) t.columns[c].push_back(row[c]);
  }
  return t;
}

const std::vector<double>* LogTable::find(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return &columns[i];
  }
  return nullptr;
}

const std::vector<double>& LogTable::at(const std::string& name) const {
  if (const auto* c = find(name)) return *c;
  throw ConfigError(path, "has no column '" + name + "'; " + suggest(name, names).substr(0, 200));
}

ChannelSeries RunChannel::series() const {
  auto span_of = [](const std::vector<double>* v) { return v != nullptr ? std::span<const double>(*v) : std::span<const double>(); };
  return {(*this)[MonitorColumn::measured], (*this)[MonitorColumn::virtual_value],
          (*this)[MonitorColumn::fault_estimate], (*this)[MonitorColumn::recovered],
          (*this)[MonitorColumn::fault], (*this)[MonitorColumn::fault_type],
          span_of(true_force), span_of(true_fault), span_of(contact)};
}

const std::vector<double>* contact_column(const LogTable& truth, const std::string& channel) {
  // Longest path prefix first: a per-channel contact beats its foot's.
  std::string prefix = channel;
  while (!prefix.empty()) {
    if (const auto* c = truth.find("truth/" + prefix + "/contact")) return c;
    const auto slash = prefix.rfind('/');
    if (slash == std::string::npos) break;
    prefix.resize(slash);
  }
  return nullptr;
}

ScoredRun load_scored_run(const std::string& run_path, const std::string& truth_path) {
  ScoredRun r;
  r.run = LogTable::load(run_path);
  if (!truth_path.empty()) {
    r.truth = LogTable::load(truth_path);
    if (r.truth.rows() != r.run.rows()) {
      throw ConfigError(truth_path, "has " + std::to_string(r.truth.rows()) + " rows but " + run_path + " has " +
                                        std::to_string(r.run.rows()) + "; give the log the run was made from");
    }
    // Same length is not enough: a run copies its log's time stamps, so they must agree row by row.
    const auto& run_time = r.run.at("time_s");
    const auto& truth_time = r.truth.at("time_s");
    for (std::size_t k = 0; k < run_time.size(); ++k) {
      if (std::abs(run_time[k] - truth_time[k]) > 1e-9 * std::max(1.0, std::abs(truth_time[k]))) {
        throw ConfigError(truth_path, "row " + std::to_string(k + 2) + " has time_s = " + format_number(truth_time[k]) +
                                          " but " + run_path + " has " + format_number(run_time[k]) +
                                          "; give the log the run was made from");
      }
    }
  }
  r.time = &r.run.at("time_s");
  // The unit: what follows "<channel>/measured_" in the first such column.
  const MonitorColumnInfo& measured = monitor_column_info(MonitorColumn::measured);
  std::string measured_mark(1, '/');  // built up: GCC 12 warns falsely (-Wrestrict) on "/" + std::string
  measured_mark += measured.key;
  measured_mark += '_';
  for (const auto& n : r.run.names) {
    if (const auto at = n.rfind(measured_mark); at != std::string::npos && at > 0) {
      r.unit = n.substr(at + measured_mark.size());
      break;
    }
  }
  // The channels: every prefix that names a fault_type column in this unit.
  const MonitorColumnInfo& marker = monitor_column_info(MonitorColumn::fault_type);
  for (const auto& n : r.run.names) {
    const auto parsed = parse_monitor_column(n, r.unit);
    if (parsed && parsed->column == marker.column) r.channels.push_back(RunChannel{parsed->channel, {}});
  }
  if (r.channels.empty()) {
    throw ConfigError(run_path, "has no <channel>/" + std::string(marker.key) + " columns; is it an output of ftsense run?");
  }
  if (r.unit.empty()) {
    throw ConfigError(run_path, "has no " + monitor_column_name(r.channels.front().name, measured, "<unit>") + " column");
  }
  for (RunChannel& ch : r.channels) {
    for (const MonitorColumnInfo& c : kMonitorColumns) {
      const std::string name = monitor_column_name(ch.name, c, r.unit);
      // A run written before an optional column existed lacks it: null.
      ch.columns[static_cast<std::size_t>(c.column)] = c.required ? &r.run.at(name) : r.run.find(name);
    }
    ch.raw_fault_estimate = r.run.find(extra_column_name(ch.name, "fault_estimate_raw", r.unit));
    if (r.has_truth()) {
      ch.true_force = r.truth.find("truth/" + ch.name + "/force_" + r.unit);
      ch.true_fault = r.truth.find("truth/" + ch.name + "/fault");
      ch.contact = contact_column(r.truth, ch.name);
    }
  }
  return r;
}

}  // namespace ftsense::report
