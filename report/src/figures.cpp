#include "ftsense/report/figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "ftsense/diagnostics.hpp"
#include "ftsense/json_text.hpp"
#include "ftsense/params.hpp"
#include "ftsense/text_file.hpp"
#include "gnuplot_text.hpp"

namespace ftsense::report {

namespace {

constexpr double kGap = std::numeric_limits<double>::quiet_NaN();  // gnuplot leaves a gap at NaN
constexpr std::size_t kMaxRows = 2500;  // data rows per figure: enough for 1400 px
constexpr double kMinStretchS = 0.05;           // shorter type stretches are widened to show
constexpr double kMergeGapS = 0.2;              // shaded stretches closer than this are one
constexpr std::size_t kMaxShadedStretches = 40;

// One colour per fault type code (row i: code i), for every figure.
constexpr std::array<unsigned, kFaultTypes.size()> kTypeColours{
    0xffffff, 0x7f7f7f, 0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd, 0x8c564b, 0xe377c2, 0x17becf};

std::string colour_text(unsigned c) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%06x", c);
  return buf;
}

std::string number(double v) {
  std::ostringstream os;
  os << std::setprecision(10) << v;
  return os.str();
}

std::string two_decimals(double v) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << v;
  return os.str();
}

// A stretch of samples [first, last] with one code.
struct Stretch {
  std::size_t first = 0, last = 0;
  int code = 0;
};

// Runs of equal non-zero codes (only where `mask` is raised, when given).
std::vector<Stretch> stretches(std::span<const double> code, std::span<const double> mask) {
  std::vector<Stretch> out;
  for (std::size_t k = 0; k < code.size(); ++k) {
    const bool on = std::isfinite(code[k]) && code[k] != 0.0 && (mask.empty() || mask[k] != 0.0);
    if (!on) continue;
    const int c = static_cast<int>(code[k]);
    if (!out.empty() && out.back().last + 1 == k && out.back().code == c) out.back().last = k;
    else out.push_back({k, k, c});
  }
  return out;
}

// Time intervals to shade: stretches merged across gaps shorter than kMergeGapS, at most kMaxShadedStretches.
std::vector<std::pair<double, double>> shaded(std::span<const double> time, const std::vector<Stretch>& s) {
  std::vector<std::pair<double, double>> out;
  for (const Stretch& x : s) {
    if (!out.empty() && time[x.first] - out.back().second < kMergeGapS) out.back().second = time[x.last];
    else out.emplace_back(time[x.first], time[x.last]);
  }
  if (out.size() > kMaxShadedStretches) {  // many short ones: one from the first to the last
    out = {{out.front().first, out.back().second}};
  }
  return out;
}

double band_distance(const RunChannel& ch, std::size_t c, const DetectorBand& band, std::span<const double> time,
                     const MetricOptions& options) {
  const auto& fe = ch[MonitorColumn::fault_estimate];
  const double centre = band.known() ? band.centre[c] : 0.0;
  const double scale = band.known() && band.threshold[c] > 0.0 ? band.threshold[c] : 1.0;
  double peak = 0.0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    if (time[k] - time.front() < options.warmup_s || !std::isfinite(fe[k])) continue;
    peak = std::max(peak, std::abs(fe[k] - centre) / scale);
  }
  return peak;
}

RunFigure new_figure(FigureKind kind, bool truth) {
  const FigureKindInfo& info = figure_kind_info(kind);
  RunFigure fig;
  fig.kind = kind;
  fig.file = truth ? info.file : info.file_without_truth;
  fig.title = truth ? info.title : info.title_without_truth;
  fig.caption = truth ? info.caption : info.caption_without_truth;
  return fig;
}

}  // namespace

const FigureKindInfo& figure_kind_info(FigureKind kind) { return kFigureKinds[static_cast<std::size_t>(kind)]; }

unsigned fault_type_colour(FaultType type) {
  const auto i = static_cast<std::size_t>(type);
  return i < kTypeColours.size() ? kTypeColours[i] : 0x000000;
}

