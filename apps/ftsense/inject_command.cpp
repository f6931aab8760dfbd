// ftsense inject: the simulator's sensor fault models applied to named columns of a recorded log,
// with the truth/... columns `ftsense report` scores against.

#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/io/csv_log.hpp"
#include "ftsense/sim/scenario.hpp"

namespace ftsense::cli {
namespace {

struct InjectionPlan {
  std::uint64_t seed = 1;
  std::vector<std::string> channels;  // names used in truth/<channel>/... and by the faults
  std::vector<std::string> columns;   // the log column each channel's faults go into
  std::vector<sim::FaultSpec> faults;
};

std::string sensor_fault_type_list() {
  std::string list;
  for (const FaultType t : sensor_fault_types()) list += (list.empty() ? "" : ", ") + std::string(to_string(t));
  return list;
}

InjectionPlan load_plan(const std::string& path) {
  const Json doc = parse_json_text(read_text_file(path, "faults file"), path);
  std::vector<std::string> errors;
  InjectionPlan plan;
  if (!doc.is_object()) throw ConfigError(path + ":", "expected an object with \"channels\" and \"faults\"");
  for (const auto& [key, value] : doc.items()) {
    if (key != "description" && key != "seed" && key != "channels" && key != "faults") {
      errors.push_back(json_pointer_append("", key) + ": unknown key; " +
                       suggest(key, {"description", "seed", "channels", "faults"}));
    }
  }
  if (doc.contains("seed")) {
    if (doc["seed"].is_number_unsigned()) plan.seed = doc["seed"].get<std::uint64_t>();
    else errors.push_back("/seed: expected a non-negative integer");
  }
  if (!doc.contains("channels") || !doc["channels"].is_object() || doc["channels"].empty()) {
    errors.push_back("/channels: expected an object mapping channel names to log columns, e.g. "
                     "{\"r_foot\": \"r_foot/force_z_N\"}");
  } else {
    for (const auto& [name, column] : doc["channels"].items()) {
      if (!column.is_string()) {
        errors.push_back(json_pointer_append("/channels", name) + ": expected the name of a log column");
        continue;
      }
      plan.channels.push_back(name);
      plan.columns.push_back(column.get<std::string>());
    }
  }
  if (!doc.contains("faults") || !doc["faults"].is_array()) {
    errors.push_back("/faults: expected an array of faults (the scenario keys of sim/README.md)");
  } else if (!plan.channels.empty()) {
    const std::vector<std::string_view> names(plan.channels.begin(), plan.channels.end());
    plan.faults = sim::parse_faults(doc["faults"], "/faults", names, std::numeric_limits<double>::max(), errors);
  }
  if (!errors.empty()) {
    std::vector<Diagnostic> problems;
    for (const auto& e : errors) {
      // "<pointer>: message" or "<pointer> = value ..." as the scenario reader words them.
      const std::size_t split = std::min(e.find(':'), e.find(' '));
      std::string message = split < e.size() ? e.substr(split) : std::string();
      if (message.rfind(" = ", 0) != 0) message.erase(0, message.find_first_not_of(": "));
      problems.push_back({path + ":" + e.substr(0, split), message});
    }
    throw ConfigError(std::move(problems));
  }
  return plan;
}

}  // namespace

int inject_command(const std::vector<std::string>& args, const Context& context) {
  const std::string command = context.command("inject");
  const std::vector<OptionSpec> specs{
      {"input", true, true, "a recorded log (CSV, first column time_s)", 'i', {}, FileArg::input},
      {"faults", true, true, "faults (JSON): {\"seed\", \"channels\": {name: column}, \"faults\": [...]}", 0, {},
       FileArg::input},
      {"output", true, true, "where to write the log with the faults (CSV)", 'o', {"out"}, FileArg::output}};
  const auto options = parse_options(command, args, specs);
  if (options.count("help")) {
    std::cout << usage_text(command,
                            "Applies the simulator's sensor fault models (sim/README.md) to named\n"
                            "columns of a recorded log, at the log's own time stamps, and writes the\n"
                            "log with the faulty columns plus truth/<channel>/force_N (the recorded\n"
                            "value) and truth/<channel>/fault (the fault type code) for\n"
                            "'" + context.program + " report --truth'.\nFault types: " + sensor_fault_type_list() + ".",
                            specs);
    return kExitOk;
  }
  require_existing_files(command, options, specs, {"faults"});
  const InjectionPlan plan = load_plan(options.at("faults"));
  require_existing_files(command, options, specs, {"input"});
  io::CsvLogReader log(options.at("input"));
  std::vector<std::size_t> column;
  std::vector<Diagnostic> problems;
  for (std::size_t c = 0; c < plan.columns.size(); ++c) {
    const std::string where = options.at("faults") + ":" + json_pointer_append("/channels", plan.channels[c]);
    // The time stamps and the truth are what faults are measured against, never faulty themselves.
    if (plan.columns[c] == "time_s" || plan.columns[c].rfind("truth/", 0) == 0) {
      problems.push_back({where, "column '" + plan.columns[c] + "' is the log's " +
                                     (plan.columns[c] == "time_s" ? "time" : "ground truth") +
                                     ", not a sensor; inject faults into a sensor's column"});
      continue;
    }
    for (std::size_t other = 0; other < c; ++other) {
      if (plan.columns[other] == plan.columns[c]) {
        problems.push_back({where, "column '" + plan.columns[c] + "' is also channel '" + plan.channels[other] +
                                       "'; give each column one channel (and put both faults on it)"});
      }
    }
    for (const char* truth : {"/force_N", "/fault"}) {
      const std::string name = "truth/" + plan.channels[c] + truth;
      if (log.find_column(name)) {
        problems.push_back({where, "the log already has a column '" + name + "' (a simulator log?); name the "
                                       "channel differently so that the output's truth columns are unique"});
      }
    }
    if (const auto index = log.find_column(plan.columns[c])) {
      column.push_back(*index);
    } else {
      const std::string closest = closest_match(plan.columns[c], log.columns());
      problems.push_back({options.at("faults") + ":" + json_pointer_append("/channels", plan.channels[c]),
                          "column '" + plan.columns[c] + "' is not in " + log.path() +
                              (closest.empty() ? std::string() : "; did you mean '" + closest + "'?")});
    }
  }
  if (!problems.empty()) throw ConfigError(std::move(problems));
  std::vector<std::string> out_columns = log.columns();
  for (const auto& ch : plan.channels) {
    out_columns.push_back("truth/" + ch + "/force_N");
    out_columns.push_back("truth/" + ch + "/fault");
  }
  std::optional<io::CsvLogWriter> out_file;
  try {
    out_file.emplace(options.at("output"), out_columns, std::vector<std::string>{options.at("input"), options.at("faults")});
  } catch (const io::OutputError& e) {
    throw UsageError{std::string("error: ") + e.what()};
  }
  io::CsvLogWriter& out = *out_file;
  // One fault state per fault, each with its own stream as in the simulator.
  std::vector<sim::FaultState> states;
  for (std::size_t f = 0; f < plan.faults.size(); ++f) {
    states.push_back({sim::Rng(plan.seed, 1000 + f), 0.0, false});
  }
  std::vector<std::optional<double>> previous(plan.channels.size());
  std::vector<double> row;
  std::vector<double> out_row(out_columns.size());
  double last_time = std::numeric_limits<double>::quiet_NaN();
  std::size_t rows = 0;
  std::vector<std::size_t> faulty_rows(plan.channels.size(), 0);
  while (log.next(row)) {
    const double t = row[0];
    const double tick = std::isnan(last_time) ? 0.0 : t - last_time;
    last_time = t;
    std::copy(row.begin(), row.end(), out_row.begin());
    for (std::size_t c = 0; c < plan.channels.size(); ++c) {
      const double recorded = row[column[c]];
      double y = recorded;
      auto code = FaultType::none;
      for (std::size_t f = 0; f < plan.faults.size(); ++f) {
        const sim::FaultSpec& spec = plan.faults[f];
        if (static_cast<std::size_t>(spec.channel) != c || t < spec.start_s || (spec.end_s && t >= *spec.end_s)) continue;
        y = sim::apply_fault(spec, t - spec.start_s, tick, y, previous[c], states[f]);
        code = spec.type;
        break;  // faults on one channel never overlap
      }
      previous[c] = y;
      out_row[column[c]] = y;
      out_row[row.size() + 2 * c] = recorded;
      out_row[row.size() + 2 * c + 1] = fault_code(code);
      if (code != FaultType::none) ++faulty_rows[c];
    }
    out.write_row(out_row);
    ++rows;
  }
  // A fault that starts after the last row would be silently absent from the output.
  for (std::size_t f = 0; f < plan.faults.size(); ++f) {
    if (!(plan.faults[f].start_s <= last_time)) {
      problems.push_back({options.at("faults") + ":" + json_pointer_append("/faults", f) + "/start_s",
                          " = " + format_number(plan.faults[f].start_s) + " is after the log's last row (t = " +
                              format_number(last_time) + " s); start the fault within the log"});
    }
  }
  if (!problems.empty()) throw ConfigError(std::move(problems));  // nothing written
  out.commit();
  std::cout << command << ": " << rows << " rows, " << plan.faults.size() << " fault(s)";
  for (std::size_t c = 0; c < plan.channels.size(); ++c) {
    std::cout << "; " << plan.channels[c] << " (" << plan.columns[c] << ") faulty on " << faulty_rows[c] << " rows";
  }
  std::cout << " -> " << options.at("output") << '\n';
  return kExitOk;
}

}  // namespace ftsense::cli
