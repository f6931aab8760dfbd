#include "ftsense/report/summary_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "ftsense/report/figures.hpp"
#include "gnuplot_text.hpp"

namespace ftsense::report {

namespace {

constexpr double kZeroDelayS = 1e-3;   // a delay of 0 drawn here on the log axis
constexpr double kMissedRowS = 100.0;  // missed faults drawn on this row
constexpr std::array<const char*, 6> kPipelineColours{"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"};

std::string type_name(FaultType t) { return t == FaultType::none ? "not flagged" : std::string(to_string(t)); }

}  // namespace

Confusion confusion(const std::vector<ScoredScenario>& runs, const std::string& pipeline) {
  Confusion c;
  std::vector<bool> injected(kFaultTypes.size(), false), named(kFaultTypes.size(), false);
  for (const auto& r : runs) {
    if (r.pipeline != pipeline) continue;
    for (const auto& m : r.channels) {
      if (!m.faulty()) continue;
      injected[static_cast<std::size_t>(m.injected_type)] = true;
      named[static_cast<std::size_t>(m.shown_type)] = true;
    }
  }
  for (std::size_t t = 1; t < kFaultTypes.size(); ++t) {
    if (injected[t]) c.injected.push_back(kFaultTypes[t].type);
  }
  c.named = c.injected;
  for (std::size_t t = 1; t < kFaultTypes.size(); ++t) {
    if (named[t] && !injected[t]) c.named.push_back(kFaultTypes[t].type);
  }
  c.named.push_back(FaultType::none);
  c.counts.assign(c.injected.size(), std::vector<int>(c.named.size(), 0));
  for (const auto& r : runs) {
    if (r.pipeline != pipeline) continue;
    for (const auto& m : r.channels) {
      if (!m.faulty()) continue;
      const auto row = std::find(c.injected.begin(), c.injected.end(), m.injected_type) - c.injected.begin();
      const auto col = std::find(c.named.begin(), c.named.end(), m.shown_type) - c.named.begin();
      ++c.counts[static_cast<std::size_t>(row)][static_cast<std::size_t>(col)];
    }
  }
  return c;
}

std::vector<Figure> write_summary_figures(const std::vector<ScoredScenario>& runs, const std::vector<Pipeline>& pipelines,
                                          const std::vector<std::string>& scenarios, const std::string& out_dir) {
  std::ostringstream gp;
  gp << "set datafile missing 'NaN'\n";

  // The confusion matrices, one panel per pipeline, one data block (index) each: column, row, count.
  const std::string matrix_dat = out_dir + "/confusion_matrix.dat";
  {
    std::ofstream f(matrix_dat);
    std::vector<Confusion> matrices;
    int most = 1;
    for (const auto& p : pipelines) {
      matrices.push_back(confusion(runs, p.key));
      const Confusion& c = matrices.back();
      for (std::size_t r = 0; r < c.injected.size(); ++r) {
        for (std::size_t k = 0; k < c.named.size(); ++k) {
          f << k << ' ' << r << ' ' << c.counts[r][k] << '\n';
          most = std::max(most, c.counts[r][k]);
        }
        f << '\n';
      }
      f << "\n";  // blank lines end the block: one index per pipeline
    }
    f.close();
    gp << "set terminal pngcairo noenhanced size " << std::max<std::size_t>(1400, pipelines.size() * 500)
       << ",600 font 'DejaVu Sans,10'\nset output " << gnuplot_quoted(out_dir + "/confusion_matrix.png") << "\n"
       << "set multiplot layout 1," << pipelines.size()
       << " title 'Injected vs named fault type, every faulty channel of every scenario (diagonal: named right)' font ',14'\n"
       << "set palette defined (0 '#ffffff', 1 '#c6dbef', " << most << " '#08519c')\nset cbrange [0:" << most
       << "]\nunset colorbox\nset xlabel 'type named (shown most while faulty)'\nset ylabel 'type injected'\n"
       << "set xtics rotate by 40 right\nset tics scale 0\nunset key\n";
    for (std::size_t p = 0; p < pipelines.size(); ++p) {
      const Confusion& c = matrices[p];
      gp << "set title " << gnuplot_quoted(pipelines[p].label) << "\nset xrange [-0.5:" << c.named.size() - 0.5
         << "]\nset yrange [" << c.injected.size() - 0.5 << ":-0.5]\nset xtics (";
      for (std::size_t k = 0; k < c.named.size(); ++k) gp << (k ? ", " : "") << gnuplot_quoted(type_name(c.named[k])) << " " << k;
      gp << ")\nset ytics (";
      for (std::size_t r = 0; r < c.injected.size(); ++r) gp << (r ? ", " : "") << gnuplot_quoted(type_name(c.injected[r])) << " " << r;
      gp << ")\nunset object\n";
      for (std::size_t r = 0; r < c.injected.size(); ++r) {
        gp << "set object rect from " << r - 0.5 << "," << r - 0.5 << " to " << r + 0.5 << "," << r + 0.5
           << " front fs empty border lc rgb '#2ca02c' lw 2\n";
      }
      if (c.injected.empty()) {
        gp << "set label 'no faulty channel' at graph 0.5, graph 0.5 center\nplot NaN notitle\nunset label\n";
        continue;
      }
      gp << "plot " << gnuplot_quoted(matrix_dat) << " index " << p << " using 1:2:3 with image, '' index " << p
         << " using 1:2:($3 > 0 ? sprintf('%d', $3) : '') with labels font ',12'\n";
    }
    gp << "unset multiplot\nunset object\nset xtics norotate autojustify autofreq\nset ytics autofreq\nset tics scale default\n"
          "set xrange [*:*]\nset yrange [*:*]\nunset xlabel\nunset ylabel\n";
  }

  // The per-scenario chart: delays (x = scenario + pipeline offset + a small spread per channel)
  // and false alarms (bars).
  const std::string delays_dat = out_dir + "/scenario_delays.dat";
  const std::string alarms_dat = out_dir + "/scenario_false_alarms.dat";
  {
    std::ofstream d(delays_dat), a(alarms_dat);
    const double width = 0.8 / static_cast<double>(std::max<std::size_t>(1, pipelines.size()));
    for (std::size_t s = 0; s < scenarios.size(); ++s) {
      for (std::size_t p = 0; p < pipelines.size(); ++p) {
        const double x = static_cast<double>(s) - 0.4 + width * (static_cast<double>(p) + 0.5);
        for (const auto& r : runs) {
          if (r.pipeline != pipelines[p].key || r.scenario != scenarios[s]) continue;
          int false_alarms = 0, i = 0;
          const auto faulty = std::count_if(r.channels.begin(), r.channels.end(), [](const auto& m) { return m.faulty(); });
          for (const auto& m : r.channels) {
            false_alarms += m.false_alarms;
            if (!m.faulty()) continue;
            const double spread = faulty > 1 ? width * 0.7 * (static_cast<double>(i++) / static_cast<double>(faulty - 1) - 0.5) : 0.0;
            const int category = !m.detected() ? 2 : m.type_correct() ? 0 : 1;
            const double y = category == 2 ? kMissedRowS : std::max(m.detection_delay_s, kZeroDelayS);
            d << x + spread << ' ' << y << ' ' << p << ' ' << category << '\n';
          }
          a << x << ' ' << false_alarms << ' ' << p << '\n';
        }
      }
    }
    d << "NaN NaN -1 -1\n";
    a << "NaN NaN -1\n";
    const double bar = width * 0.9;
    // The delays get two thirds of the height, the false alarms the rest.
    gp << "set terminal pngcairo noenhanced size 1400,860 font 'DejaVu Sans,11'\nset output "
       << gnuplot_quoted(out_dir + "/scenario_chart.png") << "\nset multiplot title "
       << gnuplot_quoted("Per scenario: detection delay of each faulty channel, type named right or wrong, and false alarms")
       << " font ',14'\nset grid\nset key outside right top vertical box opaque\nset lmargin 12\nset rmargin 58\n"
       << "set xrange [-0.5:" << scenarios.size() - 0.5 << "]\nset xtics (";
    for (std::size_t s = 0; s < scenarios.size(); ++s) gp << (s ? ", " : "") << gnuplot_quoted(scenarios[s]) << " " << s;
    gp << ")\nset size 1,0.6\nset origin 0,0.34\n"
       << "set title 'Detection delay (filled: type named right; open: wrong type; cross: missed)'\n"
       << "set logscale y\nset yrange [" << kZeroDelayS / 2 << ":" << kMissedRowS * 3 << "]\n"
       << "set ylabel 'delay [s] (0 drawn at 1 ms)'\nset xlabel ''\nunset arrow\nset arrow from graph 0, first "
       << kMissedRowS << " to graph 1, first " << kMissedRowS << " nohead dt 3 lc rgb '#888888'\n"
       << "set label 'missed' at graph 0.005, first " << kMissedRowS * 1.4 << " tc rgb '#555555'\nplot ";
    const std::array<std::pair<int, std::string>, 3> marks{{{7, "type right"}, {6, "type wrong"}, {2, "missed"}}};
    for (std::size_t p = 0; p < pipelines.size(); ++p) {
      for (std::size_t k = 0; k < marks.size(); ++k) {
        gp << (p + k ? ", " : "") << gnuplot_quoted(delays_dat) << " using 1:(($3 == " << p << " && $4 == " << k
           << ") ? $2 : NaN) with points pt " << marks[k].first << " ps 1.6 lw 2 lc rgb '"
           << kPipelineColours[p % kPipelineColours.size()] << "' title " << gnuplot_quoted(pipelines[p].label + ": " + marks[k].second);
      }
    }
    gp << "\nunset logscale y\nunset arrow\nunset label\nset title 'False alarms (after the warm-up, outside each fault "
          "and its re-admission)'\nset size 1,0.34\nset origin 0,0\nset ylabel 'false alarms'\nset yrange [0:1<*]\nset style fill solid 0.8 noborder\n"
          "set boxwidth "
       << bar << "\nplot ";
    for (std::size_t p = 0; p < pipelines.size(); ++p) {
      gp << (p ? ", " : "") << gnuplot_quoted(alarms_dat) << " using 1:(($3 == " << p << ") ? $2 : NaN) with boxes lc rgb '"
         << kPipelineColours[p % kPipelineColours.size()] << "' title " << gnuplot_quoted(pipelines[p].label) << ", "
         << gnuplot_quoted(alarms_dat) << " using 1:(($3 == " << p << ") ? $2 : NaN):(sprintf('%d', $2)) with labels offset 0,0.7 notitle";
    }
    gp << "\nunset multiplot\n";
  }
  const std::string script = out_dir + "/summary.gp";
  std::ofstream(script) << gp.str();
  run_gnuplot(script, out_dir + "/summary_gnuplot.log");
  return {{"confusion_matrix.png", "Injected vs named fault types",
           "Every faulty channel of every scenario, per pipeline: the row is its injected type, the column the type "
           "it showed most while the fault was active and flagged (\"not flagged\": never flagged then). Outlined: "
           "the diagonal, type named right."},
          {"scenario_chart.png", "Detection delay, type and false alarms per scenario",
           "Top: each faulty channel's detection delay (log scale; 0 drawn at 1 ms), filled when the type shown is the "
           "injected one, open when not, a cross on the dotted row when missed. Bottom: false alarms per scenario "
           "and pipeline."}};
}

}  // namespace ftsense::report
