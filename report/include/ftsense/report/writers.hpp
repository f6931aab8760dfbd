#pragma once
// What a scored run is written as: metrics.json, the terminal table and the report document
// (report.md and report.html, document.hpp). The metrics are computed in metrics.hpp, the alarms
// of a run without truth in alarms.hpp, the figures drawn in figures.hpp.
//
// Without truth (every real log) nothing is scored: no fault is known, so an alarm is neither a
// detection nor a false alarm. The writers then list the alarms (channel, start, end, the type
// named) and say so, instead of counting "0 of 0 faulty channels detected".

#include <string>
#include <vector>

#include "ftsense/params.hpp"
#include "ftsense/report/alarms.hpp"
#include "ftsense/report/document.hpp"
#include "ftsense/report/figures.hpp"
#include "ftsense/report/metrics.hpp"
#include "ftsense/report/run_output.hpp"

namespace ftsense::report {

// "-" for none, else the type's name.
[[nodiscard]] std::string type_label(FaultType type);

// Everything, as written to metrics.json. Without truth: per channel its alarms count and flagged
// time, the list of alarms, and a summary {"scored": false, ...}. `alarms` per run channel.
[[nodiscard]] Json metrics_json(const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                                const std::vector<std::vector<Alarm>>& alarms, const MetricOptions& options);
// The terminal summary: with truth one row per channel and a closing line; without truth the
// alarms, one row each, and how many channels they flag.
[[nodiscard]] std::string metrics_table(const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                                        const std::vector<std::vector<Alarm>>& alarms, const MetricOptions& options);
// The terminal table's columns as a document table (one row per channel, with truth).
[[nodiscard]] Table metrics_summary_table(const std::string& unit, const std::vector<ChannelMetrics>& channels);
// The run's report: what was scored, the table (or the alarms), and the figures (files in the
// report's folder).
[[nodiscard]] Document run_document(const std::string& title, const ScoredRun& run,
                                    const std::vector<ChannelMetrics>& channels,
                                    const std::vector<std::vector<Alarm>>& alarms, const MetricOptions& options,
                                    const std::vector<RunFigure>& figures);

// Fixed-point text with `digits` decimals; "-" for NaN.
[[nodiscard]] std::string fixed(double v, int digits);

}  // namespace ftsense::report