DetectorBand load_detector_band(const std::string& thresholds_path, std::size_t channels) {
  const Json j = parse_json_text(read_text_file(thresholds_path, "thresholds"), thresholds_path);
  DetectorBand band;
  band.source = thresholds_path;
  const Json stages = j.value("stages", Json::object());
  for (const auto& [stage, values] : stages.items()) {
    if (!values.is_object() || !values.contains("thresholds") || !values["thresholds"].is_array()) continue;
    const auto& t = values["thresholds"];
    if (t.size() != 1 && t.size() != channels) continue;
    for (std::size_t c = 0; c < channels; ++c) {
      band.threshold.push_back(t[t.size() == 1 ? 0 : c].get<double>());
      const Json centres = values.value("centers", Json::array());
      band.centre.push_back(centres.size() == t.size() ? centres[t.size() == 1 ? 0 : c].get<double>() : 0.0);
    }
    return band;
  }
  throw ConfigError(thresholds_path, "has no stage with \"thresholds\" for " + std::to_string(channels) +
                                         " channels; give the file `ftsense calibrate` wrote for this run's config");
}

std::vector<Panel> figure_channels(const ScoredRun& run, const std::vector<ChannelMetrics>& metrics,
                                   const std::vector<std::vector<Alarm>>& alarms, const DetectorBand& band,
                                   const MetricOptions& options) {
  std::vector<Panel> panels;
  std::vector<bool> chosen(run.channels.size(), false);
  auto choose = [&](std::size_t c, std::string why) {
    if (chosen[c] || panels.size() >= kMaxPanels) return;
    chosen[c] = true;
    panels.push_back({c, std::move(why)});
  };
  if (run.has_truth()) {
    for (std::size_t c = 0; c < metrics.size(); ++c) {
      if (metrics[c].faulty()) choose(c, "injected " + std::string(to_string(metrics[c].injected_type)));
    }
    for (std::size_t c = 0; c < metrics.size(); ++c) {
      if (metrics[c].false_alarms > 0) choose(c, std::to_string(metrics[c].false_alarms) + " false alarm(s)");
    }
  } else {
    for (std::size_t c = 0; c < alarms.size(); ++c) {
      if (alarms[c].empty()) continue;
      std::string why = "flagged: " + std::to_string(alarms[c].size()) + " alarm" + (alarms[c].size() > 1 ? "s" : "") +
                        ", " + std::string(to_string(alarms[c].front().type)) + " from " +
                        two_decimals(alarms[c].front().start_s) + " s";
      choose(c, std::move(why));
    }
  }
  // Fill up with the channels nearest to their band: the closest calls of a quiet run.
  std::vector<std::pair<double, std::size_t>> rest;
  for (std::size_t c = 0; c < run.channels.size(); ++c) {
    if (!chosen[c]) rest.emplace_back(-band_distance(run.channels[c], c, band, *run.time, options), c);
  }
  std::stable_sort(rest.begin(), rest.end());
  const std::string nearest = band.known() ? "not flagged; nearest to its band" : "not flagged; largest |fault estimate|";
  for (const auto& [d, c] : rest) {
    if (panels.size() >= kMinPanels) break;
    choose(c, nearest);
  }
  // Panels in channel order, as the flags figure lists them.
  std::stable_sort(panels.begin(), panels.end(), [](const Panel& a, const Panel& b) { return a.channel < b.channel; });
  return panels;
}

void run_gnuplot(const std::string& script, const std::string& log) {
  const std::string command = "gnuplot " + gnuplot_quoted(script) + " 2> " + gnuplot_quoted(log);
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("gnuplot failed (see " + log + "); install gnuplot-nox, or use --no-figures");
  }
}

void draw_figures(const std::string& out_dir) { run_gnuplot(out_dir + "/figures.gp", out_dir + "/gnuplot.log"); }

