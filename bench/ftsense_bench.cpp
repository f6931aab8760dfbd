// ftsense-bench: what ftsense costs inside a 1 kHz control loop, on realistic inputs.
//
// The inputs are a simulated SURALP walk (MuJoCo, configs/scenarios/clean.json, 20 s, 20,000
// ticks) run through configs/suralp.json. Modes:
//
//   ftsense-bench [Google Benchmark flags]   per-stage and whole-tick benchmarks
//   ftsense-bench --latency-histogram N      N whole ticks timed one by one: median, p99, p99.9, max
//   ftsense-bench --ticks N [CONFIG]         just N whole ticks of configs/suralp.json, or of CONFIG
//                                            (a config reading some of its inputs; a path as given,
//                                            else relative to the source tree), for valgrind
//                                            --tool=callgrind
//
// Per stage: the stage's inputs are recorded tick by tick during a full run, then replayed into a
// one-stage pipeline of the same plugin and parameters, so each stage is timed alone on the data
// it really sees (the few input copies are included). Whole tick: the full pipeline, inputs
// written from the log row each tick.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "ftsense/generic/fault_classifier.hpp"
#include "ftsense/generic/gain_isolator.hpp"
#include "ftsense/generic/step_isolator.hpp"
#include "ftsense/generic/load_apportioner.hpp"
#include "ftsense/generic/plane_fit_residual.hpp"
#include "ftsense/generic/still_reading_isolator.hpp"
#include "ftsense/generic/physical_range_detector.hpp"
#include "ftsense/generic/rejoin_detector.hpp"
#include "ftsense/generic/stuck_hold.hpp"
#include "ftsense/generic/unread_load_isolator.hpp"
#include "ftsense/io/csv_log.hpp"
#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/sim/simulator.hpp"
#include "ftsense/text_file.hpp"

#ifndef FTSENSE_SOURCE_DIR
#define FTSENSE_SOURCE_DIR "."
#endif

namespace {

using ftsense::Json;
using ftsense::Pipeline;

Json read_json(const std::string& path) { return ftsense::parse_json_text(ftsense::read_text_file(path, "config file"), path); }

// CONFIG as given (absolute, or relative to the working directory) when it names a file there,
// else relative to the source tree (the form the docs' commands use, run from anywhere).
std::string config_path(const std::string& config) {
  std::error_code error;
  if (std::filesystem::is_regular_file(config, error)) return config;
  return std::string(FTSENSE_SOURCE_DIR) + "/" + config;
}

// The walk: per tick, the concatenated values of the pipeline's inputs.
// A simulated walk's inputs, tick by tick, laid out as configs/suralp.json's inputs (names and
// their columns, one after another).
struct Walk {
  std::vector<double> time;
  std::vector<std::vector<double>> inputs;
  std::vector<std::string> names;                  // the inputs, in suralp.json's order
  std::vector<std::vector<std::string>> columns;   // each one's columns
  std::vector<std::size_t> offsets;                // where each one starts in a tick's values
};

const Walk& walk() {
  static const Walk w = [] {
    ftsense::sim::Scenario scenario =
        ftsense::sim::load_scenario(std::string(FTSENSE_SOURCE_DIR) + "/configs/scenarios/clean.json");
    scenario.duration_s = 20.0;
    // In memory, not a temporary file: runs side by side (ctest -j, two worktrees) must not share one.
    std::stringstream csv;
    (void)ftsense::sim::simulate(scenario, 1, csv);
    const Pipeline p = Pipeline::build(read_json(std::string(FTSENSE_SOURCE_DIR) + "/configs/suralp.json"),
                                       ftsense::reference_plugins::registry());
    ftsense::io::CsvLogReader log(csv, "simulated walk");
    std::vector<std::size_t> columns;
    Walk result;
    for (const auto& in : p.inputs()) {
      result.names.push_back(in.name);
      result.columns.push_back(in.columns);
      result.offsets.push_back(columns.size());
      for (const auto& c : in.columns) columns.push_back(*log.find_column(c));
    }
    std::vector<double> row;
    while (log.next(row)) {
      result.time.push_back(row[0]);
      std::vector<double> values;
      for (std::size_t c : columns) values.push_back(row[c]);
      result.inputs.push_back(std::move(values));
    }
    return result;
  }();
  return w;
}

Json suralp_config(const std::string& solver) {
  Json config = read_json(std::string(FTSENSE_SOURCE_DIR) + "/configs/suralp.json");
  for (auto& stage : config["stages"]) {
    if (stage["plugin"] == "contact_force_distribution") stage["params"]["solver"] = solver;
  }
  return config;
}

// Writes one tick's values into p's inputs, one after another (a stage replay's own layout).
void write_inputs(Pipeline& p, const std::vector<double>& values) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.inputs().size(); ++i) {
    for (double& v : p.input_values(i)) v = values[k++];
  }
}

