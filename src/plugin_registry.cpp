#include "ftsense/plugin_registry.hpp"

namespace ftsense {

void PluginRegistry::add(PluginInfo info) {
  FTSENSE_DEMAND(find(info.name) == nullptr, "plugin registered twice: " + info.name);
  plugins_.push_back(std::move(info));
}

const PluginInfo* PluginRegistry::find(std::string_view name) const noexcept {
  for (const auto& p : plugins_) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

std::vector<std::string> PluginRegistry::names() const {
  std::vector<std::string> out;
  out.reserve(plugins_.size());
  for (const auto& p : plugins_) out.push_back(p.name);
  return out;
}

}  // namespace ftsense
