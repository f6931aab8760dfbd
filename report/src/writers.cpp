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

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fixed(double v, int digits) {
  if (std::isnan(v)) return "-";
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

std::string delay_text(const ChannelMetrics& m) {
  if (!m.faulty()) return "-";
  return std::isfinite(m.detection_delay_s) ? fixed(m.detection_delay_s, 3) : "missed";
}

// Writes `columns` (time first) as a whitespace data file, decimated to at most ~4000 rows.
void write_data(const std::string& path, const std::vector<const std::vector<double>*>& columns) {
  std::ofstream f(path);
  const std::size_t n = columns.front()->size();
  const std::size_t stride = std::max<std::size_t>(1, n / 4000);
  for (std::size_t k = 0; k < n; k += stride) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double v = (*columns[c])[k];
      f << (c ? " " : "");
      if (std::isfinite(v)) f << v;
      else f << "NaN";
    }
    f << '\n';
  }
}

}  // namespace

std::string type_label(FaultType type) { return type == FaultType::none ? "-" : std::string(to_string(type)); }

Json metrics_json(const ScoredRun& run, const std::vector<ChannelMetrics>& channels, const MetricOptions& options) {
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
                             {"false_alarms", m.false_alarms},
                             {"false_alarm_time_s", m.false_alarm_time_s},
                             {"vfs_rmse", number_or_null(m.vfs_rmse)},
                             {"vfs_p95", number_or_null(m.vfs_p95)}});
  }
  const RunTotals t = totals(channels);
  j["summary"] = {{"faulty_channels", t.faulty_channels},
                  {"detected", t.detected},
                  {"types_correct", t.types_correct},
                  {"false_alarms_after_warmup", t.false_alarms}};
  return j;
}

std::string metrics_table(const std::string& unit, const std::vector<ChannelMetrics>& channels,
                          const MetricOptions& options) {
  std::ostringstream table;
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

std::string metrics_markdown(const std::string& title, const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                             const MetricOptions& options, const std::vector<std::string>& figures) {
  std::ostringstream md;
  md << "# " << title << "\n\nRun: `" << run.run.path << "`"
     << (run.has_truth() ? ", truth: `" + run.truth.path + "`" : "") << ". Warm-up " << options.warmup_s
     << " s (no false alarm is counted before it, nor within " << options.readmit_s
     << " s after a fault ends); fault estimate error "
     << "measured from " << options.settle_s << " s after onset. Units: " << run.unit << ".\n\n";
  md << "| channel | injected | onset [s] | detection delay [s] | type shown | re-admitted after [s] | "
        "fault estimate RMSE | recovered RMSE | measured RMSE | false alarms | false-alarm time [s] | VFS RMSE | "
        "VFS p95 |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& m : channels) {
    md << "| " << m.channel << " | " << type_label(m.injected_type) << " | " << fixed(m.onset_s, 2) << " | "
       << delay_text(m) << " | " << type_label(m.shown_type) << " | " << fixed(m.readmission_s, 2) << " | "
       << fixed(m.fault_estimate_rmse, 1) << " | " << fixed(m.recovered_rmse, 1) << " | "
       << fixed(m.measured_rmse, 1) << " | " << m.false_alarms << " | " << fixed(m.false_alarm_time_s, 2) << " | "
       << fixed(m.vfs_rmse, 1) << " | " << fixed(m.vfs_p95, 1) << " |\n";
  }
  const RunTotals t = totals(channels);
  md << "\nDetected " << t.detected << " of " << t.faulty_channels << " faulty channels; " << t.false_alarms
     << " false alarms after the warm-up.\n";
  for (const auto& f : figures) md << "\n![" << f << "](" << f << ")\n";
  return md.str();
}

