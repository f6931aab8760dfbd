// insole_fdi: fault detection on a real pressure-insole walk with a virtual sensor of our own.
//
// The program is ftsense's verbs (the ftsense::app library) with this example's plugin set, the
// reference plugins plus the insole virtual sensor: `insole_fdi run`, `check`, `calibrate`,
// `inject`, `report` and `plugins` behave as `ftsense <verb>` does. Its own verbs:
//
//   insole_fdi fit --config config/insole_fdi.json --input data/GaCo01_01.csv [--write]
//       fits the virtual sensor's coefficients on the healthy stretch [0, 40) s, prints the fit,
//       measures each signature_isolator's fault-free residual noise and each fault_classifier's
//       noise density there, and checks them against the config (exit 1 when they differ);
//       --write stores them.
//   insole_fdi evaluate --config config/insole_fdi.json --input data/GaCo01_01.csv
//       runs the pipeline over the walk twice: as recorded (virtual-sensor error, false alarms)
//       and with the fault schedule below injected (detection delay, type shown, false and cross
//       alarms). Exit 1 when an injected fault is missed, an alarm is raised outside the faults, or
//       a healthy sensor is flagged while another is faulty (a cross alarm: not isolated).
//
// Exit status: 0 success, 1 a check failed, 2 a usage, config or data error.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ftsense/app/app.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/calibration.hpp"
#include "ftsense/generic/fault_classifier.hpp"
#include "ftsense/generic/noise_density.hpp"
#include "ftsense/io/csv_log.hpp"
#include "ftsense/pipeline.hpp"
#include "insole/insole_fit.hpp"
#include "insole/insole_plugins.hpp"