// Where each of p's inputs starts in a walk's values: matched by name and columns, so a config
// may read fewer of the walk's inputs (configs/suralp_robust.json reads no gait plan), in any
// order. Empty when p reads an input the walk does not have.
std::vector<std::size_t> walk_offsets(const Pipeline& p, const Walk& w) {
  std::vector<std::size_t> offsets;
  for (const auto& in : p.inputs()) {
    const auto at = std::find(w.names.begin(), w.names.end(), in.name);
    if (at == w.names.end() || w.columns[static_cast<std::size_t>(at - w.names.begin())] != in.columns) return {};
    offsets.push_back(w.offsets[static_cast<std::size_t>(at - w.names.begin())]);
  }
  return offsets;
}

// Writes one tick of the walk into p's inputs, at the offsets walk_offsets gave.
void write_walk_inputs(Pipeline& p, const std::vector<std::size_t>& offsets, const std::vector<double>& values) {
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    std::size_t k = offsets[i];
    for (double& v : p.input_values(i)) v = values[k++];
  }
}

// walk_offsets, or a clear end for a config that reads another robot's inputs.
std::vector<std::size_t> walk_offsets_or_exit(const Pipeline& p, const Walk& w, const std::string& what) {
  std::vector<std::size_t> offsets = walk_offsets(p, w);
  if (offsets.empty() && !p.inputs().empty()) {
    std::fprintf(stderr, "ftsense-bench: %s reads an input configs/suralp.json does not (by name and columns)\n",
                 what.c_str());
    std::exit(2);
  }
  return offsets;
}

// One stage, alone, with the inputs it saw in a full run.
struct StageReplay {
  std::string name;
  Pipeline pipeline;
  std::vector<std::vector<double>> inputs;  // per tick, concatenated in port order
};

StageReplay make_stage_replay(const Json& config, const std::string& stage_name) {
  Pipeline full = Pipeline::build(config, ftsense::reference_plugins::registry());
  std::size_t index = 0;
  while (full.stage_name(index) != stage_name) ++index;
  const ftsense::Stage& stage = full.stage(index);
  // The one-stage config: one pipeline input per stage input, same plugin and parameters.
  Json single = {{"sample_period_s", full.sample_period_s()}, {"inputs", Json::object()}};
  Json wires = Json::object();
  const auto& ports = stage.ports().inputs();
  for (std::size_t p = 0; p < ports.size(); ++p) {
    Json columns = Json::array();
    for (std::size_t c = 0; c < ports[p].dim; ++c) {
      // Appended, not "c" + std::to_string(p): GCC 12 warns falsely (-Wrestrict) on literal + temporary.
      std::string column = "c";
      column.append(std::to_string(p)).append("_").append(std::to_string(c));
      columns.push_back(column);
    }
    const std::string name = "in" + std::to_string(p);
    single["inputs"][name] = {{"columns", columns}, {"unit", ports[p].unit.empty() ? "u" : ports[p].unit}};
    wires[ports[p].name] = "input." + name;
  }
  single["stages"] = Json::array({{{"name", stage_name}, {"plugin", std::string(stage.plugin_name())},
                                   {"params", stage.params_json()}, {"inputs", wires}}});
  single["allow_dependent_virtual_sensor"] = true;
  StageReplay replay{stage_name, Pipeline::build(single, ftsense::reference_plugins::registry()), {}};
  const Walk& w = walk();
  const std::vector<std::size_t> offsets = walk_offsets_or_exit(full, w, "the config of stage " + stage_name);
  full.reset();
  for (std::size_t k = 0; k < w.time.size(); ++k) {
    write_walk_inputs(full, offsets, w.inputs[k]);
    full.step(w.time[k]);
    std::vector<double> seen;
    for (std::size_t p = 0; p < ports.size(); ++p) {
      const auto v = full.values(full.stage_input(index, p));
      seen.insert(seen.end(), v.begin(), v.end());
    }
    replay.inputs.push_back(std::move(seen));
  }
  return replay;
}