std::vector<std::string> write_figures(const ScoredRun& run, const std::vector<ChannelMetrics>& channels,
                                       const std::string& out_dir) {
  const auto& time = *run.time;
  // The faulty channels, or the first four when none is.
  std::vector<const RunChannel*> shown;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (channels[c].faulty()) shown.push_back(&run.channels[c]);
  }
  if (shown.empty()) {
    for (std::size_t i = 0; i < std::min<std::size_t>(4, run.channels.size()); ++i) shown.push_back(&run.channels[i]);
  }
  // One data file for the channels shown: t, then per channel measured, virtual, truth,
  // fault_estimate, fault_estimate_raw, injected, recovered; then every channel's flag.
  std::vector<std::vector<double>> derived;
  derived.reserve(shown.size());
  std::vector<const std::vector<double>*> cols{&time};
  const std::vector<double> nan_column(time.size(), kNaN);
  for (const RunChannel* ch : shown) {
    const auto& measured = (*ch)[MonitorColumn::measured];
    cols.push_back(&measured);
    cols.push_back(&(*ch)[MonitorColumn::virtual_value]);
    cols.push_back(ch->true_force != nullptr ? ch->true_force : &nan_column);
    cols.push_back(&(*ch)[MonitorColumn::fault_estimate]);
    cols.push_back(ch->raw_fault_estimate != nullptr ? ch->raw_fault_estimate : &nan_column);
    derived.emplace_back(time.size(), kNaN);
    if (ch->true_force != nullptr) {
      for (std::size_t k = 0; k < time.size(); ++k) derived.back()[k] = measured[k] - (*ch->true_force)[k];
    }
    cols.push_back(&derived.back());
    cols.push_back(&(*ch)[MonitorColumn::recovered]);
  }
  for (const RunChannel& ch : run.channels) cols.push_back(&ch[MonitorColumn::fault]);
  write_data(out_dir + "/figures.dat", cols);

  std::vector<std::string> figures;
  const std::size_t per = 7;
  auto column = [&](std::size_t channel_index, std::size_t offset) { return 2 + channel_index * per + offset; };
  std::ostringstream gp;
  gp << "set datafile missing 'NaN'\nset grid\nset key top right box opaque\nset xlabel 'time [s]'\n"
     << "set terminal pngcairo noenhanced size 1400," << 330 * shown.size() << " font 'DejaVu Sans,11'\n";
  auto multiplot = [&](const std::string& file, const std::string& title, const std::string& ylabel,
                       const std::vector<std::pair<std::size_t, std::string>>& series) {
    gp << "set output '" << out_dir << "/" << file << "'\n"
       << "set multiplot layout " << shown.size() << ",1 title '" << title << "'\n"
       << "set ylabel '" << ylabel << "'\n";
    for (std::size_t i = 0; i < shown.size(); ++i) {
      gp << "set title '" << shown[i]->name << "'\nplot ";
      for (std::size_t s = 0; s < series.size(); ++s) {
        gp << (s ? ", " : "") << "'" << out_dir << "/figures.dat' using 1:" << column(i, series[s].first)
           << " with lines lw 1.5 title '" << series[s].second << "'";
      }
      gp << '\n';
    }
    gp << "unset multiplot\n";
    figures.push_back(file);
  };
  const std::string unit = run.unit;
  multiplot("fig4_virtual_vs_true.png", "Virtual vs true contact force (paper Fig. 4)", "force [" + unit + "]",
            {{0, "measured"}, {2, "true"}, {1, "virtual (VFS)"}});
  multiplot("fig5_fault_estimate.png", "Injected vs estimated fault (paper Fig. 5)", "fault [" + unit + "]",
            {{5, "injected (measured - true)"}, {4, "estimate, unfiltered"}, {3, "estimate, filtered"}});
  multiplot("fig6_recovered.png", "Recovered vs true signal (paper Fig. 6)", "force [" + unit + "]",
            {{0, "measured"}, {2, "true"}, {6, "recovered"}});
  const std::size_t n = run.channels.size();
  gp << "set terminal pngcairo noenhanced size 1400," << 120 + 40 * n << " font 'DejaVu Sans,11'\n"
     << "set output '" << out_dir << "/fig7_detection_flags.png'\n"
     << "set title 'Detection flags (paper Fig. 7): raised = channel flagged as faulty'\nset ylabel ''\n"
     << "set ytics (";
  for (std::size_t c = 0; c < n; ++c) gp << (c ? ", " : "") << "'" << run.channels[c].name << "' " << c;
  gp << ")\nset yrange [-0.5:" << n << "]\nset key off\nplot ";
  for (std::size_t c = 0; c < n; ++c) {
    gp << (c ? ", " : "") << "'" << out_dir << "/figures.dat' using 1:($" << 2 + shown.size() * per + c << "*0.7+" << c
       << ") with steps lw 2";
  }
  gp << '\n';
  figures.push_back("fig7_detection_flags.png");
  const std::string script = out_dir + "/figures.gp";
  std::ofstream(script) << gp.str();
  const std::string command = "gnuplot '" + script + "' 2> '" + out_dir + "/gnuplot.log'";
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("gnuplot failed (see " + out_dir + "/gnuplot.log); install gnuplot-nox, or use --no-figures");
  }
  return figures;
}

}  // namespace ftsense::report
