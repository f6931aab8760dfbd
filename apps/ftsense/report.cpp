#include "report.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli.hpp"
#include "ftsense/io/csv_log.hpp"
#include "ftsense/report/run_output.hpp"
#include "ftsense/report/writers.hpp"

namespace ftsense::cli {

Report make_report(const std::string& run_path, const std::string& truth_path, const std::string& out_dir,
                   const ReportOptions& options) {
  const report::ScoredRun run = report::load_scored_run(run_path, truth_path);
  Report r;
  for (const report::RunChannel& ch : run.channels) {
    r.channels.push_back(report::channel_metrics(ch.name, *run.time, ch.series(), options.metrics));
    r.alarms.push_back(report::channel_alarms(ch.name, *run.time, ch[MonitorColumn::fault], ch[MonitorColumn::fault_type],
                                              options.metrics));
  }
  r.json = report::metrics_json(run, r.channels, r.alarms, options.metrics);
  r.table = report::metrics_table(run, r.channels, r.alarms, options.metrics);
  if (out_dir.empty()) return r;
  std::filesystem::create_directories(out_dir);
  std::ofstream(out_dir + "/metrics.json") << r.json.dump(2) << '\n';
  if (options.figures) {
    const report::DetectorBand band = options.thresholds.empty()
                                          ? report::DetectorBand{}
                                          : report::load_detector_band(options.thresholds, run.channels.size());
    r.figures = report::prepare_figures(run, r.channels, r.alarms, band, options.metrics, out_dir);
  }
  report::Document doc = report::run_document(options.title, run, r.channels, r.alarms, options.metrics, r.figures);
  std::ofstream(out_dir + "/report.md") << report::render_markdown(doc);
  // The rest needs nothing of the run: gnuplot draws, the page embeds what it drew.
  auto draw = [doc = std::move(doc), out_dir, figures = options.figures] {
    if (figures) report::draw_figures(out_dir);
    std::ofstream(out_dir + "/report.html") << report::render_html(doc, out_dir);
  };
  if (options.draw_in_background) r.drawn = std::async(std::launch::async, std::move(draw));
  else draw();
  return r;
}

int report_command(const std::vector<std::string>& args, const Context& context) {
  const std::string command = context.command("report");
  const std::vector<OptionSpec> specs{
      {"run", true, true, "output of '" + context.program + " run' (CSV)", 0, {}, FileArg::input},
      {"truth", true, false, "the log the run was made from, with truth/... columns (simulator logs)", 't', {},
       FileArg::input},
      {"output", true, true, "folder for metrics.json, report.md and the figures", 'o', {"out"}, FileArg::output_folder},
      {"warmup-s", true, false, "no false alarm is counted before this time (default 2)"},
      {"thresholds", true, false, "the '" + context.program + " calibrate' file the run used: the figures draw its band",
       0, {}, FileArg::input},
      {"no-figures", false, false, "skip the gnuplot figures"}};
  const auto options = parse_options(command, args, specs);
  if (options.count("help")) {
    std::cout << usage_text(command,
                            "Computes detection delays, fault estimate errors, recovered-signal RMSE,\n"
                            "false alarms and virtual sensor errors of a run against the truth, and\n"
                            "writes metrics.json, report.md, report.html (figures embedded) and the\n"
                            "figures (PNG). Without --truth (a real log) the alarms are listed, not scored.",
                            specs);
    return kExitOk;
  }
  ReportOptions report_options;
  if (const auto w = options.find("warmup-s"); w != options.end()) {
    char* end = nullptr;
    report_options.metrics.warmup_s = std::strtod(w->second.c_str(), &end);
    if (end == w->second.c_str() || *end != '\0' || !(report_options.metrics.warmup_s >= 0.0)) {
      throw UsageError{command + ": --warmup-s = '" + w->second + "' violates >= 0"};
    }
  }
  report_options.figures = !options.count("no-figures");
  if (options.count("thresholds")) report_options.thresholds = options.at("thresholds");
  const std::string truth = options.count("truth") ? options.at("truth") : std::string();
  std::error_code ec;
  if (std::filesystem::exists(options.at("output"), ec) && !std::filesystem::is_directory(options.at("output"), ec)) {
    throw UsageError{"error: " + options.at("output") + ": --output is a folder for metrics.json, report.md and the "
                     "figures, and this is a file; give a folder name"};
  }
  require_existing_files(command, options, specs, {"run", "truth", "thresholds"});
  try {
    const Report r = make_report(options.at("run"), truth, options.at("output"), report_options);
    std::cout << r.table << "wrote " << options.at("output") << "/report.md and " << options.at("output")
              << "/report.html\n";
  } catch (const io::LogError& e) {
    throw UsageError{std::string("error: ") + e.what()};
  }
  return kExitOk;
}

}  // namespace ftsense::cli