void bench_stage(benchmark::State& state, const Json& config, const std::string& stage_name) {
  StageReplay replay = make_stage_replay(config, stage_name);
  const Walk& w = walk();
  replay.pipeline.reset();
  std::size_t k = 0;
  for (auto _ : state) {
    write_inputs(replay.pipeline, replay.inputs[k]);
    replay.pipeline.step(w.time[k]);
    benchmark::ClobberMemory();
    if (++k == w.time.size()) k = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

void bench_tick_config(benchmark::State& state, const Json& config) {
  Pipeline p = Pipeline::build(config, ftsense::reference_plugins::registry());
  const Walk& w = walk();
  const std::vector<std::size_t> offsets = walk_offsets_or_exit(p, w, "a benchmarked config");
  p.reset();
  std::size_t k = 0;
  for (auto _ : state) {
    write_walk_inputs(p, offsets, w.inputs[k]);
    p.step(w.time[k]);
    benchmark::ClobberMemory();
    if (++k == w.time.size()) k = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

// fault_classifier at its worst: 16 channels at 1 kHz, every one flagged from the first tick, so
// each 0.1 s block ends with 16 fits over the 300-block (30 s) history. Inputs: a gait-like
// reference v = 300 + 250 sin(2 pi t) N and x = v + 20 N + white noise (seed 1), precomputed.
void bench_classifier_all_flagged(benchmark::State& state) {
  constexpr std::size_t kChannels = 16;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 60000;  // 60 s: the history fills, then rolls
  ftsense::generic::FaultClassifier::Params params;
  params.residual_noise_density = {1.0};
  ftsense::generic::FaultClassifier classifier(
      params, ftsense::StageContext(kPeriod, "classify", {{"measured", kChannels}}));
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 5.0);
  std::vector<double> x(kTicks * kChannels), v(kTicks * kChannels);
  for (std::size_t k = 0; k < kTicks; ++k) {
    for (std::size_t c = 0; c < kChannels; ++c) {
      v[k * kChannels + c] = 300.0 + 250.0 * std::sin(2.0 * M_PI * (static_cast<double>(k) * kPeriod + 0.05 * c));
      x[k * kChannels + c] = v[k * kChannels + c] + 20.0 + noise(rng);
    }
  }
  const std::vector<double> flag(kChannels, 1.0);
  std::vector<double> type(kChannels), estimate(kChannels);
  classifier.reset();
  std::size_t k = 0;
  for (auto _ : state) {
    const std::span<const double> ins[] = {flag, std::span<const double>(x).subspan(k * kChannels, kChannels),
                                           std::span<const double>(v).subspan(k * kChannels, kChannels)};
    const std::span<double> outs[] = {type, estimate};
    classifier.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    if (++k == kTicks) k = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

// The isolators' synthetic inputs: per tick, channel c's load 140 N swaying by 100 N at 1 Hz (its
// phase c / 8 of a period), read with white noise of 2 N (seed 1) and, on gain_channel, times
// gain; and the readings' sum less the true total (the sum residual). Row-major x.
struct SwayingLoads {
  std::vector<double> x;
  std::vector<double> sum_residual;
};
SwayingLoads swaying_loads(std::size_t ticks, std::size_t channels, double period,
                           std::size_t gain_channel = static_cast<std::size_t>(-1), double gain = 1.0) {
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 2.0);
  SwayingLoads out{std::vector<double>(ticks * channels), std::vector<double>(ticks)};
  for (std::size_t k = 0; k < ticks; ++k) {
    double measured_sum = 0.0, true_sum = 0.0;
    for (std::size_t c = 0; c < channels; ++c) {
      const double load = 140.0 + 100.0 * std::sin(2.0 * M_PI * (static_cast<double>(k) * period + 0.125 * c));
      out.x[k * channels + c] = (c == gain_channel ? gain : 1.0) * load + noise(rng);
      measured_sum += out.x[k * channels + c];
      true_sum += load;
    }
    out.sum_residual[k] = measured_sum - true_sum;
  }
  return out;
}

// step_isolator on 8 loaded channels at 1 kHz (W = 10): every row judged every tick, the 2 x 10
// window sums per channel its whole cost. Inputs: loads swaying about 140 N (+-100 N, 1 Hz, each
// channel's phase its own) plus white noise of 2 N (seed 1), the rows their sum residual against
// the true total, no alarm; precomputed.
void bench_step_isolator(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::StepIsolator::Params params;
  params.noise_std = {2.0};
  params.residual_step_std = {2.5};
  params.virtual_step_std = {4.5};
  ftsense::generic::StepIsolator isolator(params, ftsense::StageContext(kPeriod, "step", {{"signal", kChannels}}));
  const SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod);
  const std::vector<double>& x = loads.x;
  std::vector<double> r(kTicks * kChannels);
  for (std::size_t k = 0; k < kTicks; ++k) {
    for (std::size_t c = 0; c < kChannels; ++c) r[k * kChannels + c] = loads.sum_residual[k];
  }
  const std::vector<double> alarm(kChannels, 0.0);
  std::vector<double> fault(kChannels), type(kChannels), estimate(kChannels);
  isolator.reset();
  std::size_t k = 0;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(x).subspan(k * kChannels, kChannels),
                                           std::span<const double>(r).subspan(k * kChannels, kChannels), alarm};
    const std::span<double> outs[] = {fault, type, estimate};
    isolator.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    if (++k == kTicks) k = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

// gain_isolator on 8 channels at 1 kHz with the alarm up throughout (a decision at every block's
// end; loadable and substituted off, 0.1 s blocks over 3 s, each of 8 channels fitted with its onset searched).
// Inputs: the step_isolator bench's swaying loads and noise (seed 1), channel 3 reading twice its
// load; precomputed. The time is the mean over ticks: a decision falls on one tick in 100.
void bench_gain_isolator(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::GainIsolator::Params params;
  params.residual_noise_density = {5.0};
  ftsense::generic::GainIsolator isolator(params, ftsense::StageContext(kPeriod, "gains", {{"signal", kChannels}}));
  const SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod, /*gain_channel=*/3, /*gain=*/2.0);
  const std::vector<double>& x = loads.x;
  const std::vector<double>& e = loads.sum_residual;
  const std::vector<double> alarm(kChannels, 1.0);
  std::vector<double> fault(kChannels), type(kChannels);
  isolator.reset();
  std::size_t k = 0;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(x).subspan(k * kChannels, kChannels),
                                           std::span<const double>(e).subspan(k, 1), alarm};
    const std::span<double> outs[] = {fault, type};
    isolator.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    if (++k == kTicks) k = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

// stuck_hold on 8 channels at 1 kHz: channel 3 typed frozen for 0.3 s, then held (its
// reading stuck at 140 N with its 2 N noise), the others healthy (the swaying loads, seed 1);
// every channel's two low-passes run every tick. Precomputed inputs.
void bench_stuck_hold(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::StuckHold::Params params;
  params.noise_std = {2.0};
  ftsense::generic::StuckHold hold(params, ftsense::StageContext(kPeriod, "hold", {{"signal", kChannels}}));
  SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod);
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 2.0);
  for (std::size_t k = 0; k < kTicks; ++k) loads.x[k * kChannels + 3] = 140.0 + noise(rng);
  std::vector<double> flag(kChannels, 0.0), code(kChannels, 0.0);
  std::vector<double> fault(kChannels), type(kChannels), held(kChannels);
  hold.reset();
  // Channel 3 flagged frozen for its first 300 ticks (the episode's mean and noise), then held.
  constexpr std::size_t kFlagged = 300;
  flag[3] = 1.0;
  code[3] = ftsense::fault_code(ftsense::FaultType::frozen);
  for (std::size_t k = 0; k < kFlagged; ++k) {
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(k * kChannels, kChannels), flag,
                                           code};
    const std::span<double> outs[] = {fault, type, held};
    hold.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
  }
  flag[3] = 0.0;
  code[3] = 0.0;
  std::size_t k = kFlagged;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(k * kChannels, kChannels), flag,
                                           code};
    const std::span<double> outs[] = {fault, type, held};
    hold.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    if (++k == kTicks) k = kFlagged;
  }
  if (held[3] != 1.0) state.SkipWithError("channel 3 was let go: the benchmark did not measure a hold");
  state.SetItemsProcessed(state.iterations());
}

