// ftsense-soak: hours of 1 kHz ticks through the SURALP pipelines, checked on every tick.
//
// The MuJoCo simulator walks the fault-free scenario for --duration seconds and streams its CSV
// log into a line sink (no file: an hour of log is 4.5 GB); every row is parsed and stepped
// through each --config pipeline at once. Checked, and the exit status says so:
//   - no NaN or Inf in any monitored recovered signal or fault estimate, on any tick;
//   - covariances stay bounded: every `fault_variance` / `com_variance` output the pipeline has
//     stays finite, positive, and after the first 10 % of the run never exceeds its largest value
//     during that first 10 % (Kalman variances converge; they must not creep up over an hour);
//   - zero heap allocations inside Pipeline::step after the first tick (counted exactly);
//   - resident memory (VmRSS) grows by less than 1 MiB between 10 % and 99 % of the run, both
//     read while the simulation runs (the pipelines allocate nothing; this guards the whole
//     process, simulator and parser included).
// Printed, not asserted: ticks flagged per pipeline (false alarms on a fault-free walk), the
// covariance resets, the largest |fault estimate|, and the run time.
//
// usage: ftsense-soak --scenario configs/scenarios/clean.json --config configs/suralp.json
//                     [--config ...] [--duration 3600] [--seed 1] [--quiet]

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/sim/scenario.hpp"
#include "ftsense/sim/simulator.hpp"
#include "ftsense/testing/allocation_counter.hpp"

