// The verbs as a library (include/ftsense/app/app.hpp): the dispatcher every program built on
// ftsense::app shares, `ftsense` itself included (main.cpp).

#include "ftsense/app/app.hpp"

#include <algorithm>
#include <exception>
#include <iostream>

#include "cli.hpp"
#include "ftsense/diagnostics.hpp"
#include "report.hpp"

namespace ftsense::app {

int run_command(const std::vector<std::string>& args, const Context& context) { return cli::run_command(args, context); }
int check_command(const std::vector<std::string>& args, const Context& context) {
  return cli::check_command(args, context);
}
int calibrate_command(const std::vector<std::string>& args, const Context& context) {
  return cli::calibrate_command(args, context);
}
int report_command(const std::vector<std::string>& args, const Context& context) {
  return cli::report_command(args, context);
}
int plugins_command(const std::vector<std::string>& args, const Context& context) {
  return cli::plugins_command(args, context);
}

bool has_inject() noexcept {
#ifdef FTSENSE_HAVE_SIM
  return true;
#else
  return false;
#endif
}

int inject_command(const std::vector<std::string>& args, const Context& context) {
#ifdef FTSENSE_HAVE_SIM
  return cli::inject_command(args, context);
#else
  (void)args;
  throw UsageError{context.command("inject") + ": this build of ftsense has no simulator, whose fault models "
                   "inject applies; build ftsense with FTSENSE_BUILD_SIM=ON (libmujoco-dev)"};
#endif
}

namespace {

// The built-in verbs, in the order `--help` lists them.
std::vector<Verb> built_in_verbs() {
  std::vector<Verb> verbs{
      {"run", "run a pipeline (JSON config) over a CSV log and write the monitored channels", run_command},
      {"check", "check a pipeline config and list every problem", check_command},
      {"calibrate", "thresholds from a fault-free log", calibrate_command},
      {"report", "metrics against the truth, figures and a Markdown report", report_command}};
  if (has_inject()) {
    verbs.push_back({"inject", "apply the simulator's fault models to columns of a recorded log", inject_command});
  }
  verbs.push_back({"plugins",
                   "list the plugins this program knows (--markdown: the config reference;\n"
                   "--fault-types: the fault type table)",
                   plugins_command});
  return verbs;
}

std::string help_text(const AppInfo& info, const std::vector<Verb>& verbs) {
  std::size_t width = 0;
  for (const Verb& v : verbs) width = std::max(width, v.name.size());
  std::string text = "usage: " + info.name + " <verb> [options]\n\n";
  if (!info.summary.empty()) text += info.summary + (info.summary.back() == '\n' ? "" : "\n");
  text += "\nVerbs:\n";
  for (const Verb& v : verbs) {
    std::string summary = v.summary;
    // Continuation lines of a summary line up under its first.
    for (std::size_t at = summary.find('\n'); at != std::string::npos; at = summary.find('\n', at + 1)) {
      summary.insert(at + 1, std::string(width + 4, ' '));
    }
    text += "  " + v.name + std::string(width + 2 - v.name.size(), ' ') + summary + '\n';
  }
  text += "\n'" + info.name + " <verb> --help' describes a verb; '" + info.name +
          " --version' prints the version. Exit\nstatus: 0 success, 2 usage or configuration error, 1 runtime failure.\n";
  return text;
}

}  // namespace

int main(const std::vector<std::string>& all, const PluginRegistry& registry, const AppInfo& info,
         const std::vector<Verb>& extra_verbs) {
  std::vector<Verb> verbs = built_in_verbs();
  for (const Verb& extra : extra_verbs) {
    const bool taken = std::any_of(verbs.begin(), verbs.end(), [&](const Verb& v) { return v.name == extra.name; });
    if (taken || !extra.run) {
      std::cerr << info.name << ": the verb '" << extra.name << "' is "
                << (taken ? "a built-in one; give the program's own verb another name" : "empty (no function)") << '\n';
      return kExitUsage;
    }
    verbs.push_back(extra);
  }
  if (all.empty() || all.front() == "--help" || all.front() == "-h" || all.front() == "help") {
    std::cout << help_text(info, verbs);
    return all.empty() ? kExitUsage : kExitOk;
  }
  if (all.front() == "--version" || all.front() == "-V") {
    std::cout << info.name << ' ' << info.version << '\n';
    return kExitOk;
  }
  const std::string& verb = all.front();
  const std::vector<std::string> args(all.begin() + 1, all.end());
  if (args.size() == 1 && (args.front() == "--version" || args.front() == "-V")) {  // "<name> run --version"
    std::cout << info.name << ' ' << info.version << '\n';
    return kExitOk;
  }
  const Context context{registry, info.name};
  try {
    for (const Verb& v : verbs) {
      if (v.name == verb) return v.run(args, context);
    }
    if (verb == "inject") return inject_command(args, context);  // not in this build: says why
    std::vector<std::string> names;
    for (const Verb& v : verbs) names.push_back(v.name);
    std::cerr << info.name << ": unknown verb '" << verb << "'; " << suggest(verb, names) << "\nsee '" << info.name
              << " --help'\n";
    return kExitUsage;
  } catch (const UsageError& e) {
    std::cerr << e.message << '\n';
    return kExitUsage;
  } catch (const ConfigError& e) {
    for (const auto& p : e.problems()) std::cerr << "error: " << p.text() << '\n';
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << context.command(verb) << ": " << e.what() << '\n';
    return kExitRuntime;
  }
}

int main(int argc, char** argv, const PluginRegistry& registry, const AppInfo& info,
         const std::vector<Verb>& extra_verbs) {
  return main(std::vector<std::string>(argv + 1, argv + argc), registry, info, extra_verbs);
}

}  // namespace ftsense::app
