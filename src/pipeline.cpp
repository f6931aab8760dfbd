#include "ftsense/pipeline.hpp"

// The pipeline at run time: one buffer of values, stages stepped in order (pipeline_builder.cpp
// builds it).

#include <algorithm>
#include <cmath>
#include <limits>

namespace ftsense {

namespace {
// A gather copies a few values (a foot's three coordinates, its pads' readings) into the block a
// consumer reads, which never overlaps its source (PipelineBuilder::place allocates the block
// after every signal it gathers): up to four inline, where a library call (memmove, which
// std::copy_n becomes) costs more than the copy; longer ones through std::copy_n.
void gather(const double* from, std::size_t count, double* to) noexcept {
  switch (count) {
    case 4: to[3] = from[3]; [[fallthrough]];
    case 3: to[2] = from[2]; [[fallthrough]];
    case 2: to[1] = from[1]; [[fallthrough]];
    case 1: to[0] = from[0]; [[fallthrough]];
    case 0: return;
    default: std::copy_n(from, count, to);
  }
}
}  // namespace

Pipeline::Pipeline() = default;
Pipeline::Pipeline(Pipeline&&) noexcept = default;
Pipeline& Pipeline::operator=(Pipeline&&) noexcept = default;
Pipeline::~Pipeline() = default;

std::span<double> Pipeline::input_values(std::size_t input_index) noexcept {
  const SignalRef ref = inputs_[input_index].values;
  return {values_.data() + ref.offset, ref.dim};
}

std::string_view Pipeline::stage_name(std::size_t run_index) const noexcept {
  return stages_[run_index].name;
}

Stage& Pipeline::stage(std::size_t run_index) noexcept { return *stages_[run_index].stage; }

SignalRef Pipeline::signal(std::string_view reference) const {
  const auto dot = reference.find('.');
  std::vector<std::string> known;
  if (dot != std::string_view::npos) {
    const std::string_view node = reference.substr(0, dot);
    const std::string_view port = reference.substr(dot + 1);
    if (node == "input") {
      for (const auto& in : inputs_) {
        if (in.name == port) return in.values;
      }
    }
    if (node == "previous_tick") {
      for (const auto& p : previous_ticks_) {
        if (p.name == port) return p.values;
      }
    }
    for (const auto& s : stages_) {
      if (s.name != node) continue;
      if (const auto index = s.stage->ports().find_output(port)) return s.output_refs[*index];
    }
  }
  for (const auto& [name, unit] : signal_names()) known.push_back(name);
  throw ConfigError("", "no signal named '" + std::string(reference) + "'; " +
                            suggest(reference, known));
}

std::vector<std::pair<std::string, std::string>> Pipeline::signal_names() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& in : inputs_) out.emplace_back("input." + in.name, in.unit);
  for (const auto& s : stages_) {
    const auto& outputs = s.stage->ports().outputs();
    for (std::size_t o = 0; o < outputs.size(); ++o) out.emplace_back(s.name + "." + outputs[o].name, s.output_units[o]);
  }
  for (const auto& p : previous_ticks_) out.emplace_back("previous_tick." + p.name, p.unit);
  return out;
}

void Pipeline::bind_spans() noexcept {
  for (auto& s : stages_) {
    s.input_spans.clear();
    s.output_spans.clear();
    for (const SignalRef& r : s.input_refs) s.input_spans.emplace_back(values_.data() + r.offset, r.dim);
    for (const SignalRef& r : s.output_refs) s.output_spans.emplace_back(values_.data() + r.offset, r.dim);
    s.io.inputs = s.input_spans;
    s.io.outputs = s.output_spans;
  }
}

void Pipeline::reset() noexcept {
  std::fill(values_.begin(), values_.end(), 0.0);
  for (const PreviousTick& p : previous_ticks_) {
    std::fill_n(values_.begin() + static_cast<std::ptrdiff_t>(p.values.offset), p.values.dim, p.initial);
    std::fill_n(values_.begin() + static_cast<std::ptrdiff_t>(p.staged.offset), p.staged.dim, p.initial);
  }
  for (auto& s : stages_) s.stage->reset();
}

void Pipeline::step_stage(std::size_t run_index, double time_s) noexcept {
  double* const v = values_.data();
  StageRun& s = stages_[run_index];
  for (const Copy& c : s.gathers) gather(v + c.from, c.count, v + c.to);
  s.io.time_s = time_s;
  s.stage->step(s.io);
}

void Pipeline::step(double time_s) noexcept {
  double* const v = values_.data();
  // What the tick before left: its previous-tick signals' values, read in place through this one.
  for (const Copy& c : previous_tick_loads_) gather(v + c.from, c.count, v + c.to);
  for (const InputConversion& c : conversions_) v[c.at] = c.scale * v[c.at] + c.offset;
  for (const InputGate& g : gates_) {
    double* const first = v + g.values.offset;
    for (double* x = first; x != first + g.values.dim; ++x) {
      // NaN compares false both ways and stays as it is.
      if (*x < g.min || *x > g.max) {
        *x = std::numeric_limits<double>::quiet_NaN();
        ++implausible_[g.input];
      }
    }
  }
  for (auto& s : stages_) {
    for (const Copy& c : s.gathers) gather(v + c.from, c.count, v + c.to);
    s.io.time_s = time_s;
    s.stage->step(s.io);
  }
  for (const Copy& c : monitor_gathers_) gather(v + c.from, c.count, v + c.to);
  if (derived_cannot_judge_.active) {
    const double* from = v + derived_cannot_judge_.virtual_value.offset;
    double* to = v + derived_cannot_judge_.cannot_judge.offset;
    for (std::size_t i = 0; i < derived_cannot_judge_.cannot_judge.dim; ++i) to[i] = std::isfinite(from[i]) ? 0.0 : 1.0;
  }
  // Last: what the next tick reads as previous_tick.<name>, staged so that its block keeps this
  // tick's value for whoever reads the pipeline after step() (the monitor, --record, calibrate).
  for (const Copy& c : previous_tick_stores_) gather(v + c.from, c.count, v + c.to);
}

}  // namespace ftsense