namespace {

using ftsense::Pipeline;
using ftsense::SignalRef;
using ftsense::MonitorColumn;

long resident_kib() {
  std::ifstream status("/proc/self/status");
  std::string key;
  long value = -1;
  while (status >> key) {
    if (key == "VmRSS:") {
      status >> value;
      return value;
    }
    status.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return value;
}

// One pipeline under soak with what it watches.
struct Soaked {
  std::string config_path;
  Pipeline pipeline;
  std::vector<std::size_t> log_column;  // per pipeline input value
  struct Watched {
    std::string name;
    SignalRef ref;
    double early_max = 0.0;  // largest value during the first 10 % of the run
    double late_max = 0.0;   // largest value after that
    bool bad = false;
  };
  std::vector<Watched> variances;
  std::vector<SignalRef> resets;
  std::size_t flagged_ticks = 0;
  std::size_t nonfinite_ticks = 0;
  double first_nonfinite_s = std::numeric_limits<double>::quiet_NaN();
  double max_abs_fault_estimate = 0.0;
  std::size_t step_allocations = 0;
};

class SoakSink : public std::streambuf {
 public:
  SoakSink(std::vector<Soaked>& soaked, double duration_s) : soaked_(soaked), duration_s_(duration_s) {
    line_.reserve(1 << 14);
  }
  std::string error;
  std::size_t ticks = 0;
  long rss_early_kib = -1;  // VmRSS at 10 % of the run
  long rss_late_kib = -1;   // VmRSS at 99 % of the run

 protected:
  int_type overflow(int_type ch) override {
    if (ch == traits_type::eof()) return traits_type::not_eof(ch);
    put(static_cast<char>(ch));
    return ch;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i) put(s[i]);
    return n;
  }

 private:
  void put(char c) {
    if (c != '\n') {
      line_.push_back(c);
      return;
    }
    if (error.empty()) header_seen_ ? row() : header();
    line_.clear();
  }

  void header() {
    header_seen_ = true;
    std::vector<std::string> columns;
    std::stringstream in(line_);
    for (std::string name; std::getline(in, name, ',');) columns.push_back(name);
    values_.assign(columns.size(), 0.0);
    for (Soaked& s : soaked_) {
      for (const auto& input : s.pipeline.inputs()) {
        for (const auto& column : input.columns) {
          std::size_t k = 0;
          while (k < columns.size() && columns[k] != column) ++k;
          if (k == columns.size()) {
            error = s.config_path + ": column '" + column + "' is not in the simulator's log";
            return;
          }
          s.log_column.push_back(k);
        }
      }
    }
  }

  void row() {
    const char* p = line_.data();
    const char* end = p + line_.size();
    for (double& v : values_) {
      const auto [next, ec] = std::from_chars(p, end, v);
      if (ec != std::errc()) {
        error = "unparsable cell in simulator row " + std::to_string(ticks + 2);
        return;
      }
      p = next < end ? next + 1 : end;
    }
    const double t = values_[0];
    const bool early = t < 0.1 * duration_s_;
    // Both readings inside the simulation, so the simulator's own buffers count in each.
    if (!early && rss_early_kib < 0) rss_early_kib = resident_kib();
    if (t >= 0.99 * duration_s_ && rss_late_kib < 0) rss_late_kib = resident_kib();
    for (Soaked& s : soaked_) {
      std::size_t k = 0;
      for (std::size_t i = 0; i < s.pipeline.inputs().size(); ++i) {
        for (double& v : s.pipeline.input_values(i)) v = values_[s.log_column[k++]];
      }
      {
        ftsense::testing::AllocationScope scope;
        s.pipeline.step(t);
        if (ticks > 0) s.step_allocations += scope.allocations();
      }
      const auto& m = s.pipeline.monitor();
      bool finite = true;
      for (double v : s.pipeline.values(m[MonitorColumn::recovered])) finite = finite && std::isfinite(v);
      for (double v : s.pipeline.values(m[MonitorColumn::fault_estimate])) {
        finite = finite && std::isfinite(v);
        if (std::isfinite(v)) s.max_abs_fault_estimate = std::max(s.max_abs_fault_estimate, std::abs(v));
      }
      if (!finite && s.nonfinite_ticks++ == 0) s.first_nonfinite_s = t;
      bool flagged = false;
      for (double v : s.pipeline.values(m[MonitorColumn::fault])) flagged = flagged || v != 0.0;
      s.flagged_ticks += flagged ? 1 : 0;
      for (auto& w : s.variances) {
        for (double v : s.pipeline.values(w.ref)) {
          if (!(std::isfinite(v) && v > 0.0)) w.bad = true;
          double& slot = early ? w.early_max : w.late_max;
          slot = std::max(slot, v);
        }
      }
    }
    ++ticks;
  }

  std::vector<Soaked>& soaked_;
  double duration_s_;
  std::string line_;
  std::vector<double> values_;
  bool header_seen_ = false;
};

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int usage(const std::string& message) {
  std::cerr << "ftsense-soak: " << message
            << "\nusage: ftsense-soak --scenario S.json --config C.json [--config ...] [--duration 3600]"
               " [--seed 1] [--quiet]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenario_path;
  std::vector<std::string> configs;
  double duration_s = 3600.0;
  std::uint64_t seed = 1;
  bool quiet = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--scenario" && has_value) {
      scenario_path = argv[++i];
    } else if (arg == "--config" && has_value) {
      configs.emplace_back(argv[++i]);
    } else if (arg == "--duration" && has_value) {
      duration_s = std::strtod(argv[++i], nullptr);
    } else if (arg == "--seed" && has_value) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--quiet") {
      quiet = true;
    } else {
      return usage("unknown or incomplete argument '" + arg + "'");
    }
  }
  if (scenario_path.empty() || configs.empty()) return usage("--scenario and at least one --config are required");
  if (!(duration_s > 0.0 && duration_s <= 24 * 3600.0)) return usage("--duration must be in (0, 86400] s");

  std::vector<Soaked> soaked;
  try {
    for (const auto& path : configs) {
      Pipeline p = Pipeline::build(ftsense::parse_json_text(read_text(path), path),
                                   ftsense::reference_plugins::registry());
      if (!p.has_monitor()) return usage(path + ": the config has no monitor section");
      Soaked s{path, std::move(p), {}, {}, {}};
      for (const auto& [name, unit] : s.pipeline.signal_names()) {
        const auto dot = name.find('.');
        const std::string port = dot == std::string::npos ? name : name.substr(dot + 1);
        if (port == "fault_variance" || port == "com_variance") {
          s.variances.push_back({name, s.pipeline.signal(name)});
        }
        if (port == "covariance_resets") s.resets.push_back(s.pipeline.signal(name));
      }
      soaked.push_back(std::move(s));
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  }
  ftsense::sim::Scenario scenario;
  try {
    scenario = ftsense::sim::load_scenario(scenario_path);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  }
  if (!scenario.faults.empty()) return usage(scenario_path + ": a soak walks a fault-free scenario");
  scenario.duration_s = duration_s;

  std::cout << "ftsense-soak: " << duration_s << " s of " << scenario_path << " (seed " << seed << ") through";
  for (const auto& s : soaked) std::cout << ' ' << s.config_path;
  std::cout << std::endl;
  SoakSink sink(soaked, duration_s);
  std::ostream log(&sink);
  ftsense::sim::SimulationOptions options;
  options.progress_interval_s = std::max(1.0, duration_s / 20.0);
  if (!quiet) {
    options.progress = [](double t, double total) {
      std::cerr << "\r  simulated " << static_cast<long>(t) << " / " << static_cast<long>(total) << " s" << std::flush;
    };
  }
  const auto wall_start = std::chrono::steady_clock::now();
  const auto summary = ftsense::sim::simulate(scenario, seed, log, options);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (!quiet) std::cerr << '\n';

  bool ok = true;
  auto fail = [&ok](const std::string& what) {
    std::cout << "FAIL " << what << '\n';
    ok = false;
  };
  if (!sink.error.empty()) fail(sink.error);
  if (summary.fell) fail("the simulated robot fell: " + summary.message);
  const auto expected_ticks = static_cast<std::size_t>(std::llround(duration_s * 1000.0));
  if (sink.ticks + 1 < expected_ticks) {
    fail("only " + std::to_string(sink.ticks) + " of " + std::to_string(expected_ticks) + " ticks ran");
  }
  std::cout << "  " << sink.ticks << " ticks in " << wall_s << " s wall (simulation included), "
            << "VmRSS " << sink.rss_early_kib << " KiB at 10 % -> " << sink.rss_late_kib << " KiB at 99 %\n";
  if (sink.rss_early_kib < 0 || sink.rss_late_kib < 0) fail("could not read VmRSS from /proc/self/status");
  if (sink.rss_late_kib - sink.rss_early_kib >= 1024) {
    fail("resident memory grew by " + std::to_string(sink.rss_late_kib - sink.rss_early_kib) + " KiB");
  }
  for (const Soaked& s : soaked) {
    double resets = 0.0;
    for (const SignalRef& r : s.resets) {
      for (double v : s.pipeline.values(r)) resets += v;
    }
    std::cout << "  " << s.config_path << ": ticks flagged " << s.flagged_ticks << ", max |fault estimate| "
              << s.max_abs_fault_estimate << ", covariance resets " << resets << ", allocations in step "
              << s.step_allocations << '\n';
    if (s.nonfinite_ticks > 0) {
      std::ostringstream what;
      what << s.config_path << ": " << s.nonfinite_ticks << " ticks with NaN/Inf in a recovered signal or fault "
           << "estimate (first at t = " << s.first_nonfinite_s << " s)";
      fail(what.str());
    }
    if (s.step_allocations != 0) fail(s.config_path + ": Pipeline::step allocated");
    for (const auto& w : s.variances) {
      std::cout << "    " << w.name << ": max " << w.early_max << " in the first 10 %, " << w.late_max
                << " after\n";
      if (w.bad) fail(s.config_path + ": " + w.name + " was not finite and positive on some tick");
      if (w.late_max > w.early_max) fail(s.config_path + ": " + w.name + " grew after the first 10 % of the run");
    }
  }
  std::cout << (ok ? "ok: soak passed\n" : "soak FAILED\n");
  return ok ? 0 : 1;
}
