#pragma once
// docs/config_reference.md, generated from the parameter descriptions of a plugin registry, so the
// reference cannot drift from the code (a test compares the committed file with this output).

#include <string>

#include "ftsense/plugin_registry.hpp"

namespace ftsense {

[[nodiscard]] std::string config_reference_markdown(const PluginRegistry& plugins);

// The "### `name`" section of one plugin: summary and parameter table.
[[nodiscard]] std::string plugin_reference_markdown(const PluginInfo& plugin);

}  // namespace ftsense
