#include <algorithm>
#include <iostream>

#include "cli.hpp"
#include "ftsense/config_reference.hpp"
#include "ftsense/config_schema.hpp"
#include "ftsense/fault_type.hpp"

namespace ftsense::cli {

int plugins_command(const std::vector<std::string>& args, const Context& context) {
  const std::string command = context.command("plugins");
  const std::vector<OptionSpec> specs{
      {"markdown", false, false, "print the full configuration reference (docs/config_reference.md)"},
      {"only", true, false, "with --markdown: only these plugins' sections (comma-separated names)"},
      {"schema", false, false, "print the JSON Schema of the pipeline config (docs/ftsense-config.schema.json)"},
      {"fault-types", false, false, "print the fault type table: code, name, model (docs/architecture.md)"}};
  const auto options = parse_options(command, args, specs);
  if (options.count("help")) {
    std::cout << usage_text(command, "Lists the plugins compiled into this program.", specs);
    return kExitOk;
  }
  if (options.count("fault-types")) {
    std::cout << fault_type_table_markdown();
    return kExitOk;
  }
  const PluginRegistry& registry = context.registry;
  if (options.count("markdown") && options.count("only")) {
    bool first = true;
    for (const std::string& name : split_list(options.at("only"))) {
      const PluginInfo* info = registry.find(name);
      if (info == nullptr) throw UsageError{command + ": unknown plugin '" + name + "'; " + suggest(name, registry.names())};
      std::cout << (first ? "" : "\n") << plugin_reference_markdown(*info);
      first = false;
    }
    return kExitOk;
  }
  if (options.count("schema")) {
    std::cout << config_json_schema(registry).dump(2) << '\n';
    return kExitOk;
  }
  if (options.count("markdown")) {
    std::cout << config_reference_markdown(registry);
    return kExitOk;
  }
  for (const auto& p : registry.plugins()) std::cout << p.name << "\n    " << p.summary << '\n';
  return kExitOk;
}

}  // namespace ftsense::cli