// rejoin_detector on 8 channels at 1 kHz, every channel flagged with an offset of 60 N that goes
// on (its recovered value the reading less 60): every channel judged every tick, none rejoins.
// Inputs: the swaying loads (seed 1); precomputed.
void bench_rejoin_detector(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::RejoinDetector::Params params;
  params.noise_std = {2.0};
  ftsense::generic::RejoinDetector rejoin(params, ftsense::StageContext(kPeriod, "rejoin", {{"signal", kChannels}}));
  const SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod);
  std::vector<double> recovered(loads.x.size());
  for (std::size_t i = 0; i < loads.x.size(); ++i) recovered[i] = loads.x[i] - 60.0;
  const std::vector<double> flagged(kChannels, 1.0);
  std::vector<double> rejoined(kChannels), pulses(kChannels, 0.0);
  rejoin.reset();
  std::size_t k = 1;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(k * kChannels, kChannels),
                                           std::span<const double>(recovered).subspan((k - 1) * kChannels, kChannels),
                                           flagged};
    const std::span<double> outs[] = {rejoined};
    rejoin.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    for (std::size_t j = 0; j < kChannels; ++j) pulses[j] += rejoined[j];
    if (++k == kTicks) k = 1;
  }
  for (double p : pulses) {
    if (p != 0.0) state.SkipWithError("a channel rejoined: the loads' noise passed the bound");
  }
  state.SetItemsProcessed(state.iterations());
}

