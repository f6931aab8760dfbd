#include <charconv>
#include <cstdio>
#include <iostream>
#include <optional>

#include <unistd.h>

#include "cli.hpp"
#include "ftsense/io/output_file.hpp"
#include "ftsense/sim/simulator.hpp"

namespace ftsense::cli {

int simulate_command(const std::vector<std::string>& args) {
  const std::vector<OptionSpec> specs{
      {"scenario", true, true, "scenario (JSON): gait, sensor noise, injected faults; see sim/README.md", 0, {},
       FileArg::input},
      {"output", true, true, "where to write the log (CSV)", 'o', {"out"}, FileArg::output},
      {"seed", true, false, "seed of the sensor noise and faults (default: the scenario's \"seed\")"},
      {"quiet", false, false, "no progress line on stderr"}};
  const auto options = parse_options("ftsense simulate", args, specs);
  if (options.count("help")) {
    std::cout << usage_text("ftsense simulate",
                            "Simulates the scenario's robot (MuJoCo: the SURALP-like biped walking, or with\n"
                            "\"robot\": \"quadruped\" the 13 kg quadruped crawling), with sensor models and\n"
                            "injected faults, and writes the measured signals and the ground truth\n"
                            "(truth/... columns) as a CSV log. Exit 1 if the robot falls.",
                            specs);
    return kExitOk;
  }
  require_existing_files("ftsense simulate", options, specs, {"scenario"});
  sim::Scenario scenario;
  try {
    scenario = sim::load_scenario(options.at("scenario"));
  } catch (const sim::ScenarioError& e) {
    std::string message;
    for (const auto& p : e.problems()) message += (message.empty() ? "" : "\n") + ("error: " + p);
    throw UsageError{message};
  }
  std::uint64_t seed = scenario.seed;
  if (const auto s = options.find("seed"); s != options.end()) {
    const auto [end, ec] = std::from_chars(s->second.data(), s->second.data() + s->second.size(), seed);
    if (ec != std::errc() || end != s->second.data() + s->second.size()) {
      throw UsageError{"ftsense simulate: --seed = '" + s->second + "' is not a non-negative integer"};
    }
  }
  std::optional<io::OutputFile> out_file;
  try {
    out_file.emplace(options.at("output"), std::vector<std::string>{options.at("scenario")}, "log");
  } catch (const io::OutputError& e) {
    throw UsageError{std::string("error: ") + e.what()};
  }
  std::ostream& out = out_file->stream();
  sim::SimulationOptions sim_options;
  // Progress overwrites one line with carriage returns: only on a terminal, never into a log file.
  const bool show_progress = !options.count("quiet") && isatty(fileno(stderr)) == 1;
  if (show_progress) {
    sim_options.progress = [](double t, double duration) {
      std::fprintf(stderr, "\rftsense simulate: %5.1f / %.1f s", t, duration);
      std::fflush(stderr);
    };
  }
  const sim::SimulationSummary summary = sim::simulate(scenario, seed, out, sim_options);
  if (show_progress) std::fprintf(stderr, "\n");
  try {
    out_file->commit();
  } catch (const io::OutputError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitRuntime;
  }
  std::cout << "ftsense simulate: " << summary.message << " (seed " << seed << ", " << summary.ticks
            << " rows, " << summary.cpu_s << " s CPU) -> " << options.at("output") << '\n';
  return summary.fell ? kExitRuntime : kExitOk;
}

}  // namespace ftsense::cli
