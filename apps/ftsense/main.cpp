// ftsense: fault-tolerant sensing from the command line. See `ftsense --help`.
//
// The verbs are the ftsense::app library with the reference plugins; the SURALP simulator and the
// paper's demo are this program's own verbs.

#include <string>
#include <vector>

#include "cli.hpp"
#include "ftsense/app/app.hpp"
#include "ftsense/reference_plugins.hpp"

int main(int argc, char** argv) {
  std::vector<ftsense::app::Verb> own_verbs;
#ifdef FTSENSE_HAVE_SIM
  own_verbs.push_back({"simulate", "simulate the SURALP biped walking a scenario (MuJoCo), with faults",
                       [](const std::vector<std::string>& args, const ftsense::app::Context&) {
                         return ftsense::cli::simulate_command(args);
                       }});
  own_verbs.push_back({"demo", "the paper's experiment end to end (what make demo runs)", ftsense::cli::demo_command});
#endif
  const ftsense::PluginRegistry registry = ftsense::reference_plugins::registry();
  return ftsense::app::main(argc, argv, registry,
                            {"ftsense", FTSENSE_VERSION,
                             "Checks sensors against virtual sensors, detects and classifies faults, estimates them and\n"
                             "recovers the signals."},
                            own_verbs);
}
