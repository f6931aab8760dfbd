#pragma once
// `ftsense report`: scores a run against its truth (report/: metrics, loading, writers) and
// writes metrics.json, report.md and the figures.

#include <string>
#include <vector>

#include "ftsense/app/app.hpp"
#include "ftsense/params.hpp"
#include "ftsense/report/metrics.hpp"

namespace ftsense::cli {

struct ReportOptions {
  report::MetricOptions metrics;
  std::string title = "ftsense run";
  bool figures = true;
};

struct Report {
  std::vector<report::ChannelMetrics> channels;
  Json json;                      // everything, as written to metrics.json
  std::string table;              // the terminal summary
};

// Computes the metrics; with out_dir non-empty also writes metrics.json, report.md and (if
// options.figures) the four figures there. Throws io::LogError / ConfigError on bad files.
Report make_report(const std::string& run_path, const std::string& truth_path, const std::string& out_dir,
                   const ReportOptions& options);

int report_command(const std::vector<std::string>& args, const app::Context& context);

}  // namespace ftsense::cli