namespace {

// The healthy stretch the coefficients are fitted on; everything after it is held out.
constexpr double kFitEndS = 40.0;
// Alarms on a channel up to this long after its fault ends are the flag clearing, not false alarms.
constexpr double kClearGraceS = 5.0;

using ftsense::FaultType;
struct InjectedFault {
  std::string channel;  // monitor channel, e.g. "left/L3"; the log column is channel + "/force_N"
  FaultType type;       // offset, drift, frozen or gain: the models run_pipeline applies
  double start_s;
  double end_s;
  double size;  // offset [N], drift rate [N/s], gain [1]; unused for frozen (holds the value at start_s)
};
// The fault schedule (deterministic: no random numbers). One fault at a time, 5 s apart at least.
const std::vector<InjectedFault> kSchedule = {
    {"left/L3", FaultType::offset, 50.0, 65.0, 80.0},
    {"right/R6", FaultType::drift, 70.0, 85.0, 8.0},
    {"right/R2", FaultType::frozen, 95.0, 110.0, 0.0},
    {"left/L7", FaultType::gain, 115.0, 121.0, 2.0},
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Log {
  std::vector<std::string> columns;  // without time_s
  std::vector<double> time_s;
  std::vector<std::vector<double>> rows;  // values per column, time excluded
};

Log read_log(const std::string& path) {
  ftsense::io::CsvLogReader reader(path);
  Log log;
  log.columns.assign(reader.columns().begin() + 1, reader.columns().end());
  std::vector<double> row;
  while (reader.next(row)) {
    log.time_s.push_back(row[0]);
    log.rows.emplace_back(row.begin() + 1, row.end());
  }
  if (log.rows.empty()) throw UsageError(path + ": no data rows");
  return log;
}

std::size_t column_index(const Log& log, const std::string& name, const std::string& where) {
  const auto it = std::find(log.columns.begin(), log.columns.end(), name);
  if (it == log.columns.end()) throw UsageError(where + ": the data has no column '" + name + "'");
  return static_cast<std::size_t>(it - log.columns.begin());
}

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw UsageError(path + ": cannot open");
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Runs the pipeline over the whole log; `faults` are injected into the measured columns.
// `on_tick(k, pipeline)` sees every tick after the step.
template <class OnTick>
void run_pipeline(ftsense::Pipeline& pipeline, const Log& log, const std::vector<InjectedFault>& faults,
                  const std::vector<std::vector<std::size_t>>& input_columns, OnTick&& on_tick) {
  pipeline.reset();
  std::vector<double> row(log.columns.size());
  std::map<std::size_t, double> frozen_value;  // column -> value held
  std::vector<std::size_t> fault_columns;
  for (const auto& f : faults) fault_columns.push_back(column_index(log, f.channel + "/force_N", "schedule"));
  for (std::size_t k = 0; k < log.rows.size(); ++k) {
    const double t = log.time_s[k];
    row = log.rows[k];
    for (std::size_t i = 0; i < faults.size(); ++i) {
      const auto& f = faults[i];
      if (t < f.start_s || t >= f.end_s) continue;
      double& value = row[fault_columns[i]];
      switch (f.type) {
        case FaultType::offset: value += f.size; break;
        case FaultType::drift: value += f.size * (t - f.start_s); break;
        case FaultType::frozen: value = frozen_value.try_emplace(fault_columns[i], value).first->second; break;
        case FaultType::gain: value *= f.size; break;
        default: break;  // the schedule holds only the four types above
      }
    }
    for (std::size_t in = 0; in < input_columns.size(); ++in) {
      auto values = pipeline.input_values(in);
      for (std::size_t c = 0; c < values.size(); ++c) values[c] = row[input_columns[in][c]];
    }
    pipeline.step(t);
    on_tick(k, pipeline);
  }
}

// The log's column of every pipeline input value, input by input.
std::vector<std::vector<std::size_t>> input_columns_of(const ftsense::Pipeline& pipeline, const Log& log,
                                                       const std::string& data_path) {
  std::vector<std::vector<std::size_t>> columns;
  for (const auto& in : pipeline.inputs()) {
    columns.emplace_back();
    for (const auto& c : in.columns) columns.back().push_back(column_index(log, c, data_path));
  }
  return columns;
}

// ---------------------------------------------------------------------------------------------
// fit

double round_significant(double value, int digits) {
  if (value == 0.0 || !std::isfinite(value)) return value;
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return std::stod(text);
}

// Prints `values` (ending the line begun by the caller) and whether params[key] holds exactly
// them, then stores them there; returns whether it held them.
bool store_measured(ftsense::Json& params, const std::string& key, const std::vector<double>& values,
                    const std::string& unit) {
  const auto it = params.find(key);
  bool match = it != params.end() && it->is_array() && it->size() == values.size();
  for (std::size_t i = 0; match && i < values.size(); ++i) match = (*it)[i].get<double>() == values[i];
  for (double v : values) std::cout << ' ' << v;
  std::cout << ' ' << unit << "\n  " << key << " in the config: " << (match ? "matches" : "DIFFERS") << '\n';
  params[key] = values;
  return match;
}

// Every signature_isolator's residual_noise_std: the RMS of the fault-free residual it judges,
// through the pipeline with the fitted coefficients over the healthy stretch, from the end of the
// warm-up of the detector that raises its alarms (whose filters start there). Rounded to 3
// significant digits and stored in `config`; returns whether the config held those values.
bool isolator_noise(ftsense::Json& config, const std::string& config_path, const Log& log,
                    const std::string& data_path) {
  bool all_match = true;
  for (auto& stage : config.at("stages")) {
    if (stage.at("plugin") != "signature_isolator") continue;
    const std::string stage_name = stage.at("name").get<std::string>();
    const auto& inputs = stage.at("inputs");
    if (!inputs.at("residual").is_string() || !inputs.at("alarm").is_string()) {
      throw UsageError(config_path + ": stage " + stage_name + ": fit needs 'residual' and 'alarm' wired to one signal each");
    }
    const std::string alarm_wire = inputs.at("alarm").get<std::string>();
    double warmup_s = 0.0;
    for (const auto& other : config.at("stages")) {
      if (other.at("name") == alarm_wire.substr(0, alarm_wire.find('.')) && other.contains("params")) {
        warmup_s = other.at("params").value("warmup_s", 0.0);
      }
    }
    ftsense::Pipeline pipeline = ftsense::Pipeline::build(config, insole::plugins::registry());
    const ftsense::SignalRef residual = pipeline.signal(inputs.at("residual").get<std::string>());
    std::vector<double> sum_sq;
    std::size_t samples = 0;
    run_pipeline(pipeline, log, {}, input_columns_of(pipeline, log, data_path),
                 [&](std::size_t k, const ftsense::Pipeline& p) {
                   const double t = log.time_s[k];
                   if (t - log.time_s.front() < warmup_s || t >= kFitEndS) return;
                   const auto r = p.values(residual);
                   sum_sq.resize(r.size(), 0.0);
                   for (std::size_t i = 0; i < r.size(); ++i) sum_sq[i] += std::isfinite(r[i]) ? r[i] * r[i] : 0.0;
                   ++samples;
                 });
    if (samples == 0) throw UsageError(data_path + ": no sample after the warm-up in the healthy stretch");
    std::vector<double> noise;
    for (double s : sum_sq) noise.push_back(round_significant(std::sqrt(s / static_cast<double>(samples)), 3));
    std::cout << "stage " << stage_name << ": residual noise (RMS over " << samples << " fault-free samples from "
              << warmup_s << " s):";
    all_match = store_measured(stage["params"], "residual_noise_std", noise, "N") && all_match;
  }
  return all_match;
}

// Every fault_classifier's residual_noise_density: the noise density of e = measured - virtual
// at the time scale the classifier fits (ftsense::generic::NoiseDensity, means over
// ftsense::kNoiseDensityWindowS windows, as `ftsense calibrate` measures it), over the healthy
// stretch after the first window (the filters' start-up). Rounded to 3 significant digits and
// stored in `config`; returns whether the config held those values.
bool classifier_noise_density(ftsense::Json& config, const Log& log, const std::string& data_path) {
  bool all_match = true;
  for (auto& stage : config.at("stages")) {
    if (stage.at("plugin") != ftsense::generic::FaultClassifier::name) continue;
    const std::string stage_name = stage.at("name").get<std::string>();
    ftsense::Pipeline pipeline = ftsense::Pipeline::build(config, insole::plugins::registry());
    std::size_t run_index = 0;
    while (pipeline.stage_name(run_index) != stage_name) ++run_index;
    const ftsense::SignalRef measured =
        pipeline.stage_input(run_index, ftsense::generic::FaultClassifier::kMeasured);
    const ftsense::SignalRef reference =
        pipeline.stage_input(run_index, ftsense::generic::FaultClassifier::kVirtual);
    std::vector<ftsense::generic::NoiseDensity> noise(
        measured.dim, ftsense::generic::NoiseDensity(pipeline.sample_period_s(), ftsense::kNoiseDensityWindowS));
    const double start_s = log.time_s.front() + ftsense::kNoiseDensityWindowS;
    run_pipeline(pipeline, log, {}, input_columns_of(pipeline, log, data_path),
                 [&](std::size_t k, const ftsense::Pipeline& p) {
                   const double t = log.time_s[k];
                   if (t < start_s || t >= kFitEndS) return;
                   const auto x = p.values(measured);
                   const auto v = p.values(reference);
                   for (std::size_t i = 0; i < measured.dim; ++i) noise[i].add(x[i] - v[i]);
                 });
    if (noise.empty() || noise.front().windows() == 0) {
      throw UsageError(data_path + ": the healthy stretch holds no whole window of " +
                       ftsense::format_number(ftsense::kNoiseDensityWindowS) + " s");
    }
    std::vector<double> density;
    for (const auto& q : noise) density.push_back(round_significant(q.density(), 3));
    std::cout << "stage " << stage_name << ": noise density of measured - virtual (means over "
              << noise.front().windows() << " windows of " << ftsense::kNoiseDensityWindowS << " s):";
    all_match = store_measured(stage["params"], "residual_noise_density", density, "N sqrt(s)") && all_match;
  }
  return all_match;
}

int fit_command(const std::string& config_path, const std::string& data_path, bool write) {
  ftsense::Json config = ftsense::parse_json_text(read_text(config_path), config_path);
  const Log log = read_log(data_path);
  const auto fit_rows = static_cast<Eigen::Index>(
      std::lower_bound(log.time_s.begin(), log.time_s.end(), kFitEndS) - log.time_s.begin());
  std::cout << "fit on the healthy stretch [" << log.time_s.front() << ", " << kFitEndS << ") s, "
            << fit_rows << " samples\n";
  bool all_match = true;
  bool any_stage = false;
  for (auto& stage : config.at("stages")) {
    if (stage.at("plugin") != insole::InsoleVirtualSensor::name) continue;
    any_stage = true;
    const std::string stage_name = stage.at("name").get<std::string>();
    const std::string wire = stage.at("inputs").at("measured").get<std::string>();
    if (wire.rfind("input.", 0) != 0) {
      throw UsageError(config_path + ": stage " + stage_name + ": fit needs 'measured' wired to a pipeline input");
    }
    const auto& columns = config.at("inputs").at(wire.substr(6)).at("columns");
    std::vector<std::string> names;
    std::vector<std::size_t> indices;
    for (const auto& c : columns) {
      names.push_back(c.get<std::string>());
      indices.push_back(column_index(log, names.back(), data_path));
    }
    auto& params = stage.at("params");
    const insole::InsoleVirtualSensor::Params defaults{};
    insole::FitOptions options;
    options.body_weight_N = params.at("body_weight_N").get<double>();
    options.contact_force_N = params.value("contact_force_N", defaults.contact_force_N);
    options.min_loaded_sensors = params.value("min_loaded_sensors", defaults.min_loaded_sensors);
    Eigen::MatrixXd samples(fit_rows, static_cast<Eigen::Index>(names.size()));
    for (Eigen::Index t = 0; t < fit_rows; ++t) {
      for (std::size_t k = 0; k < indices.size(); ++k) {
        samples(t, static_cast<Eigen::Index>(k)) = log.rows[static_cast<std::size_t>(t)][indices[k]];
      }
    }
    const insole::FootFit fit = insole::fit_foot(samples, names, options);
    std::vector<double> rounded;
    for (double c : fit.coefficients) rounded.push_back(round_significant(c, 6));

    std::cout << "stage " << stage_name << ":\n";
    for (std::size_t j = 0; j < names.size(); ++j) {
      std::printf("  %-18s rms error %6.2f N  stance samples %5zu  reciprocal condition %.3g\n",
                  names[j].c_str(), fit.rms_error_N[j], fit.stance_samples[j],
                  fit.reciprocal_condition[j]);
    }
    const auto it = params.find("coefficients");
    bool match = it != params.end() && it->is_array() && it->size() == rounded.size();
    for (std::size_t i = 0; match && i < rounded.size(); ++i) {
      const double stored = (*it)[i].get<double>();
      match = std::abs(stored - rounded[i]) <= 1e-5 * std::max(1.0, std::abs(rounded[i]));
    }
    std::cout << "  coefficients in the config: " << (match ? "match the fit" : "DIFFER from the fit") << '\n';
    all_match = all_match && match;
    params["coefficients"] = rounded;
  }
  if (!any_stage) throw UsageError(config_path + ": no stage uses plugin insole_virtual_sensor");
  all_match = isolator_noise(config, config_path, log, data_path) && all_match;
  all_match = classifier_noise_density(config, log, data_path) && all_match;
  if (write) {
    std::ofstream out(config_path);
    out << config.dump(2) << '\n';
    if (!out) throw UsageError(config_path + ": cannot write");
    std::cout << "wrote the fitted coefficients to " << config_path << '\n';
    return 0;
  }
  if (!all_match) {
    std::cerr << config_path << ": the coefficients are not those of the fit; run `insole_fdi fit --write`\n";
    return 1;
  }
  return 0;
}

// ---------------------------------------------------------------------------------------------
// evaluate

struct ChannelStats {
  // healthy (as recorded) run, held-out part t >= kFitEndS
  double sum_sq_error = 0.0;
  std::size_t samples = 0;
  double stance_sum_sq_error = 0.0;
  std::size_t stance_samples = 0;
  int healthy_alarms = 0;
  double healthy_alarm_s = 0.0;
  // faulty run
  std::optional<double> detection_delay_s;
  std::optional<double> typed_delay_s;  // from the fault's start to the first tick of its own type
  double fault_sum_sq_raw = 0.0;        // (measured - true)^2 from the detection to the fault's end
  double fault_sum_sq_recovered = 0.0;  // (recovered - true)^2 over the same ticks
  std::size_t fault_samples = 0;
  std::map<FaultType, std::size_t> shown;  // ticks per type shown while the channel's fault is active
  int false_alarms = 0;  // raised while no fault is active anywhere (nor clearing)
  double false_alarm_s = 0.0;
  int cross_alarms = 0;  // raised on this healthy channel while another channel is faulty
  double cross_alarm_s = 0.0;
};

// The type the pipeline showed most while the channel's fault was active; none if never flagged.
std::optional<FaultType> most_shown(const ChannelStats& s) {
  std::optional<FaultType> type;
  std::size_t most = 0;
  for (const auto& [t, ticks] : s.shown) {
    if (ticks > most) {
      most = ticks;
      type = t;
    }
  }
  return type;
}

int evaluate_command(const std::string& config_path, const std::string& data_path) {
  const auto registry = insole::plugins::registry();
  ftsense::Pipeline pipeline =
      ftsense::Pipeline::build(ftsense::parse_json_text(read_text(config_path), config_path), registry);
  if (!pipeline.has_monitor()) throw UsageError(config_path + ": needs a 'monitor' section");
  const Log log = read_log(data_path);
  const auto input_columns = input_columns_of(pipeline, log, data_path);
  const ftsense::Monitor& monitor = pipeline.monitor();
  const std::size_t n = monitor.channels.size();
  std::optional<ftsense::SignalRef> stance;
  for (const auto& e : monitor.extra) {
    if (e.name == "stance") stance = e.signal;
  }
  const double dt = pipeline.sample_period_s();
  std::vector<ChannelStats> stats(n);

  // 1. As recorded: the virtual sensor's error on held-out healthy data, and alarms (all false).
  std::vector<double> previous(n, 0.0);
  run_pipeline(pipeline, log, {}, input_columns, [&](std::size_t k, const ftsense::Pipeline& p) {
    const auto measured = p.values(monitor[ftsense::MonitorColumn::measured]);
    const auto virtual_value = p.values(monitor[ftsense::MonitorColumn::virtual_value]);
    const auto fault = p.values(monitor[ftsense::MonitorColumn::fault]);
    for (std::size_t c = 0; c < n; ++c) {
      if (fault[c] != 0.0) {
        stats[c].healthy_alarm_s += dt;
        if (previous[c] == 0.0) ++stats[c].healthy_alarms;
      }
      previous[c] = fault[c];
      if (log.time_s[k] < kFitEndS) continue;
      const double e = measured[c] - virtual_value[c];
      if (!std::isfinite(e)) continue;
      stats[c].sum_sq_error += e * e;
      ++stats[c].samples;
      if (stance && p.values(*stance)[c] != 0.0) {
        stats[c].stance_sum_sq_error += e * e;
        ++stats[c].stance_samples;
      }
    }
  });

  // 2. With the fault schedule injected.
  std::vector<std::optional<std::size_t>> fault_of(n);  // channel -> index in kSchedule
  for (std::size_t i = 0; i < kSchedule.size(); ++i) {
    const auto it = std::find(monitor.channels.begin(), monitor.channels.end(), kSchedule[i].channel);
    if (it == monitor.channels.end()) throw UsageError("schedule: no monitored channel " + kSchedule[i].channel);
    fault_of[static_cast<std::size_t>(it - monitor.channels.begin())] = i;
  }
  std::fill(previous.begin(), previous.end(), 0.0);
  std::vector<std::size_t> true_column(n);  // the recorded (true) value of each channel
  for (std::size_t c = 0; c < n; ++c) true_column[c] = column_index(log, monitor.channels[c] + "/force_N", data_path);
  run_pipeline(pipeline, log, kSchedule, input_columns, [&](std::size_t k, const ftsense::Pipeline& p) {
    const double t = log.time_s[k];
    const auto fault = p.values(monitor[ftsense::MonitorColumn::fault]);
    const auto fault_type = p.values(monitor[ftsense::MonitorColumn::fault_type]);
    const auto measured = p.values(monitor[ftsense::MonitorColumn::measured]);
    const auto recovered = p.values(monitor[ftsense::MonitorColumn::recovered]);
    bool any_fault_active = false;
    for (const auto& f : kSchedule) any_fault_active = any_fault_active || (t >= f.start_s && t < f.end_s + kClearGraceS);
    for (std::size_t c = 0; c < n; ++c) {
      if (fault_of[c]) {
        const auto& f = kSchedule[*fault_of[c]];
        const double truth = log.rows[k][true_column[c]];
        // From the detection on: before it, the recovered signal is the faulty reading by design.
        if (t >= f.start_s && t < f.end_s && std::isfinite(truth) && (stats[c].detection_delay_s || fault[c] != 0.0)) {
          stats[c].fault_sum_sq_raw += (measured[c] - truth) * (measured[c] - truth);
          stats[c].fault_sum_sq_recovered += (recovered[c] - truth) * (recovered[c] - truth);
          ++stats[c].fault_samples;
        }
      }
      const bool raised = fault[c] != 0.0 && previous[c] == 0.0;
      previous[c] = fault[c];
      if (fault[c] == 0.0) continue;
      if (fault_of[c]) {
        const auto& f = kSchedule[*fault_of[c]];
        if (t >= f.start_s && t < f.end_s) {
          if (!stats[c].detection_delay_s) stats[c].detection_delay_s = t - f.start_s;
          const FaultType shown = ftsense::fault_type_from_code(fault_type[c]).value_or(FaultType::unclassified);
          if (!stats[c].typed_delay_s && shown == f.type) stats[c].typed_delay_s = t - f.start_s;
          ++stats[c].shown[shown];
          continue;
        }
        if (t >= f.end_s && t < f.end_s + kClearGraceS) continue;  // clearing
      }
      ChannelStats& s = stats[c];
      if (any_fault_active) {
        s.cross_alarm_s += dt;
        s.cross_alarms += raised ? 1 : 0;
      } else {
        s.false_alarm_s += dt;
        s.false_alarms += raised ? 1 : 0;
      }
    }
  });

  std::printf("insole_fdi: %s over %s (%zu samples, %.2f s)\n", config_path.c_str(), data_path.c_str(),
              log.rows.size(), log.time_s.back() - log.time_s.front());
  std::printf("coefficients fitted on [0, %.0f) s; errors on the held-out [%.0f, end) s of the recorded walk\n",
              kFitEndS, kFitEndS);
  std::printf("fault schedule (deterministic, no random numbers):\n");
  for (const auto& f : kSchedule) {
    const std::string type(to_string(f.type));
    std::printf("  %-9s %-6s from %5.1f s to %5.1f s", f.channel.c_str(), type.c_str(), f.start_s, f.end_s);
    if (f.type == FaultType::offset) std::printf(", %+.0f N", f.size);
    if (f.type == FaultType::drift) std::printf(", %+.1f N/s", f.size);
    if (f.type == FaultType::frozen) std::printf(", held at the value read at %.1f s", f.start_s);
    if (f.type == FaultType::gain) std::printf(", x %.1f", f.size);
    std::printf("\n");
  }
  std::printf("\n%-9s | %9s %9s | %14s | %-6s %9s %-12s | %14s | %14s\n", "channel", "rms err", "stance", "alarms",
              "fault", "delay", "type shown", "false alarms", "cross alarms");
  std::printf("%-9s | %9s %9s | %14s | %-6s %9s %-12s | %14s | %14s\n", "", "[N]", "rms [N]", "recorded n/s",
              "", "[s]", "", "injected n/s", "injected n/s");
  int missed = 0;
  int false_alarms = 0;
  int cross_alarms = 0;
  for (std::size_t c = 0; c < n; ++c) {
    const ChannelStats& s = stats[c];
    const double rms = s.samples > 0 ? std::sqrt(s.sum_sq_error / static_cast<double>(s.samples)) : NAN;
    const double stance_rms =
        s.stance_samples > 0 ? std::sqrt(s.stance_sum_sq_error / static_cast<double>(s.stance_samples)) : NAN;
    std::string type = "-";
    std::string delay = "-";
    const std::optional<FaultType> most = most_shown(s);
    const std::string shown = most ? std::string(to_string(*most)) : "-";
    if (fault_of[c]) {
      type = to_string(kSchedule[*fault_of[c]].type);
      if (s.detection_delay_s) {
        char text[32];
        std::snprintf(text, sizeof text, "%.2f", *s.detection_delay_s);
        delay = text;
      } else {
        delay = "MISSED";
        ++missed;
      }
    }
    false_alarms += s.healthy_alarms + s.false_alarms;
    cross_alarms += s.cross_alarms;
    std::printf("%-9s | %9.2f %9.2f | %6d %6.2f s | %-6s %9s %-12s | %6d %6.2f s | %6d %6.2f s\n",
                monitor.channels[c].c_str(), rms, stance_rms, s.healthy_alarms, s.healthy_alarm_s,
                type.c_str(), delay.c_str(), shown.c_str(), s.false_alarms, s.false_alarm_s, s.cross_alarms,
                s.cross_alarm_s);
  }
  // The injected faults: when they were typed, and how far the recovered signal is from the truth.
  std::printf("\n%-9s | %-6s | %9s %9s %-12s | %9s %9s\n", "channel", "fault", "detected", "typed", "type shown",
              "raw rms", "recovered");
  std::printf("%-9s | %-6s | %9s %9s %-12s | %19s\n", "", "", "after [s]", "after [s]", "(most ticks)",
              "from detection [N]");
  int mistyped = 0;
  for (std::size_t c = 0; c < n; ++c) {
    if (!fault_of[c]) continue;
    const ChannelStats& s = stats[c];
    const FaultType injected = kSchedule[*fault_of[c]].type;
    const FaultType shown = most_shown(s).value_or(FaultType::none);
    mistyped += shown == injected ? 0 : 1;
    const auto seconds = [](const std::optional<double>& d) {
      char text[32];
      std::snprintf(text, sizeof text, "%.2f", d.value_or(NAN));
      return d ? std::string(text) : std::string("never");
    };
    const double samples = static_cast<double>(std::max<std::size_t>(1, s.fault_samples));
    std::printf("%-9s | %-6s | %9s %9s %-12s | %9.1f %9.1f\n", monitor.channels[c].c_str(),
                std::string(to_string(injected)).c_str(), seconds(s.detection_delay_s).c_str(),
                seconds(s.typed_delay_s).c_str(), std::string(to_string(shown)).c_str(),
                std::sqrt(s.fault_sum_sq_raw / samples), std::sqrt(s.fault_sum_sq_recovered / samples));
  }
  std::printf("\nmissed faults %d, mistyped faults %d (the type shown most is not the injected one), false alarms "
              "%d (recorded walk, and injected walk outside the faults and %.0f s after each), cross alarms %d "
              "(healthy channels flagged while another is faulty)\n",
              missed, mistyped, false_alarms, kClearGraceS, cross_alarms);
  if (missed > 0 || mistyped > 0 || false_alarms > 0 || cross_alarms > 0) {
    std::printf("FAIL\n");
    return 1;
  }
  std::printf("OK\n");
  return 0;
}

// The option conventions of ftsense's verbs (ftsense/app/options.hpp).
const std::vector<ftsense::app::OptionSpec> kFitOptions{
    {"config", true, true, "the pipeline config (JSON) whose insole_virtual_sensor stages are fitted", 'c', {},
     ftsense::app::FileArg::input},
    {"input", true, true, "the walk (CSV); its healthy stretch [0, 40) s is fitted", 'i', {}, ftsense::app::FileArg::input},
    {"write", false, false, "store the fitted coefficients in the config"}};
const std::vector<ftsense::app::OptionSpec> kEvaluateOptions{
    {"config", true, true, "the pipeline config (JSON)", 'c', {}, ftsense::app::FileArg::input},
    {"input", true, true, "the recorded walk (CSV)", 'i', {}, ftsense::app::FileArg::input}};

// A verb of this program: its options parsed as ftsense's are, and this file's errors (usage,
// data, fit) reported as usage or data errors (exit 2), as ftsense reports its own.
template <class Body>
int own_verb(const std::string& command, const std::vector<std::string>& args,
             const std::vector<ftsense::app::OptionSpec>& specs, std::string_view summary, Body&& body) {
  const auto options = ftsense::app::parse_options(command, args, specs);
  if (options.count("help")) {
    std::cout << ftsense::app::usage_text(command, summary, specs);
    return 0;
  }
  ftsense::app::require_existing_files(command, options, specs, {"config", "input"});
  const std::string& config_path = options.at("config");
  try {
    return body(options);
  } catch (const UsageError& e) {
    throw ftsense::app::UsageError{command + ": " + e.what()};
  } catch (const ftsense::ConfigError& e) {
    std::string message;
    for (const auto& p : e.problems()) message += (message.empty() ? "" : "\n") + config_path + ": " + p.text();
    throw ftsense::app::UsageError{message};
  } catch (const ftsense::io::LogError& e) {
    throw ftsense::app::UsageError{e.what()};
  } catch (const insole::FitError& e) {
    throw ftsense::app::UsageError{e.what()};
  } catch (const ftsense::Json::exception& e) {
    throw ftsense::app::UsageError{config_path + ": " + e.what()};
  }
}

}  // namespace

// [snippet:app_main]
int main(int argc, char** argv) {
  const ftsense::PluginRegistry registry = insole::plugins::registry();
  const std::vector<ftsense::app::Verb> own_verbs{
      {"fit", "fit the virtual sensor's coefficients on the healthy stretch and check the config's",
       [](const std::vector<std::string>& args, const ftsense::app::Context& context) {
         return own_verb(context.command("fit"), args, kFitOptions,
                         "Fits each insole_virtual_sensor stage's coefficients on the healthy stretch [0, 40) s\n"
                         "of --input, prints the fit, measures each signature_isolator's fault-free\n"
                         "residual noise and each fault_classifier's noise density there (through the\n"
                         "pipeline with the fitted coefficients), and checks them against the config\n"
                         "(exit 1 when they differ); --write stores them.",
                         [](const ftsense::app::Options& o) {
                           return fit_command(o.at("config"), o.at("input"), o.count("write") > 0);
                         });
       }},
      {"evaluate", "detection delays and false alarms with a fault schedule injected into the walk",
       [](const std::vector<std::string>& args, const ftsense::app::Context& context) {
         return own_verb(context.command("evaluate"), args, kEvaluateOptions,
                         "Runs the pipeline over the walk as recorded (virtual-sensor error on the held-out\n"
                         "part, false alarms) and with a fixed fault schedule injected (offset, drift,\n"
                         "frozen, gain: detection delay, type shown, false and cross alarms). Exit 1 when an\n"
                         "injected fault is missed, an alarm is raised outside the faults, or a healthy\n"
                         "sensor is flagged while another is faulty.",
                         [](const ftsense::app::Options& o) { return evaluate_command(o.at("config"), o.at("input")); });
       }}};
  return ftsense::app::main(argc, argv, registry,
                            {"insole_fdi", "0.1",
                             "Fault detection on pressure insoles (8 sensors per foot) with a leave-one-out virtual\n"
                             "sensor: ftsense's verbs with this example's plugins, and the example's own."},
                            own_verbs);
}
// [end-snippet]
