#include "ftsense/ports.hpp"

#include "ftsense/diagnostics.hpp"

namespace ftsense {

namespace {
std::optional<std::size_t> find_port(const std::vector<PortSpec>& ports, std::string_view name) {
  for (std::size_t i = 0; i < ports.size(); ++i) {
    if (ports[i].name == name) return i;
  }
  return std::nullopt;
}

std::vector<std::string> port_names(const std::vector<PortSpec>& ports) {
  std::vector<std::string> out;
  out.reserve(ports.size());
  for (const auto& p : ports) out.push_back(p.name);
  return out;
}
}  // namespace

std::size_t Ports::add_input(PortSpec spec) {
  FTSENSE_DEMAND(!find_input(spec.name), "input port declared twice: " + spec.name);
  FTSENSE_DEMAND(spec.dim > 0, "input port without values: " + spec.name);
  inputs_.push_back(std::move(spec));
  return inputs_.size() - 1;
}

std::size_t Ports::add_output(PortSpec spec) {
  FTSENSE_DEMAND(!find_output(spec.name), "output port declared twice: " + spec.name);
  FTSENSE_DEMAND(spec.dim > 0, "output port without values: " + spec.name);
  FTSENSE_DEMAND(spec.role == PortRole::signal, "roles are for inputs: " + spec.name);
  outputs_.push_back(std::move(spec));
  return outputs_.size() - 1;
}

std::optional<std::size_t> Ports::find_input(std::string_view name) const noexcept {
  return find_port(inputs_, name);
}
std::optional<std::size_t> Ports::find_output(std::string_view name) const noexcept {
  return find_port(outputs_, name);
}
std::vector<std::string> Ports::input_names() const { return port_names(inputs_); }
std::vector<std::string> Ports::output_names() const { return port_names(outputs_); }

StageContext::StageContext(double sample_period_s, std::string stage_name,
                           std::vector<std::pair<std::string, std::size_t>> wired_dims,
                           std::filesystem::path config_directory)
    : sample_period_s_(sample_period_s),
      stage_name_(std::move(stage_name)),
      wired_dims_(std::move(wired_dims)),
      config_directory_(std::move(config_directory)) {}

std::filesystem::path StageContext::resolve_path(const std::filesystem::path& path) const {
  if (path.is_absolute() || config_directory_.empty()) return path;
  return config_directory_ / path;
}

std::size_t StageContext::wired_dim(std::string_view input, std::size_t fallback) const noexcept {
  for (const auto& [name, dim] : wired_dims_) {
    if (name == input && dim > 0) return dim;
  }
  return fallback;
}

}  // namespace ftsense
