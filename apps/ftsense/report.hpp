#pragma once
// `ftsense report`: scores a run against its truth (report/: metrics, loading, writers) and
// writes metrics.json, report.md, report.html and the figures. Without truth (a real log) it
// lists the alarms instead of scoring them (report/alarms.hpp).

#include <future>
#include <string>
#include <vector>

#include "ftsense/app/app.hpp"
#include "ftsense/params.hpp"
#include "ftsense/report/alarms.hpp"
#include "ftsense/report/figures.hpp"
#include "ftsense/report/metrics.hpp"

namespace ftsense::cli {

struct ReportOptions {
  report::MetricOptions metrics;
  std::string title = "ftsense run";
  bool figures = true;
  std::string thresholds;  // the calibrate file the run used: its band is drawn (empty: none)
  bool draw_in_background = false;  // gnuplot and report.html in Report::drawn, while the caller goes on
};

struct Report {
  std::vector<report::ChannelMetrics> channels;
  std::vector<std::vector<report::Alarm>> alarms;  // per channel, after warm-up
  std::vector<report::RunFigure> figures;          // drawn (empty without out_dir or figures)
  std::future<void> drawn;  // with draw_in_background: get() waits for the PNGs and report.html
  Json json;                      // everything, as written to metrics.json
  std::string table;              // the terminal summary
};

// Computes the metrics (or, without truth, lists the alarms); with out_dir non-empty also writes
// metrics.json, report.md, report.html and (if options.figures) the figures there. Throws io::LogError / ConfigError on bad files.
Report make_report(const std::string& run_path, const std::string& truth_path, const std::string& out_dir,
                   const ReportOptions& options);

int report_command(const std::vector<std::string>& args, const app::Context& context);

}  // namespace ftsense::cli
