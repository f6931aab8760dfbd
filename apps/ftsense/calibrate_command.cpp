#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <iostream>
#include <limits>

#include "cli.hpp"
#include "ftsense/calibration.hpp"
#include "ftsense/generic/noise_density.hpp"
#include "ftsense/generic/residual_statistics.hpp"
#include "ftsense/generic/tick_noise.hpp"
#include "ftsense/generic/guard_step_noise.hpp"
#include "ftsense/generic/window_step_noise.hpp"
#include "ftsense/io/output_file.hpp"
#include "log_runner.hpp"

namespace ftsense::cli {

namespace {

// A noise density from fewer windows than this is too uncertain to set a detector by (its square
// is a chi-square of that many degrees of freedom).
constexpr std::size_t kMinNoiseDensityWindows = 10;

// "plugin: param, param; plugin: param", from the registry (the plugins' own declarations).
std::string calibrated_params_list(const PluginRegistry& registry, std::string_view separator = "; ") {
  std::string text;
  for (const PluginInfo& info : registry.plugins()) {
    if (info.calibrated_params.empty()) continue;
    text += (text.empty() ? std::string() : std::string(separator)) + info.name + ":";
    for (std::size_t i = 0; i < info.calibrated_params.size(); ++i) {
      text += (i == 0 ? " " : ", ") + std::string(info.calibrated_params[i].param);
    }
  }
  return text.empty() ? "none" : text;
}

// A parameter the plugin takes as one number for all its channels (its schema says so), not a
// list per channel.
bool takes_one_number(const PluginInfo& info, std::string_view param) {
  for (const ParamInfo& p : info.params) {
    if (p.key == param) return p.kind == ParamKind::number;
  }
  return false;
}

// A threshold_detector stage: what its input did over the fault-free logs.
struct Detector {
  std::string name;
  SignalRef signal;
  double warmup_s = 0.0;
  std::vector<double> max_abs;
  std::vector<double> min_seen;
  std::vector<double> max_seen;
  std::vector<std::vector<double>> magnitudes;  // every |s| after warm-up, per channel
  std::vector<double> max_time_s;               // when max_abs was seen
};

// A parameter that is a fault-free statistic of a stage's input, and its measurement.
struct Measured {
  std::string stage;
  CalibratedParam spec;
  SignalRef input;
  std::optional<SignalRef> minus;
  std::vector<generic::ResidualStatistics> statistics;  // per channel
  std::vector<generic::NoiseDensity> density;           // per channel (noise_density only)
  std::vector<generic::TickNoise> tick_noise;           // per channel (tick_noise and resolution only)
  std::vector<generic::WindowStepNoise> window_step;    // per channel (window_step only)
  std::optional<SignalRef> guard;                       // guard_step only: its guard input
  std::vector<generic::GuardStepNoise> guard_step;      // per channel (guard_step only)
  bool one_number = false;  // the plugin takes one number for all channels: the largest is written
};

}  // namespace

int calibrate_command(const std::vector<std::string>& args, const Context& context) {
  const std::string command = context.command("calibrate");
  const std::vector<OptionSpec> specs{
      {"config", true, true, "pipeline config (JSON) with stages to calibrate (threshold_detector, or plugins "
       "with calibrated parameters)", 'c', {}, FileArg::input},
      {"input", true, true, "a fault-free log (CSV); several, comma-separated, to cover several gaits", 'i', {},
       FileArg::input_list},
      {"output", true, true, "where to write the calibration (JSON), for '" + context.program + " run --thresholds'", 'o',
       {"out"}, FileArg::output},
      {"margin", true, false, "threshold = margin x the largest |signal| seen (default 1.25; 1 to 1000)"},
      {"band", false, false,
       "centre each channel's band: centre = (min + max) / 2 and threshold = margin x (max - min) / 2 "
       "of the signal seen, instead of margin x max |signal|"}};
  const auto options = parse_options(command, args, specs);
  if (options.count("help")) {
    std::cout << usage_text(command,
                            "Runs the pipeline over a fault-free log and sets each threshold_detector's\n"
                            "per-channel threshold to margin x max |signal| seen after the detector's\n"
                            "warm-up (the paper's section III: thresholds from a fault-free run). With\n"
                            "--band it also writes each channel's centre, the middle of the range the\n"
                            "signal covered, and sets the threshold to margin x half that range: a virtual\n"
                            "sensor's systematic bias then no longer hides faults of the other sign.\n"
                            "It also measures every parameter that a stage's plugin declares a fault-free\n"
                            "statistic of its inputs and the config does not give, after the pipeline's\n"
                            "longest warm-up, and writes it for the same stage, measured on a second run\n"
                            "with the first run's values in place (on the first, the detectors flag at their\n"
                            "default noise, and their flags move what the stages after them see; a noise density needs " +
                                std::to_string(kMinNoiseDensityWindows) + " windows\nof " +
                                format_number(kNoiseDensityWindowS) + " s). Such parameters here:\n  " +
                                calibrated_params_list(context.registry, ";\n  ") + ".",
                            specs);
    return kExitOk;
  }
  double margin = 1.25;
  if (const auto m = options.find("margin"); m != options.end()) {
    char* end = nullptr;
    margin = std::strtod(m->second.c_str(), &end);
    // Above 1000 the detector would be deaf to anything but a burst.
    if (end == m->second.c_str() || *end != '\0' || !(margin >= 1.0 && margin <= 1000.0)) {
      throw UsageError{command + ": --margin = '" + m->second + "' violates >= 1 and <= 1000"};
    }
  }
  const std::string& config_path = options.at("config");
  require_existing_files(command, options, specs, {"config"});
  Pipeline pipeline = load_pipeline(context, config_path);
  // The parameters the config gives are the user's: kept, not measured.
  const Json raw_config = parse_json_text(read_text_file(config_path, "config file"), config_path);
  const auto given = [&](std::string_view stage, std::string_view param) {
    for (const Json& s : raw_config.value("stages", Json::array())) {
      if (s.is_object() && s.value("name", "") == stage && s.contains("params") && s["params"].is_object() &&
          s["params"].contains(std::string(param))) {
        return true;
      }
    }
    return false;
  };

  // One run of a pipeline over every fault-free log: the threshold detectors' inputs, and the
  // parameters that are fault-free statistics of a stage's inputs (calibration.hpp), measured
  // after the longest warm-up of any stage (the filters feeding them have settled by then).
  struct Run {
    std::vector<Detector> detectors;
    std::vector<Measured> measured;
    std::vector<Json> values;  // per measured parameter: a list per channel, or one number
    double settle_s = 0.0;
    std::size_t ticks = 0;
  };
  // What a run on `pipeline` measures; `tell` says what the config gives (once).
  const auto prepare = [&](Pipeline& pipeline, bool tell) {
    Run run;
    for (std::size_t i = 0; i < pipeline.stage_count(); ++i) {
      if (pipeline.stage(i).plugin_name() != "threshold_detector") continue;
      const Json params = pipeline.stage(i).params_json();
      Detector d{std::string(pipeline.stage_name(i)), pipeline.stage_input(i, 0), params.value("warmup_s", 0.0), {}, {}, {}, {}, {}};
      d.magnitudes.resize(d.signal.dim);
      d.max_time_s.assign(d.signal.dim, std::nan(""));
      d.max_abs.assign(d.signal.dim, 0.0);
      d.min_seen.assign(d.signal.dim, std::numeric_limits<double>::infinity());
      d.max_seen.assign(d.signal.dim, -std::numeric_limits<double>::infinity());
      run.detectors.push_back(std::move(d));
    }

    for (std::size_t i = 0; i < pipeline.stage_count(); ++i) {
      run.settle_s = std::max(run.settle_s, pipeline.stage(i).params_json().value("warmup_s", 0.0));
      const PluginInfo* info = context.registry.find(pipeline.stage(i).plugin_name());
      if (info == nullptr) continue;
      const Ports& ports = pipeline.stage(i).ports();
      for (const CalibratedParam& spec : info->calibrated_params) {
        if (given(pipeline.stage_name(i), spec.param)) {
          if (tell) {
            std::cout << command << ": " << pipeline.stage_name(i) << ": " << spec.param
                      << " given in the config, kept\n";
          }
          continue;
        }
        const auto in = ports.find_input(spec.input);
        const auto minus = spec.minus_input.empty() ? std::nullopt : ports.find_input(spec.minus_input);
        if (!in || (!spec.minus_input.empty() && !minus)) continue;  // the contract test rules this out
        // A step across guards without the guard input wired (an optional port): not measured.
        const auto guard = spec.guard_input.empty() ? std::nullopt : ports.find_input(spec.guard_input);
        if (!spec.guard_input.empty() && !guard) continue;
        Measured m{std::string(pipeline.stage_name(i)), spec, pipeline.stage_input(i, *in), std::nullopt, {}, {}, {}, {},
                   std::nullopt, {}, takes_one_number(*info, spec.param)};
        if (minus) m.minus = pipeline.stage_input(i, *minus);
        if (guard) m.guard = pipeline.stage_input(i, *guard);
        // Only a correlation time needs the lags beyond one (and their ring of past samples).
        const double max_lag_s = spec.statistic == FaultFreeStatistic::correlation_time
                                     ? generic::ResidualStatistics::kDefaultMaxLagS : 0.0;
        m.statistics.assign(m.input.dim, generic::ResidualStatistics(pipeline.sample_period_s(), max_lag_s));
        if (spec.statistic == FaultFreeStatistic::noise_density) {
          m.density.assign(m.input.dim, generic::NoiseDensity(pipeline.sample_period_s(), kNoiseDensityWindowS));
        }
        if (spec.statistic == FaultFreeStatistic::tick_noise || spec.statistic == FaultFreeStatistic::resolution) {
          m.tick_noise.resize(m.input.dim);
        }
        if (spec.statistic == FaultFreeStatistic::window_step) {
          m.window_step.assign(m.input.dim, generic::WindowStepNoise(pipeline.sample_period_s()));
        }
        if (spec.statistic == FaultFreeStatistic::guard_step) {
          m.guard_step.assign(m.input.dim, generic::GuardStepNoise(pipeline.sample_period_s()));
        }
        run.measured.push_back(std::move(m));
      }
    }
    return run;
  };
  Run first = prepare(pipeline, true);
  if (first.detectors.empty() && first.measured.empty()) {
    throw ConfigError(config_path + ":/stages", "has no threshold_detector stage and no calibrated parameter the "
                                                "config leaves open (" + calibrated_params_list(context.registry) +
                                                "); nothing to calibrate");
  }

  // Every fault-free log in turn (the pipeline restarts for each, and so does the warm-up).
  const std::vector<std::string> inputs = split_list(options.at("input"));
  // Refused before the logs are read: the thresholds file must not replace a log or the config.
  std::vector<std::string> read_files = inputs;
  read_files.push_back(config_path);
  try {
    io::check_output_path(options.at("output"), read_files, "--output");
  } catch (const io::OutputError& e) {
    throw UsageError{std::string("error: ") + e.what()};
  }
  for (const std::string& input : inputs) {
    if (input.empty()) throw UsageError{command + ": --input = '" + options.at("input") + "' has an empty log path"};
  }
  require_existing_files(command, options, specs, {"input"});
  // Runs `pipeline` over every log in turn (the pipeline restarts for each, and so does the
  // warm-up); false when a log cannot be read (said on stderr).
  const auto measure = [&](Pipeline& pipeline, Run& run, bool tell) {
    for (const std::string& input : inputs) {
      std::optional<io::CsvLogReader> log;
      try {
        log.emplace(input, time_column_of(pipeline));
      } catch (const io::LogError& e) {
        throw UsageError{std::string("error: ") + e.what()};
      }
      const ColumnMap map = ColumnMap::make(pipeline, *log);
      double start = std::nan("");
      double last = std::nan("");
      const ClockPolicy clock;
      RunSummary summary;
      try {
        summary = run_over_log(pipeline, *log, map, nullptr, [&](double t) {
          // The runner resets the pipeline after a long gap: the warm-up starts again there.
          if (std::isnan(start) || t - last > clock.gap_reset_periods * pipeline.sample_period_s()) {
            start = t;
            for (auto& m : run.measured) {
              for (auto& s : m.statistics) s.break_sequence();
              for (auto& d : m.density) d.break_sequence();
              for (auto& q : m.tick_noise) q.break_sequence();
              for (auto& w : m.window_step) w.break_sequence();
              for (auto& g : m.guard_step) g.break_sequence();
            }
          }
          last = t;
          if (t - start >= run.settle_s) {
            for (auto& m : run.measured) {
              const auto a = pipeline.values(m.input);
              for (std::size_t j = 0; j < a.size(); ++j) {
                const double r = m.minus ? a[j] - pipeline.values(*m.minus)[j] : a[j];
                m.statistics[j].add(r);
                if (!m.density.empty()) m.density[j].add(r);
                if (!m.tick_noise.empty()) m.tick_noise[j].add(r);
                if (!m.window_step.empty()) m.window_step[j].add(r);
                // NaN guard: unknown, so guarded (as the plugins take it).
                if (!m.guard_step.empty()) m.guard_step[j].add(r, pipeline.values(*m.guard)[j] != 0.0);
              }
            }
          }
          for (auto& d : run.detectors) {
            if (t - start < d.warmup_s) continue;
            const auto s = pipeline.values(d.signal);
            for (std::size_t j = 0; j < s.size(); ++j) {
              if (!std::isfinite(s[j])) continue;
              d.magnitudes[j].push_back(std::abs(s[j]));
              if (std::abs(s[j]) > d.max_abs[j]) d.max_time_s[j] = t;
              d.max_abs[j] = std::max(d.max_abs[j], std::abs(s[j]));
              d.min_seen[j] = std::min(d.min_seen[j], s[j]);
              d.max_seen[j] = std::max(d.max_seen[j], s[j]);
            }
          }
        });
      } catch (const io::LogError& e) {
        std::cerr << "error: " << e.what() << '\n';
        return false;
      }
      run.ticks += summary.ticks;
      if (tell) std::cerr << clock_warnings(input, summary, pipeline.sample_period_s(), clock);
    }

    return true;
  };
  if (!measure(pipeline, first, true)) return kExitRuntime;

  // The run's values, or what refuses them.
  std::vector<std::string> notes;  // values written with a caveat (the last run's, printed once)
  const auto conclude = [&](Run& run) {
    std::vector<std::string> refusals;
    notes.clear();
    // Refuse what cannot honestly be calibrated: a threshold from no data, from a burst, or that
    // overflows would pass as a number and silently blind (or deafen) the detector.
    constexpr double kBurstRatio = 1000.0;  // max |s| / median |s| of a fault-free residual is tens
    for (auto& d : run.detectors) {
      for (std::size_t j = 0; j < d.magnitudes.size(); ++j) {
        const std::string what = command + ": " + d.name + " channel " + std::to_string(j) + ": ";
        auto& m = d.magnitudes[j];
        if (m.empty()) {
          refusals.push_back(what + "no finite sample after the " + format_number(d.warmup_s) +
                             " s warm-up (a log shorter than the warm-up, or a virtual sensor never ready: is an "
                             "input such as the IMU all NaN?); calibrate on a log where it is");
          continue;
        }
        if (d.max_seen[j] == d.min_seen[j]) {
          refusals.push_back(what + "the signal was " + format_number(d.max_seen[j]) +
                             " throughout, so the threshold would be 0 and flag any change (an input never "
                             "finite, such as an all-NaN sensor, held by a filter?); calibrate on a log where it varies");
          continue;
        }
        const auto middle = m.begin() + static_cast<std::ptrdiff_t>(m.size() / 2);
        std::nth_element(m.begin(), middle, m.end());
        const double median = *middle;
        if (median > 0.0 && d.max_abs[j] > kBurstRatio * median) {
          refusals.push_back(what + "max |signal| " + format_number(d.max_abs[j]) + " at t = " +
                             format_number(d.max_time_s[j]) + " s is more than " + format_number(kBurstRatio) +
                             " x its median " + format_number(median) +
                             ": the log holds a burst or a fault there; calibrate on a fault-free log");
        }
        if (!std::isfinite(margin * d.max_abs[j])) {
          refusals.push_back(what + "margin x max |signal| = " + format_number(margin) + " x " +
                             format_number(d.max_abs[j]) + " is not a finite number; give a smaller --margin");
        }
      }
    }
    // The measured statistics, per parameter: a list per channel, or one number, the largest over
    // the channels, for a parameter the plugin takes once for all of them (calibration.hpp).
    for (const auto& m : run.measured) {
      std::vector<double> values;
      for (std::size_t j = 0; j < m.statistics.size(); ++j) {
        const generic::ResidualStatistics& st = m.statistics[j];
        const std::string what = command + ": " + m.stage + " " + std::string(m.spec.param) + " channel " +
                                 std::to_string(j) + ": ";
        if (st.count() < 2) {
          refusals.push_back(what + "fewer than 2 finite samples after the " + format_number(run.settle_s) +
                             " s warm-up (a log shorter than the warm-up, or an input never finite?); calibrate on a "
                             "log where it is");
          continue;
        }
        const double centre = st.centre(), sd = st.standard_deviation();
        double value = 0.0;
        switch (m.spec.statistic) {
          case FaultFreeStatistic::centre: value = centre; break;
          case FaultFreeStatistic::standard_deviation: value = sd; break;
          case FaultFreeStatistic::rms: value = std::sqrt(centre * centre + sd * sd); break;
          case FaultFreeStatistic::correlation_time: value = st.correlation_time_s(); break;
          case FaultFreeStatistic::noise_density: value = m.density[j].density(); break;
          case FaultFreeStatistic::tick_noise: value = m.tick_noise[j].standard_deviation(); break;
          case FaultFreeStatistic::resolution: value = m.tick_noise[j].resolution(); break;
          case FaultFreeStatistic::window_step: value = m.window_step[j].standard_deviation(); break;
          case FaultFreeStatistic::guard_step: value = m.guard_step[j].standard_deviation(); break;
        }
        const bool spread = m.spec.statistic == FaultFreeStatistic::standard_deviation ||
                            m.spec.statistic == FaultFreeStatistic::rms ||
                            m.spec.statistic == FaultFreeStatistic::noise_density ||
                            m.spec.statistic == FaultFreeStatistic::tick_noise ||
                            m.spec.statistic == FaultFreeStatistic::window_step ||
                            m.spec.statistic == FaultFreeStatistic::guard_step;
        if (m.spec.statistic == FaultFreeStatistic::noise_density && m.density[j].windows() < kMinNoiseDensityWindows) {
          refusals.push_back(what + std::to_string(m.density[j].windows()) + " whole windows of " +
                             format_number(kNoiseDensityWindowS) + " s after the warm-up, fewer than " +
                             std::to_string(kMinNoiseDensityWindows) + "; calibrate on at least " +
                             format_number(kMinNoiseDensityWindows * kNoiseDensityWindowS) +
                             " s of fault-free log after the warm-up (several logs add up), or give it in the config");
        } else if (m.spec.statistic == FaultFreeStatistic::tick_noise && m.tick_noise[j].count() == 0) {
          refusals.push_back(what + "no three consecutive finite readings that are not all equal: the reading "
                             "never changes (held?) or is never finite; give its noise in the config");
        } else if (m.spec.statistic == FaultFreeStatistic::window_step && m.window_step[j].count() == 0) {
          refusals.push_back(what + "no " + std::to_string(2 * m.window_step[j].window_ticks()) +
                             " consecutive finite samples after the warm-up (two windows of " +
                             format_number(generic::kStepWindowS) + " s); calibrate on a log where they are, or give "
                             "it in the config");
        } else if (m.spec.statistic == FaultFreeStatistic::guard_step && !(value > 0.0)) {
          // 0 is the parameter's own "not judged": a log without guards leaves steps inside one
          // unjudged rather than refuse the rest of the calibration.
          value = 0.0;
          notes.push_back(what + (m.guard_step[j].count() == 0
                                      ? "no guard (input " + std::string(m.spec.guard_input) + " nonzero) with " +
                                            std::to_string(m.guard_step[j].window_ticks()) +
                                            " finite unguarded samples on each side after the warm-up"
                                      : "the signal did not move across its guards") +
                          "; written as 0: a step inside a guard is not judged (calibrate on a log with guards, a "
                          "walk's landings, or give it in the config)");
        } else if (!std::isfinite(value)) {
          refusals.push_back(what + "is not a finite number (" + format_number(value) +
                             "): the log holds absurd values; calibrate on a fault-free log");
        } else if (spread && !(value > 0.0)) {
          refusals.push_back(what + "is 0: the signal did not vary, and a zero noise level would flag any change "
                                    "(an input held constant?); calibrate on a log where it varies, or give it in the "
                                    "config");
        }
        values.push_back(value);
      }
      if (m.one_number) {
        run.values.push_back(values.empty() ? 0.0 : *std::max_element(values.begin(), values.end()));
      } else {
        run.values.push_back(values);
      }
    }
    return refusals;
  };
  std::vector<std::string> refusals = conclude(first);
  if (!refusals.empty()) {
    for (const auto& r : refusals) std::cerr << "error: " << r << '\n';
    std::cerr << command << ": nothing written\n";
    return kExitRuntime;
  }

  const bool band = options.count("band") > 0;
  // The calibration file of a run; with `tell`, its values are printed too.
  const auto calibration_json = [&](const Run& run, bool tell) {
    Json out = {{"description", std::string(band ? "centres = (min + max) / 2 and thresholds = margin x (max - min) / 2 of the "
                                                   "detector input over a fault-free run, after warm-up"
                                                 : "thresholds = margin x max |detector input| over a fault-free run, after "
                                                   "warm-up") +
                                   (run.measured.empty() ? "" : "; params: fault-free statistics of the stages' inputs "
                                                                "(calibration.hpp) after the longest warm-up, measured on "
                                                                "a second run with the first run's values in place")},
                {"config", config_path},
                {"input", options.at("input")},
                {"margin", margin},
                {"band", band},
                {"sample_period_s", pipeline.sample_period_s()},
                {"ticks", run.ticks},
                {"stages", Json::object()}};
    for (const auto& d : run.detectors) {
      std::vector<double> thresholds;
      std::vector<double> centers;
      for (std::size_t j = 0; j < d.max_abs.size(); ++j) {
        const bool seen = d.min_seen[j] <= d.max_seen[j];  // a channel that was never finite has no range
        if (band) {
          centers.push_back(seen ? 0.5 * (d.min_seen[j] + d.max_seen[j]) : 0.0);
          thresholds.push_back(std::max(seen ? margin * 0.5 * (d.max_seen[j] - d.min_seen[j]) : 0.0, 1e-9));
        } else {
          thresholds.push_back(std::max(margin * d.max_abs[j], 1e-9));  // a threshold must be > 0
        }
      }
      Json entry = {{"warmup_s", d.warmup_s}, {"max_abs_signal", d.max_abs}, {"thresholds", thresholds}};
      if (band) {
        entry["min_signal"] = d.min_seen;
        entry["max_signal"] = d.max_seen;
        entry["centers"] = centers;
      }
      out["stages"][d.name] = entry;
      if (!tell) continue;
      std::cout << command << ": " << d.name << ": thresholds";
      for (double t : thresholds) std::cout << ' ' << std::round(t * 10.0) / 10.0;
      if (band) {
        std::cout << "; centres";
        for (double c : centers) std::cout << ' ' << std::round(c * 10.0) / 10.0;
      }
      std::cout << '\n';
    }
    for (std::size_t i = 0; i < run.measured.size(); ++i) {
      const Measured& m = run.measured[i];
      out["stages"][m.stage]["params"][std::string(m.spec.param)] = run.values[i];
      if (!tell) continue;
      std::cout << command << ": " << m.stage << ": " << m.spec.param;
      const Json& v = run.values[i];
      for (const Json& x : v.is_array() ? v : Json::array({v})) {
        char text[32];
        std::snprintf(text, sizeof text, " %.4g", x.get<double>());  // the file has every digit
        std::cout << text;
      }
      std::cout << '\n';
    }
    return out;
  };

  // The first run had every parameter it measures at its default, and a detector at a default
  // noise flags a healthy log: its flags move what the stages after it see (a recovery that
  // substitutes a reading, fed back to the relations a tick late), so the statistics measured
  // there are not the fault-free pipeline's. They are measured again on a second run with the
  // first run's values in place; the largest relative change between the runs is printed.
  Run calibrated = std::move(first);
  if (!calibrated.measured.empty()) {
    Json config = raw_config;
    (void)apply_thresholds(config, calibration_json(calibrated, false), "<the first run's values>");
    Pipeline second_pipeline = Pipeline::build(config, context.registry, std::filesystem::path(config_path).parent_path());
    Run second = prepare(second_pipeline, false);
    if (!measure(second_pipeline, second, false)) return kExitRuntime;
    refusals = conclude(second);
    if (!refusals.empty()) {
      for (const auto& r : refusals) std::cerr << "error: " << r << " (on the second run)\n";
      std::cerr << command << ": nothing written\n";
      return kExitRuntime;
    }
    double largest = 0.0;
    std::string where = "none";
    for (std::size_t i = 0; i < second.measured.size() && i < calibrated.values.size(); ++i) {
      const Json& before = calibrated.values[i];
      const Json& after = second.values[i];
      const Json before_list = before.is_array() ? before : Json::array({before});
      const Json after_list = after.is_array() ? after : Json::array({after});
      for (std::size_t j = 0; j < before_list.size() && j < after_list.size(); ++j) {
        const double b = before_list[j].get<double>(), a = after_list[j].get<double>();
        const double scale = std::max(std::abs(b), std::abs(a));
        const double change = scale > 0.0 ? std::abs(a - b) / scale : 0.0;
        if (change > largest) {
          largest = change;
          where = second.measured[i].stage + " " + std::string(second.measured[i].spec.param) + " channel " +
                  std::to_string(j);
        }
      }
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.3g %%", 100.0 * largest);
    std::cout << command << ": measured again with the first run's values in place: largest change " << text
              << " (" << where << ")\n";
    calibrated = std::move(second);
  }
  const Json out = calibration_json(calibrated, true);
  for (const auto& note : notes) std::cerr << "warning: " << note << '\n';
  std::optional<io::OutputFile> file;
  try {
    file.emplace(options.at("output"), read_files, "thresholds");
  } catch (const io::OutputError& e) {
    throw UsageError{std::string("error: ") + e.what()};
  }
  file->stream() << out.dump(2) << '\n';
  file->commit();
  return kExitOk;
}

}  // namespace ftsense::cli
