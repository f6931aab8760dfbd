#pragma once
// A pipeline of stages built from a JSON config, checked once, then stepped every tick.
//
// Config (pipeline_document.hpp describes it; docs/config_reference.md has every key):
//   {
//     "sample_period_s": 0.001,
//     "inputs": { "forces": { "columns": ["r_foot/p1/force_N", ...], "unit": "N" }, ... },
//     "stages": [ { "name": "residual", "plugin": "difference_residual", "params": {...},
//                   "inputs": { "measured": "input.forces", "virtual": "vfs.forces" } }, ... ],
//     "monitor": { "channels": [...], "measured": "input.forces", "virtual": "...",
//                  "fault_estimate": "...", "recovered": "...", "fault": "...",
//                  "fault_type": "..." },
//     "allow_dependent_virtual_sensor": false
//   }
// A wire names "input.<input>", "<stage>.<output port>" or "previous_tick.<name>", or an array
// of them that is concatenated in order. "previous_tick.<name>" (declared under "previous_tick":
// signal, dim, unit, initial) holds what its signal held at the end of the tick before: how a
// stage reads a later stage's output, one tick late (a feedback loop; without it, a cycle).
//
// Build checks, all reported together with JSON Pointer paths: document structure and key sets,
// unknown plugins, parameters, unknown or missing ports, doubly driven inputs, dimensions, units,
// cycles, and the independence rule (a stage input with role `virtual_estimate` must not depend
// on any pipeline input that its `measured` input depends on, unless
// "allow_dependent_virtual_sensor" is true, which turns the error into a warning).
//
// Per tick: write each input's values into input_values(i), call step(t), read values(ref).
// step() first converts each input with a scale or offset (value = scale * logged + offset), then
// replaces input values outside their input's plausible_range by NaN. Both act in place on the
// input values, so write the logged values before every step() (as `ftsense run` does).
// step() runs the stages in dependency order over one preallocated buffer: no allocation, no
// exception, no string lookup.

#include <array>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/diagnostics.hpp"
#include "ftsense/json_text.hpp"
#include "ftsense/monitor_columns.hpp"
#include "ftsense/params.hpp"
#include "ftsense/plugin.hpp"
#include "ftsense/plugin_registry.hpp"

namespace ftsense {

// A block of values in the pipeline's buffer.
struct SignalRef {
  std::size_t offset = 0;
  std::size_t dim = 0;
};

struct PipelineInput {
  std::string name;
  std::vector<std::string> columns;       // source columns (log column names), one per value
  std::string unit;
  std::vector<std::string> derived_from;  // other inputs this one is computed from
  SignalRef values;
  // Values outside [min, max] are replaced by NaN before the stages run (no range: +-inf).
  double plausible_min = -std::numeric_limits<double>::infinity();
  double plausible_max = std::numeric_limits<double>::infinity();
  // value = scale * logged + offset, one coefficient per value (1 and 0: no conversion).
  std::vector<double> scale;
  std::vector<double> offset;
};

// What the `run` program writes per monitored channel: one signal per row of kMonitorColumns
// (monitor_columns.hpp), each with one value per channel.
struct Monitor {
  std::vector<std::string> channels;
  std::string unit;  // unit of the measured signal
  std::array<SignalRef, kMonitorColumnCount> columns;
  // Optional further per-channel signals, written as <channel>/<name>[_<unit>].
  struct Extra {
    std::string name;
    std::string unit;
    SignalRef signal;
  };
  std::vector<Extra> extra;

  [[nodiscard]] SignalRef operator[](MonitorColumn column) const noexcept {
    return columns[static_cast<std::size_t>(column)];
  }
};

class Pipeline {
 public:
  // Builds and checks the pipeline; throws ConfigError listing every problem found.
  // `config_directory`: where the config file lives; plugins resolve relative file parameters
  // (a URDF, say) against it (StageContext::resolve_path). Empty: the working directory.
  [[nodiscard]] static Pipeline build(const Json& config, const PluginRegistry& plugins,
                                      const std::filesystem::path& config_directory = {});

  Pipeline(Pipeline&&) noexcept;
  Pipeline& operator=(Pipeline&&) noexcept;
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;
  ~Pipeline();

  [[nodiscard]] double sample_period_s() const noexcept { return sample_period_s_; }
  // The log's time column: name, unit as written, and seconds per unit.
  [[nodiscard]] const std::string& time_column() const noexcept { return time_column_; }
  [[nodiscard]] const std::string& time_unit() const noexcept { return time_unit_; }
  [[nodiscard]] double time_seconds_per_unit() const noexcept { return time_seconds_per_unit_; }
  [[nodiscard]] const std::vector<PipelineInput>& inputs() const noexcept { return inputs_; }
  [[nodiscard]] std::span<double> input_values(std::size_t input_index) noexcept;
  [[nodiscard]] bool has_monitor() const noexcept { return has_monitor_; }
  [[nodiscard]] const Monitor& monitor() const noexcept { return monitor_; }
  [[nodiscard]] const std::vector<Diagnostic>& warnings() const noexcept { return warnings_; }
  // Input values replaced by NaN for lying outside their input's plausible_range, per input,
  // since the pipeline was built (reset() keeps the count).
  [[nodiscard]] const std::vector<std::size_t>& implausible_counts() const noexcept { return implausible_; }

