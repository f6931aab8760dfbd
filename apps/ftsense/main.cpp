// ftsense: fault-tolerant sensing from the command line. See `ftsense --help`.

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "report.hpp"
#include "ftsense/diagnostics.hpp"

namespace {

constexpr const char* kHelp =
    "usage: ftsense <verb> [options]\n"
    "\n"
    "Checks sensors against virtual sensors, detects and classifies faults, estimates them and\n"
    "recovers the signals. Verbs:\n"
#ifdef FTSENSE_HAVE_SIM
    "  simulate  simulate the SURALP biped walking a scenario (MuJoCo), with faults\n"
    "  demo      the paper's experiment end to end (what make demo runs)\n"
    "  inject    apply the simulator's fault models to columns of a recorded log\n"
#endif
    "  run       run a pipeline (JSON config) over a CSV log and write the monitored channels\n"
    "  check     check a pipeline config and list every problem\n"
    "  calibrate thresholds from a fault-free log\n"
    "  report    metrics against the truth, figures and a Markdown report\n"
    "  plugins   list the plugins this program knows (--markdown: the config reference;\n"
    "            --fault-types: the fault type table)\n"
    "\n"
    "'ftsense <verb> --help' describes a verb; 'ftsense --version' prints the version. Exit\n"
    "status: 0 success, 2 usage or configuration error, 1 runtime failure.\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace ftsense::cli;
  const std::vector<std::string> all(argv + 1, argv + argc);
  if (all.empty() || all.front() == "--help" || all.front() == "-h" || all.front() == "help") {
    std::cout << kHelp;
    return all.empty() ? kExitUsage : kExitOk;
  }
  if (all.front() == "--version" || all.front() == "-V") {
    std::cout << "ftsense " << FTSENSE_VERSION << '\n';
    return kExitOk;
  }
  const std::string verb = all.front();
  const std::vector<std::string> args(all.begin() + 1, all.end());
  try {
    if (verb == "run") return run_command(args);
    if (verb == "check") return check_command(args);
    if (verb == "calibrate") return calibrate_command(args);
    if (verb == "report") return report_command(args);
#ifdef FTSENSE_HAVE_SIM
    if (verb == "simulate") return simulate_command(args);
    if (verb == "demo") return demo_command(args);
    if (verb == "inject") return inject_command(args);
#endif
    if (verb == "plugins") return plugins_command(args);
    std::cerr << "ftsense: unknown verb '" << verb << "'; "
              << ftsense::suggest(verb, {"run", "check", "calibrate", "report", "simulate", "demo", "inject", "plugins"}) << "\nsee 'ftsense --help'\n";
    return kExitUsage;
  } catch (const UsageError& e) {
    std::cerr << e.message << '\n';
    return kExitUsage;
  } catch (const ftsense::ConfigError& e) {
    for (const auto& p : e.problems()) std::cerr << "error: " << p.text() << '\n';
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "ftsense " << verb << ": " << e.what() << '\n';
    return kExitRuntime;
  }
}