// physical_range_detector on 8 channels at 1 kHz with a floor of 0 N: the swaying loads (all
// above it) judged every tick, none flagged.
// Inputs: the swaying loads (seed 1); precomputed.
void bench_physical_range_detector(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::PhysicalRangeDetector::Params params;
  params.floor = {0.0};
  params.noise_std = {2.0};
  ftsense::generic::PhysicalRangeDetector range(params,
                                                ftsense::StageContext(kPeriod, "pressed", {{"signal", kChannels}}));
  const SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod);
  std::vector<double> fault(kChannels), type(kChannels), flags(kChannels, 0.0);
  std::size_t k = 0;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(k * kChannels, kChannels)};
    const std::span<double> outs[] = {fault, type};
    range.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    for (std::size_t j = 0; j < kChannels; ++j) flags[j] += fault[j];
    if (++k == kTicks) k = 0;
  }
  for (double f : flags) {
    if (f != 0.0) state.SkipWithError("a channel was flagged: the loads went below the floor's bound");
  }
  state.SetItemsProcessed(state.iterations());
}

// load_apportioner on two feet of four pads at 1 kHz, both feet down and one pad of each
// substituted (l_foot/p4, r_foot/p3): every channel's virtual load is a solve of the sum and both
// feet's plane relations over three unknowns (its own and the two substituted). Inputs: the
// swaying loads (seed 1), the reference their true sum; precomputed.
void bench_load_apportioner(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::LoadApportioner::Params params;
  params.points_per_foot = 4;
  params.points = {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}};
  params.noise_std = {2.0};
  ftsense::generic::LoadApportioner apportion(
      params, ftsense::StageContext(kPeriod, "apportion", {{"signal", kChannels}, {"reference", 1}}));
  const SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod);
  std::vector<double> reference(kTicks);
  for (std::size_t k = 0; k < kTicks; ++k) {
    double sum = 0.0;
    for (std::size_t c = 0; c < kChannels; ++c) sum += loads.x[k * kChannels + c];
    reference[k] = sum - loads.sum_residual[k];
  }
  const std::vector<double> loadable(kChannels, 1.0), correction(kChannels, 0.0), flagged(kChannels, 0.0);
  std::vector<double> substituted(kChannels, 0.0), virtual_load(kChannels);
  substituted[3] = 1.0;
  substituted[6] = 1.0;
  double not_a_number = 0.0;
  std::size_t k = 0;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(k * kChannels, kChannels),
                                           std::span<const double>(reference).subspan(k, 1),
                                           loadable, correction, substituted, flagged};
    const std::span<double> outs[] = {virtual_load};
    apportion.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    if (k > 200 && std::isnan(virtual_load[3])) not_a_number += 1.0;
    if (++k == kTicks) k = 0;
  }
  if (not_a_number > 0.0) state.SkipWithError("a substituted pad was not apportioned once the relations were learnt");
  state.SetItemsProcessed(state.iterations());
}