std::vector<RunFigure> write_figures(const ScoredRun& run, const std::vector<ChannelMetrics>& metrics,
                                     const std::vector<std::vector<Alarm>>& alarms, const DetectorBand& band,
                                     const MetricOptions& options, const std::string& out_dir) {
  std::vector<RunFigure> figures = prepare_figures(run, metrics, alarms, band, options, out_dir);
  draw_figures(out_dir);
  return figures;
}

std::vector<RunFigure> prepare_figures(const ScoredRun& run, const std::vector<ChannelMetrics>& metrics,
                                       const std::vector<std::vector<Alarm>>& alarms, const DetectorBand& band,
                                       const MetricOptions& options, const std::string& out_dir) {
  const auto& time = *run.time;
  const bool truth = run.has_truth();
  const std::vector<Panel> panels = figure_channels(run, metrics, alarms, band, options);
  const std::size_t n = run.channels.size();
  const std::string dat = out_dir + "/figures.dat";
  const std::string types_dat = out_dir + "/types.dat";

  // figures.dat: t, then per panel measured, virtual, true, estimate, raw estimate, injected,
  // recovered; then every channel's flag. Decimated to about kMaxRows rows.
  constexpr std::size_t per = 7;
  {
    std::ofstream f(dat);
    const std::size_t stride = std::max<std::size_t>(1, time.size() / kMaxRows);
    auto put = [&f](double v) {
      if (std::isfinite(v)) f << ' ' << v;
      else f << " NaN";
    };
    for (std::size_t k = 0; k < time.size(); k += stride) {
      f << time[k];
      for (const Panel& p : panels) {
        const RunChannel& ch = run.channels[p.channel];
        const double measured = ch[MonitorColumn::measured][k];
        const double true_force = ch.true_force != nullptr ? (*ch.true_force)[k] : kGap;
        put(measured);
        put(ch[MonitorColumn::virtual_value][k]);
        put(true_force);
        put(ch[MonitorColumn::fault_estimate][k]);
        put(ch.raw_fault_estimate != nullptr ? (*ch.raw_fault_estimate)[k] : kGap);
        put(measured - true_force);
        put(ch[MonitorColumn::recovered][k]);
      }
      for (const RunChannel& ch : run.channels) put(ch[MonitorColumn::fault][k]);
      f << '\n';
    }
  }
  auto column = [&](std::size_t panel, std::size_t offset) { return 2 + panel * per + offset; };

  // Shaded stretches per channel: the injected fault (truth) or the alarms (no truth).
  std::vector<std::vector<std::pair<double, double>>> shade(n);
  for (std::size_t c = 0; c < n; ++c) {
    const RunChannel& ch = run.channels[c];
    if (truth) {
      if (ch.true_fault != nullptr) shade[c] = shaded(time, stretches(*ch.true_fault, {}));
    } else {
      for (const Alarm& a : alarms[c]) shade[c].emplace_back(a.start_s, a.end_s);
      if (shade[c].size() > kMaxShadedStretches) shade[c] = {{shade[c].front().first, shade[c].back().second}};
    }
  }

  std::vector<RunFigure> figures;
  std::ostringstream gp;
  const std::string dat_q = gnuplot_quoted(dat);
  gp << "set datafile missing 'NaN'\nset grid\nset key outside right top vertical box opaque\n"
     << "set xlabel 'time [s]'\nset lmargin 12\nset rmargin 34\n";
  const double t_first = time.empty() ? 0.0 : time.front();
  const double t_last = time.empty() ? 1.0 : time.back();
  gp << "set xrange [" << number(t_first) << ":" << number(t_last) << "]\n";

  // A mark in the last fifth of the time axis has its label on its left, inside the plot.
  auto late = [&](double t) { return t > t_first + 0.8 * (t_last - t_first); };
  auto decorate_panel = [&](std::size_t c) {
    gp << "unset object\nunset arrow\nunset label\n";
    for (const auto& [a, b] : shade[c]) {
      gp << "set object rect from " << number(a) << ", graph 0 to " << number(std::max(b, a + 0.02))
         << ", graph 1 behind fc rgb '" << (truth ? "#fbe4e1" : "#fdebd0") << "' fs solid 1.0 noborder\n";
    }
    if (!truth) return;
    const ChannelMetrics& m = metrics[c];
    if (std::isfinite(m.onset_s)) {
      gp << "set arrow from " << number(m.onset_s) << ", graph 0 to " << number(m.onset_s)
         << ", graph 1 nohead front lc rgb '#c0392b' dt 2 lw 2\n"
         << "set label " << gnuplot_quoted("onset " + two_decimals(m.onset_s) + " s") << " at " << number(m.onset_s)
         << ", graph 0.92 " << (late(m.onset_s) ? "right offset -0.4,0" : "offset 0.4,0") << " front tc rgb '#c0392b'\n";
    }
    if (std::isfinite(m.detection_delay_s)) {
      const double t = m.onset_s + m.detection_delay_s;
      gp << "set arrow from " << number(t) << ", graph 0 to " << number(t)
         << ", graph 1 nohead front lc rgb '#1e8449' dt 3 lw 2\n"
         << "set label " << gnuplot_quoted("flagged +" + two_decimals(m.detection_delay_s) + " s") << " at " << number(t)
         << ", graph 0.08 " << (late(t) ? "right offset -0.4,0" : "offset 0.4,0") << " front tc rgb '#1e8449'\n";
    }
  };

  struct Series {
    std::size_t offset;
    std::string style, title;
  };
  auto per_channel = [&](FigureKind kind, const std::string& ylabel, const std::vector<Series>& series, bool band_lines) {
    RunFigure fig = new_figure(kind, truth);
    gp << "set terminal pngcairo noenhanced size 1400," << 80 + 300 * panels.size() << " font 'DejaVu Sans,11'\n"
       << "set output " << gnuplot_quoted(out_dir + "/" + fig.file) << "\n"
       << "set multiplot layout " << panels.size() << ",1 title " << gnuplot_quoted(fig.title) << " font ',14'\n"
       << "set ylabel " << gnuplot_quoted(ylabel) << "\nset yrange [*:*]\n";
    for (std::size_t i = 0; i < panels.size(); ++i) {
      const std::size_t c = panels[i].channel;
      fig.channels.push_back(run.channels[c].name);
      fig.why.push_back(panels[i].why);
      decorate_panel(c);
      gp << "set title " << gnuplot_quoted(run.channels[c].name + " (" + panels[i].why + ")") << "\nplot ";
      bool first = true;
      for (const Series& s : series) {
        if (!truth && (s.offset == 2 || s.offset == 5)) continue;  // true force, injected fault
        if (s.offset == 4 && run.channels[c].raw_fault_estimate == nullptr) continue;  // not written by the run
        gp << (first ? "" : ", ") << dat_q << " using 1:" << column(i, s.offset) << " with lines " << s.style
           << " title " << gnuplot_quoted(s.title);
        first = false;
        if (band_lines && s.offset == 3 && band.known()) {  // the band right after the filtered estimate
          const double lo = band.centre[c] - band.threshold[c], hi = band.centre[c] + band.threshold[c];
          gp << ", " << number(hi) << " with lines lc rgb '#c0392b' dt 4 lw 1.5 title "
             << gnuplot_quoted(band.centre[c] != 0.0 ? "band " + two_decimals(band.centre[c]) + " +- " + two_decimals(band.threshold[c])
                                             : "threshold +-" + two_decimals(band.threshold[c]))
             << ", " << number(lo) << " with lines lc rgb '#c0392b' dt 4 lw 1.5 notitle";
        }
      }
      gp << '\n';
    }
    gp << "unset multiplot\nunset object\nunset arrow\nunset label\n";
    figures.push_back(std::move(fig));
  };

  const std::string unit = run.unit;
  const std::string measured_style = "lc rgb '#9a9a9a' lw 1";
  const std::string true_style = "lc rgb '#000000' dt (6,4) lw 2";
  per_channel(FigureKind::virtual_sensor, "force [" + unit + "]",
              {{0, measured_style, "measured"}, {1, "lc rgb '#1f77b4' lw 1.5", "virtual (VFS)"}, {2, true_style, "true"}},
              false);
  per_channel(FigureKind::fault_estimate, "fault [" + unit + "]",
              {{4, "lc rgb '#9ecae1' lw 1", "estimate, unfiltered"},
               {3, "lc rgb '#1f77b4' lw 1.5", "estimate, filtered"},
               {5, true_style, "injected (measured - true)"}},
              true);
  per_channel(FigureKind::recovered, "force [" + unit + "]",
              {{0, measured_style, "measured"}, {6, "lc rgb '#2ca02c' lw 1.5", "recovered"}, {2, true_style, "true"}},
              false);

  // Fig. 7: every channel's flag, the injected stretches shaded in its row.
  {
    RunFigure fig = new_figure(FigureKind::flags, truth);
    gp << "set terminal pngcairo noenhanced size 1400," << 140 + 45 * n << " font 'DejaVu Sans,11'\n"
       << "set output " << gnuplot_quoted(out_dir + "/" + fig.file) << "\nset title " << gnuplot_quoted(fig.title) << " font ',14'\n"
       << "set ylabel ''\nset yrange [-0.5:" << n << "]\nset ytics (";
    auto row_of = [n](std::size_t c) { return n - 1 - c; };  // channel 0 on top, as in Fig. 8
    for (std::size_t c = 0; c < n; ++c) gp << (c ? ", " : "") << gnuplot_quoted(run.channels[c].name) << " " << row_of(c);
    gp << ")\nunset object\n";
    for (std::size_t c = 0; c < n; ++c) {
      fig.channels.push_back(run.channels[c].name);
      if (!truth) continue;
      for (const auto& [a, b] : shade[c]) {
        gp << "set object rect from " << number(a) << ", " << row_of(c) - 0.1 << " to " << number(std::max(b, a + 0.02))
           << ", " << row_of(c) + 0.8 << " behind fc rgb '#fbe4e1' fs solid 1.0 noborder\n";
      }
    }
    gp << "set key off\nplot ";
    for (std::size_t c = 0; c < n; ++c) {
      gp << (c ? ", " : "") << dat_q << " using 1:($" << 2 + panels.size() * per + c << "*0.7+" << row_of(c)
         << ") with steps lw 2 lc rgb '#1f77b4'";
    }
    gp << "\nunset object\nset ytics autofreq\n";
    figures.push_back(std::move(fig));
  }

  // Fig. 8: the fault types over time; types.dat has one box per stretch:
  // x, y, x_low, x_high, y_low, y_high, colour, strip (0 named, 1 injected).
  {
    RunFigure fig = new_figure(FigureKind::fault_types, truth);
    std::vector<bool> present(kFaultTypes.size(), false);
    std::ofstream f(types_dat);
    std::size_t boxes = 0;
    auto put_box = [&](const Stretch& s, double y, double half_height, int strip) {
      const double a = time[s.first], b = std::max(time[s.last], a + kMinStretchS);
      f << number((a + b) / 2) << ' ' << y << ' ' << number(a) << ' ' << number(b) << ' ' << y - half_height << ' '
        << y + half_height << ' ' << fault_type_colour(fault_type_from_code(s.code).value_or(FaultType::unclassified))
        << ' ' << strip << '\n';
      present[static_cast<std::size_t>(fault_type_from_code(s.code).value_or(FaultType::unclassified))] = true;
      ++boxes;
    };
    const double row = truth ? 1.0 : 0.5;
    auto row_y = [&](std::size_t c) { return static_cast<double>(n - 1 - c) * row; };  // channel 0 on top
    for (std::size_t c = 0; c < n; ++c) {
      const RunChannel& ch = run.channels[c];
      fig.channels.push_back(ch.name);
      for (const Stretch& s : stretches(ch[MonitorColumn::fault_type], ch[MonitorColumn::fault])) {
        // A flagged stretch whose type reads none is a fault of no known type.
        put_box(s.code == 0 ? Stretch{s.first, s.last, 1} : s, row_y(c) + (truth ? 0.25 : 0.0), truth ? 0.2 : 0.18, 0);
      }
      if (truth && ch.true_fault != nullptr) {
        for (const Stretch& s : stretches(*ch.true_fault, {})) put_box(s, row_y(c) - 0.25, 0.2, 1);
      }
    }
    if (boxes == 0) f << "NaN NaN NaN NaN NaN NaN 0 0\n";  // gnuplot needs a point; nothing is drawn
    f.close();
    gp << "set terminal pngcairo noenhanced size 1400," << 160 + (truth ? 70 : 40) * n << " font 'DejaVu Sans,11'\n"
       << "set output " << gnuplot_quoted(out_dir + "/" + fig.file) << "\nset title " << gnuplot_quoted(fig.title) << " font ',14'\n"
       << "set ylabel ''\nset lmargin 20\nset yrange [" << -0.6 * row << ":" << (static_cast<double>(n) - 0.4) * row
       << "]\nset ytics (";
    for (std::size_t c = 0; c < n; ++c) {
      if (truth) {
        gp << (c ? ", " : "") << gnuplot_quoted(run.channels[c].name + " named") << " " << row_y(c) + 0.25 << ", "
           << gnuplot_quoted("injected") << " " << row_y(c) - 0.25;
      } else {
        gp << (c ? ", " : "") << gnuplot_quoted(run.channels[c].name) << " " << row_y(c);
      }
    }
    gp << ")\n";
    if (boxes == 0) {
      gp << "set label " << gnuplot_quoted(truth ? "no channel flagged, no fault injected" : "no channel flagged")
         << " at graph 0.5, graph 0.5 center front\n";
    }
    // The named type solid, the injected one lighter beneath it.
    gp << "set grid noytics\n" << (boxes == 0 ? "unset key" : "set key outside right top vertical box opaque") << "\nplot "
       << gnuplot_quoted(types_dat)
       << " using 1:($8 == 0 ? $2 : NaN):3:4:5:6:7 with boxxyerror fs solid 1.0 noborder lc rgb variable notitle, "
       << gnuplot_quoted(types_dat) << " using 1:($8 == 1 ? $2 : NaN):3:4:5:6:7 with boxxyerror fs transparent solid 0.45 noborder "
       << "lc rgb variable notitle";
    for (std::size_t t = 1; t < present.size(); ++t) {
      if (present[t]) {
        gp << ", keyentry with boxes fs solid 1.0 lc rgb '" << colour_text(kTypeColours[t]) << "' title "
           << gnuplot_quoted(std::string(kFaultTypes[t].name));
      }
    }
    gp << "\nunset label\nset yrange [*:*]\nset ytics autofreq\nset grid ytics\nset lmargin 12\n";
    figures.push_back(std::move(fig));
  }

  std::ofstream(out_dir + "/figures.gp") << gp.str();

  // figures.json: what each figure draws (and why each channel).
  Json manifest = {{"truth", truth}, {"band", band.known() ? Json(band.source) : Json(nullptr)}, {"figures", Json::array()}};
  for (const RunFigure& fig : figures) {
    Json j = {{"kind", figure_kind_info(fig.kind).key}, {"file", fig.file}, {"title", fig.title}, {"channels", fig.channels}};
    if (!fig.why.empty()) {
      Json why = Json::object();
      for (std::size_t i = 0; i < fig.why.size(); ++i) why[fig.channels[i]] = fig.why[i];
      j["why"] = why;
    }
    manifest["figures"].push_back(j);
  }
  std::ofstream(out_dir + "/figures.json") << manifest.dump(2) << '\n';
  return figures;
}

}  // namespace ftsense::report
