#pragma once
// The run-time catalogue of plugins a pipeline can be built from (made from a PluginSet).

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense {

struct PluginInfo {
  std::string name;
  std::string summary;
  std::vector<ParamInfo> params;
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