// unread_load_isolator on 8 channels (two contact groups of 4) at 1 kHz, every channel loadable,
// after one tick in the air, the alarm up and the sum short (-100 N) throughout: every channel's
// state and every candidate test run every tick.
// Inputs: the swaying loads (seed 1); precomputed.
void bench_unread_load_isolator(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::UnreadLoadIsolator::Params params;
  params.contact_group_size = 4;
  params.noise_std = {2.0};
  params.residual_noise_std = {10.0};
  ftsense::generic::UnreadLoadIsolator isolator(params, ftsense::StageContext(kPeriod, "unread", {{"signal", kChannels}}));
  const SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod);
  const std::vector<double> e(1, -100.0), alarm(kChannels, 1.0), loadable(kChannels, 1.0), air(kChannels, 0.0);
  std::vector<double> fault(kChannels), type(kChannels);
  isolator.reset();
  {  // one tick in the air first, so that every channel has an air level
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(0, kChannels), e, alarm, air};
    const std::span<double> outs[] = {fault, type};
    isolator.step(ftsense::StepIO{0.0, ins, outs});
  }
  std::size_t k = 0;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(k * kChannels, kChannels), e,
                                           alarm, loadable};
    const std::span<double> outs[] = {fault, type};
    isolator.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    if (++k == kTicks) k = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

// plane_fit_residual on two feet of four pads at 1 kHz, both feet in full contact (every swaying
// load above the loaded bound), the readings corrected, none substituted: every row a 4 x 4 sum.
void bench_plane_fit_residual(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::PlaneFitResidual::Params params;
  params.points = {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}};
  params.loadable = params.correction = params.substituted = true;
  params.noise_std = {2.0};
  ftsense::generic::PlaneFitResidual plane(params, ftsense::StageContext(kPeriod, "plane", {{"signal", kChannels}}));
  const SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod);
  const std::vector<double> loadable(kChannels, 1.0), correction(kChannels, 0.0), substituted(kChannels, 0.0);
  std::vector<double> residual(kChannels);
  std::size_t k = 0;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(k * kChannels, kChannels),
                                           loadable, correction, substituted};
    const std::span<double> outs[] = {residual};
    plane.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    if (++k == kTicks) k = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

