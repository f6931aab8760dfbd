#pragma once
// The run-time catalogue of plugins a pipeline can be built from (made from a PluginSet).

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense {

struct PluginInfo {
  std::string name;
  std::string summary;
  std::vector<ParamInfo> params;
  // JSON text of the parameters the reference's port table is made with: the plugin's
  // example_params, one object or an array of them; empty when the defaults serve.
  std::string example_params;
  // The plugin's ports as declared with each example over the defaults (or by its declare_ports),
  // for a stage ticking every `sample_period_s` and wired to nothing; the union over the examples
  // (a port some parameters add). A port sized by its wiring or parameters has the size of the
  // example and says how in its dim_rule. Null, with the problems in `diag`, when an example
  // does not construct.
  std::function<std::optional<Ports>(double sample_period_s, Diagnostics& diag)> example_ports;
  // The parameters `ftsense calibrate` measures on fault-free logs (calibration.hpp); empty for
  // most plugins.
  std::vector<CalibratedParam> calibrated_params;
  // Checks parameters only (used when a stage cannot be constructed, to still report them).
  std::function<void(const Json& raw, std::string_view params_path, Diagnostics& diag)> check_params;
  // Loads parameters and constructs the stage. Returns null when anything is wrong; problems go
  // to `diag` with paths under `stage_path` (parameters under stage_path + "/params").
  std::function<std::unique_ptr<Stage>(const Json& raw_params, std::string_view stage_path,
                                       const StageContext& context, Diagnostics& diag)>
      create;
};

template <Plugin P>
PluginInfo make_plugin_info() {
  PluginInfo info;
  info.name = std::string(P::name);
  info.summary = std::string(P::summary);
  info.params = param_infos<typename P::Params>();
  info.check_params = [](const Json& raw, std::string_view params_path, Diagnostics& diag) {
    (void)load_params<typename P::Params>(raw, params_path, P::name, diag);
  };
  info.create = [](const Json& raw, std::string_view stage_path, const StageContext& context,
                   Diagnostics& diag) -> std::unique_ptr<Stage> {
    Diagnostics local;
    const std::string params_path = std::string(stage_path) + "/params";
    auto params = load_params<typename P::Params>(raw, params_path, P::name, local);
    diag.merge(local);  // warnings (implausible values) too, when the parameters load
    if (local.has_errors()) return nullptr;
    try {
      return std::make_unique<StageOf<P>>(params, context);
    } catch (const ConfigError& e) {
      // Constructors report paths relative to their stage ("/params/x", "/inputs/y").
      for (const auto& p : e.problems()) diag.error(std::string(stage_path) + p.path, p.message);
      return nullptr;
    }
  };
  if constexpr (PluginHasExampleParams<P>) info.example_params = std::string(P::example_params);
  if constexpr (PluginHasCalibratedParams<P>) {
    info.calibrated_params.assign(P::calibrated_params.begin(), P::calibrated_params.end());
  }
  info.example_ports = [example = info.example_params](double sample_period_s,
                                                       Diagnostics& diag) -> std::optional<Ports> {
    const Json parsed = example.empty() ? Json::object() : Json::parse(example);
    const Json examples = parsed.is_array() ? parsed : Json::array({parsed});
    Ports all;  // the union over the examples, in order of first appearance
    for (std::size_t e = 0; e < examples.size(); ++e) {
      Diagnostics local;
      // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "/" + to_string(e).
      std::string path = "/";
      path += P::name;
      path += "/example_params";
      if (parsed.is_array()) {
        path += '/';
        path += std::to_string(e);
      }
      auto params = load_params<typename P::Params>(examples[e], path, P::name, local);
      diag.merge(local);
      if (local.has_errors()) return std::nullopt;
      std::optional<Ports> ports;
      if constexpr (PluginDeclaresPortsFromParams<P>) {
        ports = P::declare_ports(params);
      } else {
        try {
          const P plugin(params, StageContext(sample_period_s, std::string(P::name)));
          ports = plugin.ports();
        } catch (const ConfigError& error) {
          for (const auto& p : error.problems()) diag.error(path + p.path, p.message);
          return std::nullopt;
        }
      }
      for (const PortSpec& spec : ports->inputs()) {
        if (!all.find_input(spec.name)) all.add_input(spec);
      }
      for (const PortSpec& spec : ports->outputs()) {
        if (!all.find_output(spec.name)) all.add_output(spec);
      }
    }
    return all;
  };
  return info;
}

class PluginRegistry {
 public:
  void add(PluginInfo info);
  [[nodiscard]] const PluginInfo* find(std::string_view name) const noexcept;
  [[nodiscard]] std::vector<std::string> names() const;
  [[nodiscard]] const std::vector<PluginInfo>& plugins() const noexcept { return plugins_; }

 private:
  std::vector<PluginInfo> plugins_;
};

}  // namespace ftsense
