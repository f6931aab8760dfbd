#pragma once
// Figures over many scored runs (the demo's pipelines x scenarios), drawn with gnuplot:
//   - the confusion matrix of injected vs named fault types, one panel per pipeline: a faulty
//     channel counts once, in the row of its injected type and the column of the type it showed
//     most while the fault was active and flagged (metrics.hpp's "type shown"; "not flagged"
//     when it never was); the diagonal is the type named right;
//   - per scenario, each faulty channel's detection delay (log scale; a delay of 0 is drawn at
//     1 ms), filled when the type shown is the injected one, open when not, a cross when missed;
//     and the false alarms per scenario and pipeline.

#include <string>
#include <vector>

#include "ftsense/fault_type.hpp"
#include "ftsense/report/document.hpp"
#include "ftsense/report/metrics.hpp"

namespace ftsense::report {

struct ScoredScenario {
  std::string pipeline, scenario;
  std::vector<ChannelMetrics> channels;
};

struct Pipeline {
  std::string key;    // as in ScoredScenario::pipeline
  std::string label;  // in legends
};

// Rows: the injected types found, in code order; columns: the same, then other types named, then
// none ("not flagged"). counts[row][column] over the pipeline's runs.
struct Confusion {
  std::vector<FaultType> injected, named;
  std::vector<std::vector<int>> counts;
};
[[nodiscard]] Confusion confusion(const std::vector<ScoredScenario>& runs, const std::string& pipeline);

// Writes confusion_matrix.png and scenario_chart.png (with summary.gp and its data) into
// `out_dir`; returns them as document figures. Throws std::runtime_error when gnuplot fails.
[[nodiscard]] std::vector<Figure> write_summary_figures(const std::vector<ScoredScenario>& runs,
                                                        const std::vector<Pipeline>& pipelines,
                                                        const std::vector<std::string>& scenarios,
                                                        const std::string& out_dir);

}  // namespace ftsense::report
