#include "ftsense/report/writers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace ftsense::report {

namespace {

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

std::string delay_text(const ChannelMetrics& m) {
  if (!m.faulty()) return "-";
  return std::isfinite(m.detection_delay_s) ? fixed(m.detection_delay_s, 3) : "missed";
}

std::size_t alarm_count(const std::vector<std::vector<Alarm>>& alarms, std::size_t* channels_flagged) {
  std::size_t count = 0;
  *channels_flagged = 0;
  for (const auto& a : alarms) {
    count += a.size();
    *channels_flagged += !a.empty();
  }
  return count;
}

std::string alarm_end_text(const Alarm& a) { return a.open ? "end of log" : fixed(a.end_s, 3); }

// The closing line without truth: how many alarms, on how many channels, or "no channel flagged".
std::string alarms_sentence(const std::vector<std::vector<Alarm>>& alarms, const MetricOptions& options) {
  std::size_t flagged = 0;
  const std::size_t count = alarm_count(alarms, &flagged);
  std::ostringstream os;
  if (count == 0) {
    os << "No channel flagged after the " << options.warmup_s << " s warm-up (" << alarms.size() << " channels).";
  } else {
    os << count << " alarm" << (count > 1 ? "s" : "") << " on " << flagged << " of " << alarms.size()
       << " channels after the " << options.warmup_s << " s warm-up; not scored: without truth no fault is known, "
       << "so none is called a detection or a false alarm.";
  }
  return os.str();
}

}  // namespace