// still_reading_isolator on 8 channels at 1 kHz, the alarm up, nothing flagged: every block's end
// (50 ticks) judges the span; the other ticks add to the block's sums.
void bench_still_reading_isolator(benchmark::State& state) {
  constexpr std::size_t kChannels = 8;
  constexpr double kPeriod = 0.001;
  constexpr std::size_t kTicks = 20000;
  ftsense::generic::StillReadingIsolator::Params params;
  params.noise_std = {2.0};
  params.residual_noise_density = {0.5};
  ftsense::generic::StillReadingIsolator isolator(
      params, ftsense::StageContext(kPeriod, "still", {{"signal", kChannels}, {"sum_residual", 1}}));
  const SwayingLoads loads = swaying_loads(kTicks, kChannels, kPeriod);
  const std::vector<double> alarm(kChannels, 1.0), loadable(kChannels, 1.0), flagged(kChannels, 0.0);
  std::vector<double> fault(kChannels), type(kChannels);
  isolator.reset();
  std::size_t k = 0;
  for (auto _ : state) {
    const std::span<const double> ins[] = {std::span<const double>(loads.x).subspan(k * kChannels, kChannels),
                                           std::span<const double>(loads.sum_residual).subspan(k, 1), alarm,
                                           loadable, flagged};
    const std::span<double> outs[] = {fault, type};
    isolator.step(ftsense::StepIO{static_cast<double>(k) * kPeriod, ins, outs});
    benchmark::ClobberMemory();
    if (++k == kTicks) k = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

void register_benchmarks() {
  const std::pair<const char*, const char*> stages[] = {
      {"com", "lipm_com_estimator"},        {"split", "leg_force_split"},
      {"cop_l", "foot_cop"},                {"vfs_l", "contact_force_distribution"},
      {"fault_filter", "random_walk_fault_filter (8 channels)"}, {"fault_lowpass", "low_pass (8 channels)"},
      {"detector", "threshold_detector (8 channels)"}, {"recovery", "fault_recovery (8 channels)"}};
  for (const auto& [stage, what] : stages) {
    const std::string name = std::string("stage/") + stage + " [" + what + "]";
    benchmark::RegisterBenchmark(name.c_str(), [stage = std::string(stage)](benchmark::State& s) {
      bench_stage(s, suralp_config("active_set"), stage);
    });
  }
  benchmark::RegisterBenchmark("stage/vfs_l [contact_force_distribution, solver ceres]",
                               [](benchmark::State& s) { bench_stage(s, suralp_config("ceres"), "vfs_l"); });
  benchmark::RegisterBenchmark("stage/pads [contact_point_height, robust config]", [](benchmark::State& s) {
    bench_stage(s, read_json(std::string(FTSENSE_SOURCE_DIR) + "/configs/suralp_robust.json"), "pads");
  });
  benchmark::RegisterBenchmark("stage/fdi [contact_force_fdi, robust config]", [](benchmark::State& s) {
    bench_stage(s, read_json(std::string(FTSENSE_SOURCE_DIR) + "/configs/suralp_robust.json"), "fdi");
  });
  benchmark::RegisterBenchmark("stage/classify [fault_classifier, 16 channels all flagged, 1 kHz, synthetic]",
                               bench_classifier_all_flagged);
  benchmark::RegisterBenchmark("stage/step [step_isolator, 8 loaded channels, 1 kHz, synthetic]",
                               bench_step_isolator);
  benchmark::RegisterBenchmark("stage/gains [gain_isolator, 8 channels, alarm up, 1 kHz, synthetic]",
                               bench_gain_isolator);
  benchmark::RegisterBenchmark("stage/hold [stuck_hold, 8 channels, one held, 1 kHz, synthetic]", bench_stuck_hold);
  benchmark::RegisterBenchmark("stage/rejoin [rejoin_detector, 8 channels, all flagged, 1 kHz, synthetic]",
                               bench_rejoin_detector);
  benchmark::RegisterBenchmark("stage/range [physical_range_detector, 8 channels, floor 0, 1 kHz, synthetic]",
                               bench_physical_range_detector);
  benchmark::RegisterBenchmark(
      "stage/apportion [load_apportioner, 2 feet x 4 pads, 2 substituted, 1 kHz, synthetic]",
      bench_load_apportioner);
  benchmark::RegisterBenchmark("stage/unread [unread_load_isolator, 8 channels, alarm up, 1 kHz, synthetic]",
                               bench_unread_load_isolator);
  benchmark::RegisterBenchmark(
      "stage/plane [plane_fit_residual, 2 feet x 4 pads, full contact, 1 kHz, synthetic]", bench_plane_fit_residual);
  benchmark::RegisterBenchmark("stage/still [still_reading_isolator, 8 channels, alarm up, 1 kHz, synthetic]",
                               bench_still_reading_isolator);
  benchmark::RegisterBenchmark("tick/suralp.json [active_set solver]",
                               [](benchmark::State& s) { bench_tick_config(s, suralp_config("active_set")); });
  benchmark::RegisterBenchmark("tick/suralp.json [ceres solver]",
                               [](benchmark::State& s) { bench_tick_config(s, suralp_config("ceres")); });
  benchmark::RegisterBenchmark("tick/suralp_robust.json", [](benchmark::State& s) {
    bench_tick_config(s, read_json(std::string(FTSENSE_SOURCE_DIR) + "/configs/suralp_robust.json"));
  });
}

std::size_t parse_count(const char* text) {
  char* end = nullptr;
  const unsigned long long n = std::strtoull(text, &end, 10);
  if (end == text || *end != '\0' || n == 0) {
    std::fprintf(stderr, "ftsense-bench: '%s' is not a positive tick count\n", text);
    std::exit(2);
  }
  return static_cast<std::size_t>(n);
}

int latency_histogram(std::size_t ticks) {
  Pipeline p = Pipeline::build(suralp_config("active_set"), ftsense::reference_plugins::registry());
  const Walk& w = walk();
  const std::vector<std::size_t> offsets = walk_offsets_or_exit(p, w, "configs/suralp.json");
  std::vector<double> ns(ticks);
  p.reset();
  for (std::size_t i = 0, k = 0; i < ticks; ++i) {
    write_walk_inputs(p, offsets, w.inputs[k]);
    const auto start = std::chrono::steady_clock::now();
    p.step(w.time[k]);
    const auto stop = std::chrono::steady_clock::now();
    ns[i] = std::chrono::duration<double, std::nano>(stop - start).count();
    if (++k == w.time.size()) k = 0;
  }
  std::sort(ns.begin(), ns.end());
  auto at = [&](double q) { return ns[static_cast<std::size_t>(q * static_cast<double>(ticks - 1))]; };
  std::printf("latency of one whole tick of configs/suralp.json (active_set), %zu ticks over a %zu-tick walk:\n",
              ticks, w.time.size());
  std::printf("  median %.0f ns  p90 %.0f ns  p99 %.0f ns  p99.9 %.0f ns  max %.0f ns\n", at(0.5), at(0.9), at(0.99),
              at(0.999), ns.back());
  return 0;
}

int run_ticks(std::size_t ticks, const std::string& config) {
  Pipeline p = Pipeline::build(config.empty() ? suralp_config("active_set")
                                              : read_json(config_path(config)),
                               ftsense::reference_plugins::registry());
  const Walk& w = walk();
  const std::vector<std::size_t> offsets = walk_offsets_or_exit(p, w, config.empty() ? "configs/suralp.json" : config);
  p.reset();
  double sink = 0.0;
  for (std::size_t i = 0, k = 0; i < ticks; ++i) {
    write_walk_inputs(p, offsets, w.inputs[k]);
    p.step(w.time[k]);
    sink += p.values(p.monitor()[ftsense::MonitorColumn::recovered])[0];
    if (++k == w.time.size()) k = 0;
  }
  std::printf("ran %zu ticks (checksum %.6g)\n", ticks, sink);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--latency-histogram") return latency_histogram(parse_count(argv[2]));
  if ((argc == 3 || argc == 4) && std::string(argv[1]) == "--ticks") {
    // A config that cannot be read or built ends with its diagnostic, not std::terminate.
    try {
      return run_ticks(parse_count(argv[2]), argc == 4 ? argv[3] : "");
    } catch (const std::exception& error) {
      std::fprintf(stderr, "ftsense-bench: %s\n", error.what());
      return 2;
    }
  }
  register_benchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
