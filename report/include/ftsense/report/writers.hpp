#pragma once
// What a scored run is written as: metrics.json, the terminal table, report.md and the paper's
// four figures (gnuplot PNG). The metrics themselves are computed in metrics.hpp.

#include <string>
#include <vector>

#include "ftsense/params.hpp"
#include "ftsense/report/metrics.hpp"
#include "ftsense/report/run_output.hpp"

namespace ftsense::report {

// "-" for none, else the type's name.
[[nodiscard]] std::string type_label(FaultType type);

// Everything, as written to metrics.json.
[[nodiscard]] Json metrics_json(const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                                const MetricOptions& options);
// The terminal summary: one row per channel and a closing line.
[[nodiscard]] std::string metrics_table(const std::string& unit, const std::vector<ChannelMetrics>& channels,
                                        const MetricOptions& options);
// report.md: title, what was scored, the table, and the figures (file names in `out_dir`).
[[nodiscard]] std::string metrics_markdown(const std::string& title, const ScoredRun& run,
                                           const std::vector<ChannelMetrics>& channels, const MetricOptions& options,
                                           const std::vector<std::string>& figures);
// Draws the figures into `out_dir` with gnuplot (figures.dat, figures.gp, the PNGs); returns the
// PNG file names. Throws std::runtime_error when gnuplot fails.
[[nodiscard]] std::vector<std::string> write_figures(const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                                                     const std::string& out_dir);

}  // namespace ftsense::report
