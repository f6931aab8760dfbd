#pragma once
// The figures of one run (gnuplot, pngcairo): the paper's Figs. 4-7 and a fault-type timeline.
//
// With truth, each panel draws the true signal dashed on top of the virtual / recovered lines,
// shades the injected fault's stretches, and marks the onset (red) and the first flag (green);
// the fault estimate panels draw the detector's band (centre +- threshold) when the thresholds
// file of `ftsense calibrate` is given. Without truth (a real log) nothing was injected: the
// figures say "measured" instead of "true", show the estimated fault alone, and shade the alarms.
//
// Which channels the per-channel figures draw (figure_channels): with truth, the faulty channels,
// then those with false alarms; without truth, the flagged channels (an alarm after warm-up).
// At most kMaxPanels of them, in channel order; when fewer than kMinPanels, the figure is filled
// up with the other channels whose filtered fault estimate came nearest to the detector's band
// after warm-up (|estimate - centre| / threshold, or |estimate| when no threshold is known), so a
// figure of a quiet run shows its closest calls. Every figure is listed, with its channels and
// why each was drawn, in figures.json beside the PNGs.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/report/alarms.hpp"
#include "ftsense/report/metrics.hpp"
#include "ftsense/report/run_output.hpp"

namespace ftsense::report {

inline constexpr std::size_t kMinPanels = 4;
inline constexpr std::size_t kMaxPanels = 8;

// The detector's band per run channel: flagged when |estimate - centre| > threshold. Empty when
// unknown (no thresholds file, or a pipeline whose detector has no single threshold).
struct DetectorBand {
  std::vector<double> centre, threshold;
  std::string source;  // the file it was read from
  [[nodiscard]] bool known() const { return !threshold.empty(); }
};
// From a thresholds file of `ftsense calibrate`: the first stage whose "thresholds" has one value
// (for every channel) or one per channel; "centers" when present (calibrate --band), else 0.
// Throws ConfigError on a file that has no such stage.
[[nodiscard]] DetectorBand load_detector_band(const std::string& thresholds_path, std::size_t channels);

enum class FigureKind { virtual_sensor, fault_estimate, recovered, flags, fault_types };

struct FigureKindInfo {
  FigureKind kind;
  std::string_view key;                          // in figures.json
  std::string_view file, file_without_truth;     // PNG names
  std::string_view title, title_without_truth;
  std::string_view caption, caption_without_truth;  // what it shows
};

inline constexpr std::array<FigureKindInfo, 5> kFigureKinds{{
    {FigureKind::virtual_sensor, "virtual_sensor", "fig4_virtual_vs_true.png", "fig4_virtual_vs_measured.png",
     "Virtual vs true contact force (paper Fig. 4)", "Virtual vs measured contact force (paper Fig. 4, no truth)",
     "Measured reading (grey), the virtual sensor's estimate (blue) and the true force (black, dashed, on top). "
     "Shaded: the injected fault; red dashed line: its onset; green dotted line: the first flag.",
     "Measured reading (grey) and the virtual sensor's estimate (blue); no truth is known. Shaded: the alarms."},
    {FigureKind::fault_estimate, "fault_estimate", "fig5_fault_estimate.png", "fig5_fault_estimate.png",
     "Injected vs estimated fault (paper Fig. 5)", "Estimated fault (paper Fig. 5, no truth: nothing injected)",
     "The fault estimate before (light) and after (blue) the low-pass, the detector's band (red, centre +- "
     "threshold, when the thresholds file is known) and the injected fault, measured - true (black, dashed, on top).",
     "The fault estimate before (light) and after (blue) the low-pass and the detector's band (red, when the "
     "thresholds file is known). Without truth there is no injected fault to compare it with. Shaded: the alarms."},
    {FigureKind::recovered, "recovered", "fig6_recovered.png", "fig6_recovered_vs_measured.png",
     "Recovered vs true signal (paper Fig. 6)", "Recovered vs measured signal (paper Fig. 6, no truth)",
     "Measured reading (grey), the recovered signal handed on (green) and the true force (black, dashed, on top).",
     "Measured reading (grey) and the recovered signal handed on (green). Shaded: the alarms."},
    {FigureKind::flags, "flags", "fig7_detection_flags.png", "fig7_detection_flags.png",
     "Detection flags (paper Fig. 7)", "Detection flags (paper Fig. 7, no truth)",
     "Every channel's flag (raised = flagged faulty); shaded: the injected fault's stretches.",
     "Every channel's flag (raised = flagged faulty); no truth is known, so no alarm is scored."},
    {FigureKind::fault_types, "fault_types", "fig8_fault_types.png", "fig8_fault_types.png",
     "Fault types over time", "Fault types named over time (no truth)",
     "Per channel, the fault type the pipeline names while it flags the channel (upper strip) and the injected "
     "fault type (lower strip, lighter), one colour per type; stretches shorter than 50 ms are widened to show.",
     "Per channel, the fault type the pipeline names while it flags the channel, one colour per type; "
     "stretches shorter than 50 ms are widened to show."},
}};

[[nodiscard]] const FigureKindInfo& figure_kind_info(FigureKind kind);

// The colour that draws a fault type in every figure, as 0xRRGGBB.
[[nodiscard]] unsigned fault_type_colour(FaultType type);

struct Panel {
  std::size_t channel = 0;  // index into ScoredRun::channels
  std::string why;          // "injected offset", "flagged: 2 alarms", "not flagged: nearest to its band"
};
[[nodiscard]] std::vector<Panel> figure_channels(const ScoredRun& run, const std::vector<ChannelMetrics>& metrics,
                                                 const std::vector<std::vector<Alarm>>& alarms,
                                                 const DetectorBand& band, const MetricOptions& options);

struct RunFigure {
  FigureKind kind;
  std::string file, title, caption;
  std::vector<std::string> channels;  // drawn, in panel order
  std::vector<std::string> why;       // per channel drawn, why (per-channel figures; else empty)
};

// Writes what draws every figure into `out_dir` (figures.dat, types.dat, the script figures.gp
// and figures.json) and returns the figures; draw_figures(out_dir) then draws the PNGs (it needs
// nothing of the run, so it may run while the next run is scored). `alarms` per run channel
// (drawn without truth).
[[nodiscard]] std::vector<RunFigure> prepare_figures(const ScoredRun& run, const std::vector<ChannelMetrics>& metrics,
                                                     const std::vector<std::vector<Alarm>>& alarms,
                                                     const DetectorBand& band, const MetricOptions& options,
                                                     const std::string& out_dir);
// Runs gnuplot on out_dir/figures.gp; throws std::runtime_error when it fails.
void draw_figures(const std::string& out_dir);
// prepare_figures, then draw_figures.
[[nodiscard]] std::vector<RunFigure> write_figures(const ScoredRun& run, const std::vector<ChannelMetrics>& metrics,
                                                   const std::vector<std::vector<Alarm>>& alarms,
                                                   const DetectorBand& band, const MetricOptions& options,
                                                   const std::string& out_dir);

// Runs `gnuplot script`, its messages into `log`; throws std::runtime_error naming the log when
// it fails.
void run_gnuplot(const std::string& script, const std::string& log);

}  // namespace ftsense::report