std::string fixed(double v, int digits) {
  if (std::isnan(v)) return "-";
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

std::string type_label(FaultType type) { return type == FaultType::none ? "-" : std::string(to_string(type)); }

Json metrics_json(const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                  const std::vector<std::vector<Alarm>>& alarms, const MetricOptions& options) {
  const auto& time = *run.time;
  const double duration = time.empty() ? 0.0 : time.back() - time.front();
  Json j = {{"run", run.run.path},
            {"truth", run.truth.path},
            {"warmup_s", options.warmup_s},
            {"settle_s", options.settle_s},
            {"readmit_s", options.readmit_s},
            {"duration_s", duration},
            {"unit", run.unit},
            {"channels", Json::array()}};
  if (!run.has_truth()) {
    j["alarms"] = Json::array();
    for (std::size_t c = 0; c < channels.size(); ++c) {
      double flagged_s = 0.0;
      for (const Alarm& a : alarms[c]) {
        flagged_s += a.end_s - a.start_s;
        j["alarms"].push_back({{"channel", a.channel},
                               {"start_s", a.start_s},
                               {"end_s", a.end_s},
                               {"open", a.open},
                               {"type", std::string(to_string(a.type))}});
      }
      j["channels"].push_back({{"channel", channels[c].channel},
                               {"alarms", alarms[c].size()},
                               {"flagged_time_s", flagged_s}});
    }
    std::size_t flagged = 0;
    const std::size_t count = alarm_count(alarms, &flagged);
    j["summary"] = {{"scored", false}, {"alarms", count}, {"channels_flagged", flagged}};
    return j;
  }
  for (const auto& m : channels) {
    j["channels"].push_back({{"channel", m.channel},
                             {"injected_type", type_label(m.injected_type)},
                             {"onset_s", number_or_null(m.onset_s)},
                             {"end_s", number_or_null(m.end_s)},
                             {"detection_delay_s", number_or_null(m.detection_delay_s)},
                             {"detected_type", type_label(m.detected_type)},
                             {"shown_type", type_label(m.shown_type)},
                             {"type_correct", m.faulty() ? Json(m.type_correct()) : Json(nullptr)},
                             {"fault_estimate_rmse", number_or_null(m.fault_estimate_rmse)},
                             {"recovered_rmse", number_or_null(m.recovered_rmse)},
                             {"measured_rmse", number_or_null(m.measured_rmse)},
                             {"readmission_s", number_or_null(m.readmission_s)},
                             {"fault_ended", m.faulty() ? Json(m.fault_ended) : Json(nullptr)},
                             {"loaded_delay_s", number_or_null(m.loaded_delay_s)},
                             {"fault_size", number_or_null(m.fault_size)},
                             {"fault_slope_per_s", number_or_null(m.fault_slope)},
                             {"false_alarms", m.false_alarms},
                             {"false_alarm_time_s", m.false_alarm_time_s},
                             {"vfs_rmse", number_or_null(m.vfs_rmse)},
                             {"vfs_p95", number_or_null(m.vfs_p95)},
                             {"vfs_missing_share", number_or_null(m.vfs_missing_share)}});
  }
  const RunTotals t = totals(channels);
  j["summary"] = {{"faulty_channels", t.faulty_channels},
                  {"detected", t.detected},
                  {"types_correct", t.types_correct},
                  {"false_alarms_after_warmup", t.false_alarms}};
  return j;
}

std::string metrics_table(const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                          const std::vector<std::vector<Alarm>>& alarms, const MetricOptions& options) {
  std::ostringstream table;
  const std::string& unit = run.unit;
  if (!run.has_truth()) {
    table << "No truth given: the alarms are listed, not scored.\n";
    table << std::left << std::setw(12) << "channel" << std::right << std::setw(12) << "alarm from s" << std::setw(12)
          << "to s" << "  " << "type named\n";
    for (const auto& a : alarms) {
      for (const Alarm& x : a) {
        table << std::left << std::setw(12) << x.channel << std::right << std::setw(12) << fixed(x.start_s, 3)
              << std::setw(12) << alarm_end_text(x) << "  " << to_string(x.type) << '\n';
      }
    }
    table << alarms_sentence(alarms, options) << '\n';
    return table.str();
  }
  table << std::left << std::setw(12) << "channel" << std::setw(12) << "injected" << std::right << std::setw(9)
        << "onset s" << std::setw(10) << "delay s" << std::setw(12) << "est.err " + unit << std::setw(12)
        << "recov " + unit << std::setw(12) << "meas " + unit << std::setw(8) << "alarms" << std::setw(12)
        << "VFS rms " + unit << std::setw(12) << "VFS p95 " + unit << '\n';
  for (const auto& m : channels) {
    table << std::left << std::setw(12) << m.channel << std::setw(12) << type_label(m.injected_type) << std::right
          << std::setw(9) << fixed(m.onset_s, 2) << std::setw(10) << delay_text(m) << std::setw(12)
          << fixed(m.fault_estimate_rmse, 1) << std::setw(12) << fixed(m.recovered_rmse, 1) << std::setw(12)
          << fixed(m.measured_rmse, 1) << std::setw(8) << m.false_alarms << std::setw(12) << fixed(m.vfs_rmse, 1)
          << std::setw(12) << fixed(m.vfs_p95, 1) << '\n';
  }
  const RunTotals t = totals(channels);
  table << "detected " << t.detected << " of " << t.faulty_channels << " faulty channels; " << t.false_alarms
        << " false alarms after the " << options.warmup_s << " s warm-up\n";
  return table.str();
}

Table metrics_summary_table(const std::string& unit, const std::vector<ChannelMetrics>& channels) {
  Table t{{"channel", "injected", "onset [s]", "delay [s]", "est. err [" + unit + "]", "recovered [" + unit + "]",
           "measured [" + unit + "]", "false alarms", "VFS RMS [" + unit + "]", "VFS p95 [" + unit + "]"},
          {}};
  for (const auto& m : channels) {
    t.rows.push_back({m.channel, type_label(m.injected_type), fixed(m.onset_s, 2), delay_text(m),
                      fixed(m.fault_estimate_rmse, 1), fixed(m.recovered_rmse, 1), fixed(m.measured_rmse, 1),
                      std::to_string(m.false_alarms), fixed(m.vfs_rmse, 1), fixed(m.vfs_p95, 1)});
  }
  return t;
}

Document run_document(const std::string& title, const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                      const std::vector<std::vector<Alarm>>& alarms, const MetricOptions& options,
                      const std::vector<RunFigure>& figures) {
  Document doc;
  doc.title = title;
  std::ostringstream intro;
  if (run.has_truth()) {
    intro << "Run: `" << run.run.path << "`, truth: `" << run.truth.path << "`. Warm-up " << options.warmup_s
          << " s (no false alarm is counted before it, nor within " << options.readmit_s
          << " s after a fault ends); fault estimate error measured from " << options.settle_s
          << " s after onset. Units: " << run.unit << ".";
    doc.paragraph(intro.str());
    Table t{{"channel", "injected", "onset [s]", "detection delay [s]", "type shown", "re-admitted after [s]",
             "fault estimate RMSE", "recovered RMSE", "measured RMSE", "false alarms", "false-alarm time [s]",
             "VFS RMSE", "VFS p95"},
            {}};
    for (const auto& m : channels) {
      t.rows.push_back({m.channel, type_label(m.injected_type), fixed(m.onset_s, 2), delay_text(m),
                        type_label(m.shown_type), fixed(m.readmission_s, 2), fixed(m.fault_estimate_rmse, 1),
                        fixed(m.recovered_rmse, 1), fixed(m.measured_rmse, 1), std::to_string(m.false_alarms),
                        fixed(m.false_alarm_time_s, 2), fixed(m.vfs_rmse, 1), fixed(m.vfs_p95, 1)});
    }
    doc.table(std::move(t));
    const RunTotals totals_ = totals(channels);
    doc.paragraph("Detected " + std::to_string(totals_.detected) + " of " + std::to_string(totals_.faulty_channels) +
                  " faulty channels; " + std::to_string(totals_.false_alarms) + " false alarms after the warm-up.");
  } else {
    intro << "Run: `" << run.run.path << "`. No truth was given (a real log): no fault is known to have happened, "
          << "so the alarms are listed, not scored; none is called a detection or a false alarm. Alarms that end "
          << "within the " << options.warmup_s << " s warm-up are not listed. Units: " << run.unit << ".";
    doc.paragraph(intro.str());
    Table t{{"channel", "alarm from [s]", "to [s]", "duration [s]", "type named"}, {}};
    for (const auto& a : alarms) {
      for (const Alarm& x : a) {
        t.rows.push_back({x.channel, fixed(x.start_s, 3), alarm_end_text(x), fixed(x.end_s - x.start_s, 3),
                          std::string(to_string(x.type))});
      }
    }
    if (!t.rows.empty()) doc.table(std::move(t));
    doc.paragraph(alarms_sentence(alarms, options));
  }
  if (figures.empty()) return doc;
  doc.heading("Figures");
  const RunFigure& first = figures.front();
  std::string which = run.has_truth() ? "The per-channel figures draw the faulty channels, then those with false alarms"
                                      : "The per-channel figures draw the flagged channels";
  which += " (at most " + std::to_string(kMaxPanels) + "); when fewer than " + std::to_string(kMinPanels) +
           ", the channels whose fault estimate came nearest to the detector's band fill up the figure. Drawn: ";
  for (std::size_t i = 0; i < first.channels.size(); ++i) {
    which += (i ? "; " : "") + first.channels[i] + (i < first.why.size() ? " (" + first.why[i] + ")" : "");
  }
  which += ".";
  doc.paragraph(which);
  for (const RunFigure& f : figures) doc.figure({f.file, f.title, f.caption});
  return doc;
}

}  // namespace ftsense::report
