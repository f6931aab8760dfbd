#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

#include "cli.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/io/csv_log.hpp"

namespace ftsense::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A whole CSV log in memory, column by column.
struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;

  static Table load(const std::string& path) {
    io::CsvLogReader reader(path);
    Table t;
    t.names = reader.columns();
    t.columns.resize(t.names.size());
    std::vector<double> row;
    while (reader.next(row)) {
      for (std::size_t c = 0; c < row.size(); ++c) t.columns[c].push_back(row[c]);
    }
    return t;
  }
  [[nodiscard]] const std::vector<double>* find(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) return &columns[i];
    }
    return nullptr;
  }
  [[nodiscard]] const std::vector<double>& at(const std::string& name, const std::string& file) const {
    if (const auto* c = find(name)) return *c;
    throw ConfigError(file, "has no column '" + name + "'; " + suggest(name, names).substr(0, 200));
  }
  [[nodiscard]] std::size_t rows() const { return columns.empty() ? 0 : columns[0].size(); }
};

double rms(const std::vector<double>& v) {
  if (v.empty()) return kNaN;
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return kNaN;
  const auto k = static_cast<std::size_t>(std::clamp(p * static_cast<double>(v.size() - 1), 0.0,
                                                     static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

std::string fixed(double v, int digits) {
  if (std::isnan(v)) return "-";
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

// Whether the type shown names the injected one (null for a healthy channel).
Json faulty_type_correct(const ChannelMetrics& m) {
  if (m.injected_type == 0) return nullptr;
  return m.shown_type == m.injected_type;
}

std::string type_name(int code) {
  const auto type = fault_type_from_code(code);
  return type == FaultType::none ? "-" : type ? std::string(to_string(*type)) : "unknown";
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

Report make_report(const std::string& run_path, const std::string& truth_path, const std::string& out_dir,
                   const ReportOptions& options) {
  const Table run = Table::load(run_path);
  Table truth;
  const bool has_truth = !truth_path.empty();
  if (has_truth) {
    truth = Table::load(truth_path);
    if (truth.rows() != run.rows()) {
      throw ConfigError(truth_path, "has " + std::to_string(truth.rows()) + " rows but " + run_path + " has " +
                                        std::to_string(run.rows()) + "; give the log the run was made from");
    }
  }
  const std::vector<double>& time = run.at("time_s", run_path);
  std::vector<std::string> channels;
  for (const auto& n : run.names) {
    const std::string suffix = "/fault_type";
    if (n.size() > suffix.size() && n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0) {
      channels.push_back(n.substr(0, n.size() - suffix.size()));
    }
  }
  if (channels.empty()) throw ConfigError(run_path, "has no <channel>/fault_type columns; is it an output of ftsense run?");
  const double t0 = time.empty() ? 0.0 : time.front();
  const double t_end = time.empty() ? 0.0 : time.back();
  const double dt = time.size() > 1 ? (t_end - t0) / static_cast<double>(time.size() - 1) : 1e-3;

  // The unit suffix of the measured-type columns ("N" in <channel>/measured_N).
  std::string unit;
  for (const auto& n : run.names) {
    const std::string prefix = channels.front() + "/measured_";
    if (n.rfind(prefix, 0) == 0) unit = n.substr(prefix.size());
  }
  if (unit.empty()) throw ConfigError(run_path, "has no " + channels.front() + "/measured_<unit> column");
  auto channel_column = [&](const std::string& ch, const std::string& quantity) -> const std::vector<double>& {
    return run.at(ch + "/" + quantity + "_" + unit, run_path);
  };
  auto optional_column = [&](const std::string& ch, const std::string& quantity) {
    return run.find(ch + "/" + quantity + "_" + unit);
  };

  Report report;
  for (const auto& ch : channels) {
    ChannelMetrics m;
    m.channel = ch;
    const auto& measured = channel_column(ch, "measured");
    const auto& estimate = channel_column(ch, "virtual");
    const auto& fault_estimate = channel_column(ch, "fault_estimate");
    const auto& recovered = channel_column(ch, "recovered");
    const auto& flag = run.at(ch + "/fault", run_path);
    const auto& flag_type = run.at(ch + "/fault_type", run_path);
    const std::vector<double>* true_force = has_truth ? truth.find("truth/" + ch + "/force_N") : nullptr;
    const std::vector<double>* true_fault = has_truth ? truth.find("truth/" + ch + "/fault") : nullptr;
    const std::string foot = ch.substr(0, ch.find('/'));
    const std::vector<double>* contact =
        has_truth ? truth.find(foot == "l_foot" ? "truth/contact_l" : foot == "r_foot" ? "truth/contact_r" : "-") : nullptr;

    // Fault window from the truth labels.
    std::size_t onset = time.size(), end = time.size();
    if (true_fault != nullptr) {
      for (std::size_t k = 0; k < time.size(); ++k) {
        if ((*true_fault)[k] != 0.0) {
          if (onset == time.size()) {
            onset = k;
            m.injected_type = static_cast<int>((*true_fault)[k]);
          }
          end = k;
        }
      }
    }
    const bool faulty = onset < time.size();
    m.onset_s = faulty ? time[onset] : kNaN;
    m.end_s = faulty ? time[end] : kNaN;
    m.detection_delay_s = kNaN;
    if (faulty) {
      for (std::size_t k = onset; k < time.size(); ++k) {
        if (flag[k] != 0.0) {
          m.detection_delay_s = time[k] - time[onset];
          m.detected_type = static_cast<int>(flag_type[k]);
          break;
        }
      }
    }
    if (faulty) {
      std::map<int, int> shown;
      for (std::size_t k = onset; k <= end; ++k) {
        if (flag[k] != 0.0 && std::isfinite(flag_type[k])) ++shown[static_cast<int>(flag_type[k])];
      }
      int best = 0;
      for (const auto& [type, count] : shown) {
        if (count > best) {
          best = count;
          m.shown_type = type;
        }
      }
    }
    // Re-admission after a fault that ends before the log does.
    m.readmission_s = kNaN;
    std::size_t grace_end = end;
    if (faulty && end + 1 < time.size()) {
      for (std::size_t k = end + 1; k < time.size(); ++k) {
        if (flag[k] == 0.0) {
          m.readmission_s = time[k] - time[end];
          break;
        }
      }
      while (grace_end + 1 < time.size() && time[grace_end + 1] - time[end] <= options.readmit_s) ++grace_end;
    }
    // False alarms: after warm-up, outside the fault window and its re-admission grace.
    bool previous = false;
    for (std::size_t k = 0; k < time.size(); ++k) {
      const bool in_window = faulty && k >= onset && k <= grace_end;
      const bool raised = flag[k] != 0.0 && time[k] - t0 >= options.warmup_s && !in_window;
      if (raised && !previous) ++m.false_alarms;
      if (raised) m.false_alarm_time_s += dt;
      previous = raised;
    }
    std::vector<double> estimate_error, recovered_error, measured_error, vfs_error;
    if (true_force != nullptr) {
      for (std::size_t k = 0; k < time.size(); ++k) {
        const double truth_k = (*true_force)[k];
        if (!std::isfinite(truth_k)) continue;
        const bool after_warmup = time[k] - t0 >= options.warmup_s;
        if (faulty && k >= onset && k <= end) {
          if (time[k] - time[onset] >= options.settle_s && std::isfinite(measured[k])) {
            estimate_error.push_back(fault_estimate[k] - (measured[k] - truth_k));
          }
          recovered_error.push_back(recovered[k] - truth_k);
          if (std::isfinite(measured[k])) measured_error.push_back(measured[k] - truth_k);
        } else if (!faulty && after_warmup) {
          recovered_error.push_back(recovered[k] - truth_k);
          if (std::isfinite(measured[k])) measured_error.push_back(measured[k] - truth_k);
        }
        if (after_warmup && (contact == nullptr || (*contact)[k] > 0.5)) vfs_error.push_back(std::abs(estimate[k] - truth_k));
      }
    }
    m.fault_estimate_rmse = rms(estimate_error);
    m.recovered_rmse = rms(recovered_error);
    m.measured_rmse = rms(measured_error);
    m.vfs_rmse = rms(vfs_error);
    m.vfs_p95 = percentile(vfs_error, 0.95);
    report.channels.push_back(m);
  }

  // JSON and the terminal table.
  Json j = {{"run", run_path},
            {"truth", truth_path},
            {"warmup_s", options.warmup_s},
            {"settle_s", options.settle_s},
            {"readmit_s", options.readmit_s},
            {"duration_s", t_end - t0},
            {"unit", unit},
            {"channels", Json::array()}};
  int detected = 0, faulty_count = 0, false_alarms = 0, types_correct = 0;
  std::ostringstream table;
  table << std::left << std::setw(12) << "channel" << std::setw(12) << "injected" << std::right << std::setw(9)
        << "onset s" << std::setw(10) << "delay s" << std::setw(12) << "est.err " + unit << std::setw(12)
        << "recov " + unit << std::setw(12) << "meas " + unit << std::setw(8) << "alarms" << std::setw(12)
        << "VFS rms " + unit << std::setw(12) << "VFS p95 " + unit << '\n';
  for (const auto& m : report.channels) {
    const bool faulty = m.injected_type != 0;
    faulty_count += faulty;
    detected += faulty && std::isfinite(m.detection_delay_s);
    types_correct += faulty && m.shown_type == m.injected_type;
    false_alarms += m.false_alarms;
    j["channels"].push_back({{"channel", m.channel},
                             {"injected_type", type_name(m.injected_type)},
                             {"onset_s", number_or_null(m.onset_s)},
                             {"end_s", number_or_null(m.end_s)},
                             {"detection_delay_s", number_or_null(m.detection_delay_s)},
                             {"detected_type", type_name(m.detected_type)},
                             {"shown_type", type_name(m.shown_type)},
                             {"type_correct", faulty_type_correct(m)},
                             {"fault_estimate_rmse", number_or_null(m.fault_estimate_rmse)},
                             {"recovered_rmse", number_or_null(m.recovered_rmse)},
                             {"measured_rmse", number_or_null(m.measured_rmse)},
                             {"readmission_s", number_or_null(m.readmission_s)},
                             {"false_alarms", m.false_alarms},
                             {"false_alarm_time_s", m.false_alarm_time_s},
                             {"vfs_rmse", number_or_null(m.vfs_rmse)},
                             {"vfs_p95", number_or_null(m.vfs_p95)}});
    table << std::left << std::setw(12) << m.channel << std::setw(12) << type_name(m.injected_type) << std::right
          << std::setw(9) << fixed(m.onset_s, 2) << std::setw(10)
          << (faulty ? (std::isfinite(m.detection_delay_s) ? fixed(m.detection_delay_s, 3) : "missed") : "-")
          << std::setw(12) << fixed(m.fault_estimate_rmse, 1) << std::setw(12) << fixed(m.recovered_rmse, 1)
          << std::setw(12) << fixed(m.measured_rmse, 1) << std::setw(8) << m.false_alarms << std::setw(12)
          << fixed(m.vfs_rmse, 1) << std::setw(12) << fixed(m.vfs_p95, 1) << '\n';
  }
  j["summary"] = {{"faulty_channels", faulty_count},
                  {"detected", detected},
                  {"types_correct", types_correct},
                  {"false_alarms_after_warmup", false_alarms}};
  table << "detected " << detected << " of " << faulty_count << " faulty channels; " << false_alarms
        << " false alarms after the " << options.warmup_s << " s warm-up\n";
  report.json = j;
  report.table = table.str();
  if (out_dir.empty()) return report;

  // Files.
  std::filesystem::create_directories(out_dir);
  std::ofstream(out_dir + "/metrics.json") << j.dump(2) << '\n';
  std::vector<std::string> shown;
  for (const auto& m : report.channels) {
    if (m.injected_type != 0) shown.push_back(m.channel);
  }
  if (shown.empty()) {
    for (std::size_t i = 0; i < std::min<std::size_t>(4, channels.size()); ++i) shown.push_back(channels[i]);
  }
  std::vector<std::string> figures;
  if (options.figures) {
    // One data file for the channels shown: t, then per channel measured, virtual, truth,
    // fault_estimate, fault_estimate_raw, injected, recovered; then every channel's flag.
    std::vector<std::vector<double>> derived;
    derived.reserve(shown.size() * 2 + 1);
    std::vector<const std::vector<double>*> cols{&time};
    const std::vector<double> nan_column(time.size(), kNaN);
    for (const auto& ch : shown) {
      const auto& measured = channel_column(ch, "measured");
      const std::vector<double>* t = has_truth ? truth.find("truth/" + ch + "/force_N") : nullptr;
      cols.push_back(&measured);
      cols.push_back(&channel_column(ch, "virtual"));
      cols.push_back(t != nullptr ? t : &nan_column);
      cols.push_back(&channel_column(ch, "fault_estimate"));
      const auto* raw = optional_column(ch, "fault_estimate_raw");
      cols.push_back(raw != nullptr ? raw : &nan_column);
      derived.emplace_back(time.size(), kNaN);
      if (t != nullptr) {
        for (std::size_t k = 0; k < time.size(); ++k) derived.back()[k] = measured[k] - (*t)[k];
      }
      cols.push_back(&derived.back());
      cols.push_back(&channel_column(ch, "recovered"));
    }
    for (const auto& ch : channels) cols.push_back(&run.at(ch + "/fault", run_path));
    write_data(out_dir + "/figures.dat", cols);

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
        gp << "set title '" << shown[i] << "'\nplot ";
        for (std::size_t s = 0; s < series.size(); ++s) {
          gp << (s ? ", " : "") << "'" << out_dir << "/figures.dat' using 1:" << column(i, series[s].first)
             << " with lines lw 1.5 title '" << series[s].second << "'";
        }
        gp << '\n';
      }
      gp << "unset multiplot\n";
      figures.push_back(file);
    };
    multiplot("fig4_virtual_vs_true.png", "Virtual vs true contact force (paper Fig. 4)", "force [" + unit + "]",
              {{0, "measured"}, {2, "true"}, {1, "virtual (VFS)"}});
    multiplot("fig5_fault_estimate.png", "Injected vs estimated fault (paper Fig. 5)", "fault [" + unit + "]",
              {{5, "injected (measured - true)"}, {4, "estimate, unfiltered"}, {3, "estimate, filtered"}});
    multiplot("fig6_recovered.png", "Recovered vs true signal (paper Fig. 6)", "force [" + unit + "]",
              {{0, "measured"}, {2, "true"}, {6, "recovered"}});
    gp << "set terminal pngcairo noenhanced size 1400," << 120 + 40 * channels.size() << " font 'DejaVu Sans,11'\n"
       << "set output '" << out_dir << "/fig7_detection_flags.png'\n"
       << "set title 'Detection flags (paper Fig. 7): raised = channel flagged as faulty'\nset ylabel ''\n"
       << "set ytics (";
    for (std::size_t c = 0; c < channels.size(); ++c) gp << (c ? ", " : "") << "'" << channels[c] << "' " << c;
    gp << ")\nset yrange [-0.5:" << channels.size() << "]\nset key off\nplot ";
    for (std::size_t c = 0; c < channels.size(); ++c) {
      gp << (c ? ", " : "") << "'" << out_dir << "/figures.dat' using 1:($" << 2 + shown.size() * per + c << "*0.7+"
         << c << ") with steps lw 2";
    }
    gp << '\n';
    figures.push_back("fig7_detection_flags.png");
    const std::string script = out_dir + "/figures.gp";
    std::ofstream(script) << gp.str();
    const std::string command = "gnuplot '" + script + "' 2> '" + out_dir + "/gnuplot.log'";
    if (std::system(command.c_str()) != 0) {
      throw std::runtime_error("gnuplot failed (see " + out_dir + "/gnuplot.log); install gnuplot-nox, or use --no-figures");
    }
  }

  std::ofstream md(out_dir + "/report.md");
  md << "# " << options.title << "\n\nRun: `" << run_path << "`" << (has_truth ? ", truth: `" + truth_path + "`" : "")
     << ". Warm-up " << options.warmup_s << " s (no false alarm is counted before it, nor within "
     << options.readmit_s << " s after a fault ends); fault estimate error "
     << "measured from " << options.settle_s << " s after onset. Units: " << unit << ".\n\n";
  md << "| channel | injected | onset [s] | detection delay [s] | type shown | re-admitted after [s] | "
        "fault estimate RMSE | recovered RMSE | measured RMSE | false alarms | false-alarm time [s] | VFS RMSE | "
        "VFS p95 |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& m : report.channels) {
    const bool faulty = m.injected_type != 0;
    md << "| " << m.channel << " | " << type_name(m.injected_type) << " | " << fixed(m.onset_s, 2) << " | "
       << (faulty ? (std::isfinite(m.detection_delay_s) ? fixed(m.detection_delay_s, 3) : "missed") : "-") << " | "
       << type_name(m.shown_type) << " | " << fixed(m.readmission_s, 2) << " | " << fixed(m.fault_estimate_rmse, 1) << " | " << fixed(m.recovered_rmse, 1)
       << " | " << fixed(m.measured_rmse, 1) << " | " << m.false_alarms << " | " << fixed(m.false_alarm_time_s, 2)
       << " | " << fixed(m.vfs_rmse, 1) << " | " << fixed(m.vfs_p95, 1) << " |\n";
  }
  md << "\nDetected " << detected << " of " << faulty_count << " faulty channels; " << false_alarms
     << " false alarms after the warm-up.\n";
  for (const auto& f : figures) md << "\n![" << f << "](" << f << ")\n";
  return report;
}

int report_command(const std::vector<std::string>& args) {
  const std::vector<OptionSpec> specs{
      {"run", true, true, "output of 'ftsense run' (CSV)"},
      {"truth", true, false, "the log the run was made from, with truth/... columns (simulator logs)"},
      {"out", true, true, "folder for metrics.json, report.md and the figures"},
      {"warmup-s", true, false, "no false alarm is counted before this time (default 2)"},
      {"no-figures", false, false, "skip the gnuplot figures"}};
  const auto options = parse_options("report", args, specs);
  if (options.count("help")) {
    std::cout << usage_text("report",
                            "Computes detection delays, fault estimate errors, recovered-signal RMSE,\n"
                            "false alarms and virtual sensor errors of a run against the truth, and\n"
                            "writes metrics.json, report.md and the paper's four figures (PNG).",
                            specs);
    return kExitOk;
  }
  ReportOptions report_options;
  if (const auto w = options.find("warmup-s"); w != options.end()) {
    char* end = nullptr;
    report_options.warmup_s = std::strtod(w->second.c_str(), &end);
    if (end == w->second.c_str() || *end != '\0' || !(report_options.warmup_s >= 0.0)) {
      throw UsageError{"ftsense report: --warmup-s = '" + w->second + "' violates >= 0"};
    }
  }
  report_options.figures = !options.count("no-figures");
  const std::string truth = options.count("truth") ? options.at("truth") : std::string();
  try {
    const Report r = make_report(options.at("run"), truth, options.at("out"), report_options);
    std::cout << r.table << "wrote " << options.at("out") << "/report.md\n";
  } catch (const io::LogError& e) {
    throw UsageError{std::string("error: ") + e.what()};
  }
  return kExitOk;
}

}  // namespace ftsense::cli
