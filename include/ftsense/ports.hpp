#pragma once
// Named, fixed-size input and output ports of a pipeline stage, and the per-tick view of them.
//
// A port carries a vector of `dim` doubles in one unit (SI symbol, "1" for dimensionless). A
// plugin declares its ports in its constructor, in the order of its index constants, and never
// changes them afterwards. On every tick the pipeline hands the plugin a StepIO whose spans point
// into preallocated buffers: in(i) has inputs()[i].dim values, out(i) has outputs()[i].dim.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ftsense {

// What an input means to the independence rule (method.md section 0): a stage that compares a
// `measured` signal with a `virtual_estimate` must not get a virtual estimate computed from the
// very sensor it judges. The pipeline checks this once when it is built.
enum class PortRole { signal, measured, virtual_estimate };

// The unit of an input that accepts any unit; an output with this unit takes the (common) unit
// of the stage's any-unit inputs, so unit-generic plugins (filters, differences) pass units on.
inline constexpr std::string_view kAnyUnit = "";
inline constexpr std::string_view kDimensionless = "1";
// An output in the square of that common unit (a variance of a unit-generic estimate).
inline constexpr std::string_view kAnyUnitSquared = "^2";

struct PortSpec {
  std::string name;
  std::size_t dim = 1;
  std::string unit;
  std::string description;
  PortRole role = PortRole::signal;
  // Outputs only: channel j is computed without channel j of the stage's `measured` input
  // (a leave-one-out estimate). The independence rule then accepts it as the virtual sensor of
  // that measured signal, channel by channel.
  bool leave_one_out = false;
  // For the config reference (docs/config_reference.md), which lists ports without a config:
  // how `dim` follows the parameters or the wiring ("channels: as wired", "= len(params.joints)");
  // empty when `dim` is fixed.
  std::string dim_rule = {};
  // The frame a geometric vector is expressed in ("world", "base", "imu", "foot", "sole");
  // empty when no frame applies (scalars, per-channel signals, flags).
  std::string frame = {};

  // Set the optional fields on a spec written as {name, dim, unit, description[, role, ...]}:
  //   ports_.add_input(PortSpec{"com", 3, "m", "CoM position c"}.in_frame("world"));
  [[nodiscard]] PortSpec in_frame(std::string f) && {
    frame = std::move(f);
    return std::move(*this);
  }
  [[nodiscard]] PortSpec sized_by(std::string rule) && {
    dim_rule = std::move(rule);
    return std::move(*this);
  }
};

class Ports {
 public:
  // Both return the new port's index; plugins compare it with their index constants.
  std::size_t add_input(PortSpec spec);
  std::size_t add_output(PortSpec spec);

  [[nodiscard]] const std::vector<PortSpec>& inputs() const noexcept { return inputs_; }
  [[nodiscard]] const std::vector<PortSpec>& outputs() const noexcept { return outputs_; }
  [[nodiscard]] std::optional<std::size_t> find_input(std::string_view name) const noexcept;
  [[nodiscard]] std::optional<std::size_t> find_output(std::string_view name) const noexcept;
  [[nodiscard]] std::vector<std::string> input_names() const;
  [[nodiscard]] std::vector<std::string> output_names() const;

 private:
  std::vector<PortSpec> inputs_;
  std::vector<PortSpec> outputs_;
};

// The per-tick view a stage's step() receives. Spans point into the pipeline's buffers.
struct StepIO {
  double time_s = 0.0;
  std::span<const std::span<const double>> inputs;
  std::span<const std::span<double>> outputs;

  [[nodiscard]] std::span<const double> in(std::size_t index) const noexcept { return inputs[index]; }
  [[nodiscard]] std::span<double> out(std::size_t index) const noexcept { return outputs[index]; }
};

// What a stage's constructor may know about where it sits in a pipeline.
class StageContext {
 public:
  StageContext(double sample_period_s, std::string stage_name,
               std::vector<std::pair<std::string, std::size_t>> wired_dims = {},
               std::filesystem::path config_directory = {});

  // The pipeline's fixed tick period T [s].
  [[nodiscard]] double sample_period_s() const noexcept { return sample_period_s_; }
  [[nodiscard]] std::string_view stage_name() const noexcept { return stage_name_; }
  // Number of values wired to input `input`, or `fallback` when nothing is wired to it (the
  // pipeline reports the missing wire; the plugin only needs a size to construct with).
  [[nodiscard]] std::size_t wired_dim(std::string_view input, std::size_t fallback) const noexcept;
  // The directory of the config file the pipeline was built from (empty when it was not read from
  // a file). Plugins resolve relative file parameters against it (resolve_path).
  [[nodiscard]] const std::filesystem::path& config_directory() const noexcept { return config_directory_; }
  // `path` as given when absolute, else relative to config_directory() (or to the working
  // directory when that is empty).
  [[nodiscard]] std::filesystem::path resolve_path(const std::filesystem::path& path) const;

 private:
  double sample_period_s_;
  std::string stage_name_;
  std::vector<std::pair<std::string, std::size_t>> wired_dims_;
  std::filesystem::path config_directory_;
};

}  // namespace ftsense
