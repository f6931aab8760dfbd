#pragma once
// The verbs of the `ftsense` program as a library (target ftsense::app), for a program with its
// own plugin set: `my_program run ...` then behaves as `ftsense run ...` (same options, outputs and
// exit codes) with the program's plugins, and the program may add verbs of its own.
//
//   int main(int argc, char** argv) {
//     return ftsense::app::main(argc, argv, my_plugins::registry(), {"my_program", "1.0", "..."});
//   }
//
// The verbs: run, check, calibrate, report, plugins, and inject when ftsense was built with its
// simulator (has_inject()). Messages and usage lines name the program (AppInfo::name).

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/app/options.hpp"
#include "ftsense/plugin_registry.hpp"

namespace ftsense::app {

struct AppInfo {
  std::string name = "ftsense";  // in usage lines and messages: "<name> run: ..."
  std::string version;           // printed by --version / -V
  std::string summary;           // the lines after the usage line of `<name> --help`
};

// What a verb runs with: the program's plugins (every config is built with them) and its name.
struct Context {
  const PluginRegistry& registry;
  std::string program = "ftsense";

  // "<program> <verb>", as messages and usage lines name a verb.
  [[nodiscard]] std::string command(std::string_view verb) const { return program + " " + std::string(verb); }
};

// A verb of the program's own, dispatched like the built-in ones (its exceptions too: UsageError
// and ConfigError exit 2, any other std::exception exits 1).
struct Verb {
  std::string name;
  std::string summary;  // one line in `<name> --help`
  std::function<int(const std::vector<std::string>& args, const Context& context)> run;
};

// The built-in verbs; `args` are the arguments after the verb. Each returns the exit code and
// throws UsageError (exit 2), ConfigError (exit 2) or std::exception (exit 1), as main() reports them.
int run_command(const std::vector<std::string>& args, const Context& context);
int check_command(const std::vector<std::string>& args, const Context& context);
int calibrate_command(const std::vector<std::string>& args, const Context& context);
int report_command(const std::vector<std::string>& args, const Context& context);
int plugins_command(const std::vector<std::string>& args, const Context& context);
// Only when has_inject(); otherwise it throws UsageError saying so.
int inject_command(const std::vector<std::string>& args, const Context& context);
[[nodiscard]] bool has_inject() noexcept;

// The whole program: "<name> <verb> [options]", "--help", "--version"; the built-in verbs and
// `extra_verbs` (which may not reuse a built-in name). Prints errors and returns the exit code.
int main(int argc, char** argv, const PluginRegistry& registry, const AppInfo& info,
         const std::vector<Verb>& extra_verbs = {});
int main(const std::vector<std::string>& args, const PluginRegistry& registry, const AppInfo& info,
         const std::vector<Verb>& extra_verbs = {});

}  // namespace ftsense::app
