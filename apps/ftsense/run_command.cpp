#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "cli.hpp"
#include "ftsense/fault_type.hpp"
#include "log_runner.hpp"

namespace ftsense::cli {

int run_command(const std::vector<std::string>& args, const Context& context) {
  const std::string command = context.command("run");
  const std::vector<OptionSpec> specs{
      {"config", true, true, "pipeline config (JSON); see docs/config_reference.md", 'c', {}, FileArg::input},
      {"input", true, true, "input log (CSV, first column time_s); - for standard input", 'i', {}, FileArg::input},
      {"output", true, false, "where to write the monitored channels (CSV; - for standard output, the summary then on "
                              "standard error); without it only the summary is printed", 'o', {"out"}, FileArg::output},
      {"thresholds", true, false, "thresholds from '" + context.program + " calibrate' (JSON), applied to the config", 0, {},
       FileArg::input},
      {"record", true, false, "further signals to write, comma-separated \"<stage>.<port>\" or \"input.<name>\""},
      {"gap-reset", true, false, "a time step longer than this many sample periods resets the pipeline (default 10)"}};
  const auto options = parse_options(command, args, specs);
  if (options.count("help")) {
    std::cout << usage_text(command,
                            "Runs the pipeline of --config over every row of --input and writes, per\n"
                            "monitored channel, measured, virtual, fault estimate, recovered, fault and\n"
                            "fault type to --output. The config is checked completely before the log is\n"
                            "opened; every problem is listed, one per line.",
                            specs);
    return kExitOk;
  }
  const std::string& config_path = options.at("config");
  const std::string& input_path = options.at("input");
  const bool write_output = options.count("output") > 0;
  const std::string output_path = write_output ? options.at("output") : std::string();

  ClockPolicy clock;
  if (const auto g = options.find("gap-reset"); g != options.end()) {
    char* end = nullptr;
    clock.gap_reset_periods = std::strtod(g->second.c_str(), &end);
    if (end == g->second.c_str() || *end != '\0' || !(clock.gap_reset_periods >= 1.5) ||
        !std::isfinite(clock.gap_reset_periods)) {
      throw UsageError{command + ": --gap-reset " + g->second +
                       ": give a number of sample periods >= 1.5 (a step of 1 T is no gap)"};
    }
  }

  // 1. The config, completely, before any data file is touched.
  require_existing_files(command, options, specs, {"config", "thresholds"});
  Pipeline pipeline = options.count("thresholds") ? load_pipeline(context, config_path, options.at("thresholds"))
                                                  : load_pipeline(context, config_path);
  if (!pipeline.has_monitor()) {
    throw ConfigError(config_path + ":/monitor",
                      "missing; '" + command + "' writes the monitored channels, so the config needs a "
                      "\"monitor\" section (docs/config_reference.md)");
  }

  // 2. The log: open, map columns (all missing ones reported together).
  require_existing_files(command, options, specs, {"input"});
  std::optional<io::CsvLogReader> log;
  try {
    if (input_path == "-") log.emplace(std::cin, "standard input", time_column_of(pipeline));
    else log.emplace(input_path, time_column_of(pipeline));
  } catch (const io::LogError& e) {
    throw UsageError{std::string("error: ") + e.what()};
  }
  ColumnMap map = [&] {
    try {
      return ColumnMap::make(pipeline, *log);
    } catch (const ConfigError& e) {
      std::vector<Diagnostic> problems = e.problems();
      for (auto& p : problems) p.path = config_path + ":" + p.path;
      throw ConfigError(std::move(problems));
    }
  }();
  std::vector<SignalRef> recorded;
  std::vector<std::string> columns = monitor_columns(pipeline.monitor());
  if (const auto r = options.find("record"); r != options.end()) {
    std::vector<std::pair<std::string, std::string>> units;
    for (const auto& [name, unit] : pipeline.signal_names()) units.emplace_back(name, unit);
    for (const std::string& name : split_list(r->second)) {
      SignalRef ref;
      try {
        ref = pipeline.signal(name);
      } catch (const ConfigError& e) {
        throw UsageError{command + ": --record: " + std::string(e.what())};
      }
      std::string unit;
      for (const auto& [n, u] : units) {
        if (n == name) unit = u;
      }
      for (std::size_t i = 0; i < ref.dim; ++i) {
        std::string column = name;
        if (ref.dim > 1) column += '/' + std::to_string(i);
        if (unit != "1") column += '_' + unit;
        columns.push_back(column);
      }
      recorded.push_back(ref);
    }
  }
  // Every column once: a name written twice (--record a,a; a recorded signal named like a
  // monitor column) would make a header that no CSV reader, ftsense's own included, accepts.
  for (std::size_t i = 1; i < columns.size(); ++i) {
    if (std::find(columns.begin(), columns.begin() + static_cast<std::ptrdiff_t>(i), columns[i]) !=
        columns.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw UsageError{command + ": the output would have the column '" + columns[i] +
                       "' twice; record each signal once (--record)"};
    }
  }
  std::optional<io::CsvLogWriter> out;
  if (write_output) {
    try {
      std::vector<std::string> inputs{input_path, config_path};
      if (options.count("thresholds")) inputs.push_back(options.at("thresholds"));
      out.emplace(output_path, columns, inputs);
    } catch (const io::OutputError& e) {
      throw UsageError{std::string("error: ") + e.what()};
    }
  }

  // 3. Every row.
  RunSummary summary;
  try {
    summary = run_over_log(pipeline, *log, map, out ? &*out : nullptr, {}, recorded, clock);
  } catch (const io::LogError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitRuntime;
  }
  if (out) out->commit();  // only now does output_path change
  std::cerr << clock_warnings(input_path, summary, pipeline.sample_period_s(), clock);
  // With the rows on standard output, the summary goes to standard error.
  std::ostream& summary_out = output_path == "-" ? std::cerr : std::cout;
  summary_out << command << ": " << summary.ticks << " ticks, " << pipeline.monitor().channels.size()
            << " channels -> " << (write_output ? output_path : std::string("(no --output: nothing written)")) << '\n';
  for (std::size_t i = 0; i < pipeline.inputs().size(); ++i) {
    if (const std::size_t n = pipeline.implausible_counts()[i]; n > 0) {
      const PipelineInput& in = pipeline.inputs()[i];
      summary_out << "  input " << in.name << ": " << n << " value" << (n == 1 ? "" : "s") << " outside its plausible_range ["
                  << format_number(in.plausible_min) << ", " << format_number(in.plausible_max) << "] " << in.unit
                  << " read as missing\n";
    }
  }
  // Silence is not health: say where channels could not be judged at all, one line for the
  // channels that share the same stretch (a virtual sensor's input out usually blinds them all).
  std::vector<bool> said(summary.unjudged_ticks.size(), false);
  const auto seconds = [&pipeline](std::size_t ticks) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", static_cast<double>(ticks) * pipeline.sample_period_s());
    return std::string(text);
  };
  for (std::size_t c = 0; c < summary.unjudged_ticks.size(); ++c) {
    const std::size_t n = summary.unjudged_ticks[c];
    if (n == 0 || said[c]) continue;
    std::string names;
    for (std::size_t d = c; d < summary.unjudged_ticks.size(); ++d) {
      if (!said[d] && summary.unjudged_ticks[d] == n &&
          summary.longest_unjudged_ticks[d] == summary.longest_unjudged_ticks[c] &&
          summary.longest_unjudged_start_s[d] == summary.longest_unjudged_start_s[c]) {
        names += (names.empty() ? "" : ", ") + pipeline.monitor().channels[d];
        said[d] = true;
      }
    }
    const std::size_t longest = summary.longest_unjudged_ticks[c];
    summary_out << "  " << names << ": not judged for " << n << " tick" << (n == 1 ? "" : "s") << " (" << seconds(n)
                << " s), the longest stretch " << seconds(longest) << " s from t = "
                << format_number(summary.longest_unjudged_start_s[c])
                << " s: the virtual sensor was not ready, or a fault could not be isolated, so a fault there "
                   "would go unseen\n";
  }
  bool any_flagged = false;
  for (std::size_t c = 0; c < summary.first_fault_time_s.size(); ++c) {
    if (std::isnan(summary.first_fault_time_s[c])) continue;
    any_flagged = true;
    summary_out << "  " << pipeline.monitor().channels[c] << ": fault first flagged at t = "
                << format_number(summary.first_fault_time_s[c]) << " s";
    // The types the channel's fault_type column showed while flagged, in code order.
    std::string types;
    for (const FaultTypeInfo& type : kFaultTypes) {
      if (type.type != FaultType::none && (summary.fault_types_seen[c] & fault_type_bit(type.type)) != 0) {
        types += (types.empty() ? "" : ", ") + std::string(type.name);
      }
    }
    if (!types.empty()) summary_out << "; fault type" << (types.find(',') == std::string::npos ? " " : "s ") << types;
    summary_out << '\n';
  }
  if (!any_flagged) summary_out << "  no channel flagged\n";
  return kExitOk;
}

}  // namespace ftsense::cli