  // Looks up "input.<name>", "<stage>.<port>" or "previous_tick.<name>" (set-up time only; throws
  // ConfigError).
  [[nodiscard]] SignalRef signal(std::string_view reference) const;
  [[nodiscard]] std::span<const double> values(SignalRef ref) const noexcept {
    return {values_.data() + ref.offset, ref.dim};
  }
  // Every signal's reference name and unit: inputs, stage outputs in run order, previous-tick signals.
  [[nodiscard]] std::vector<std::pair<std::string, std::string>> signal_names() const;

  [[nodiscard]] std::size_t stage_count() const noexcept { return stages_.size(); }
  [[nodiscard]] std::string_view stage_name(std::size_t run_index) const noexcept;
  [[nodiscard]] Stage& stage(std::size_t run_index) noexcept;
  // The signal wired to input `input_index` of stage `run_index` (in the stage's buffer layout).
  [[nodiscard]] SignalRef stage_input(std::size_t run_index, std::size_t input_index) const noexcept {
    return stages_[run_index].input_refs[input_index];
  }

  // Writable view of a signal (tests, benchmarks and tools that set a stage's inputs directly).
  [[nodiscard]] std::span<double> mutable_values(SignalRef ref) noexcept {
    return {values_.data() + ref.offset, ref.dim};
  }
  // Runs one stage alone (its input gathers, then its step) over the current buffers.
  void step_stage(std::size_t run_index, double time_s) noexcept;

  // Back to the initial state: every stage reset, every buffer zeroed but the previous-tick
  // signals, which take their `initial` value.
  void reset() noexcept;
  // One tick at time `time_s` over the values currently in the input buffers.
  void step(double time_s) noexcept;

 private:
  Pipeline();
  friend class PipelineBuilder;

  struct Copy {
    std::size_t from = 0;
    std::size_t to = 0;
    std::size_t count = 0;
  };
  struct StageRun {
    std::string name;
    std::unique_ptr<Stage> stage;
    std::vector<Copy> gathers;  // concatenated inputs, copied before the step
    std::vector<SignalRef> input_refs;
    std::vector<SignalRef> output_refs;
    std::vector<std::string> output_units;  // resolved (unit-generic outputs take their input's)
    std::vector<std::span<const double>> input_spans;
    std::vector<std::span<double>> output_spans;
    StepIO io;
  };
  void bind_spans() noexcept;

  double sample_period_s_ = 0.0;
  std::string time_column_ = "time_s";
  std::string time_unit_ = "s";
  double time_seconds_per_unit_ = 1.0;
  std::vector<PipelineInput> inputs_;
  std::vector<StageRun> stages_;
  std::vector<Copy> monitor_gathers_;
  // The previous-tick signals: each a block the stages read (`values`), which holds one value
  // through a whole tick and after it: at the end of a tick its signal is copied into `staged`
  // (`previous_tick_stores_`), and at the start of the next `staged` into `values`
  // (`previous_tick_loads_`); reset() sets both to `initial`.
  struct PreviousTick {
    std::string name;
    std::string unit;
    SignalRef values;
    SignalRef staged;
    double initial = 0.0;
  };
  std::vector<PreviousTick> previous_ticks_;
  std::vector<Copy> previous_tick_loads_;
  std::vector<Copy> previous_tick_stores_;
  bool has_monitor_ = false;
  // The monitor's cannot_judge when no stage gives it: 1 where the virtual value is not finite.
  struct DerivedCannotJudge {
    bool active = false;
    SignalRef virtual_value;
    SignalRef cannot_judge;
  };
  DerivedCannotJudge derived_cannot_judge_;
  Monitor monitor_;
  std::vector<Diagnostic> warnings_;
  std::vector<double> values_;
  std::vector<std::size_t> implausible_;  // per input
  // The inputs with a plausible_range, laid out for the tick (the others cost nothing).
  struct InputGate {
    std::size_t input = 0;
    SignalRef values;
    double min = 0.0;
    double max = 0.0;
  };
  std::vector<InputGate> gates_;
  // The inputs' values with a scale or offset, laid out for the tick: buffer offset, coefficients.
  struct InputConversion {
    std::size_t at = 0;
    double scale = 1.0;
    double offset = 0.0;
  };
  std::vector<InputConversion> conversions_;
};

}  // namespace ftsense
