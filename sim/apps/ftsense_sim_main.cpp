// ftsense-sim --scenario S.json --out LOG.csv [--seed N] [--quiet]
// ftsense-sim --write-urdf PATH --robot quadruped
// Exit status: 0 ok, 2 usage or scenario error, 1 runtime failure (e.g. the robot fell).
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "ftsense/sim/mujoco_model.hpp"
#include "ftsense/sim/quadruped_urdf.hpp"
#include "ftsense/sim/simulator.hpp"

namespace {

constexpr const char* kUsage =
    "usage: ftsense-sim --scenario S.json --out LOG.csv [--seed N] [--quiet]\n"
    "       ftsense-sim --write-urdf PATH --robot quadruped\n"
    "  Simulates the scenario's robot (\"robot\": the SURALP-like biped by default, or the\n"
    "  quadruped) walking and writes the CSV log; or writes the quadruped's URDF.\n"
    "  --seed N   seed for the sensor noise and faults (default: the scenario's \"seed\")\n"
    "  --quiet    no progress output on stderr\n"
    "exit status: 0 ok, 2 usage or scenario error, 1 runtime failure (e.g. the robot fell)\n";

int usage_error(const std::string& msg) {
  std::cerr << "ftsense-sim: " << msg << "\n" << "try 'ftsense-sim --help'\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenario_path, out_path, urdf_path, robot;
  std::optional<std::uint64_t> seed;
  bool quiet = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    auto value = [&]() -> std::optional<std::string> {
      if (i + 1 >= argc) return std::nullopt;
      return std::string(argv[++i]);
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (a == "--scenario") {
      auto v = value();
      if (!v) return usage_error("--scenario needs a file name");
      scenario_path = *v;
    } else if (a == "--out") {
      auto v = value();
      if (!v) return usage_error("--out needs a file name");
      out_path = *v;
    } else if (a == "--seed") {
      auto v = value();
      if (!v) return usage_error("--seed needs a non-negative integer");
      std::uint64_t s = 0;
      const auto res = std::from_chars(v->data(), v->data() + v->size(), s);
      if (res.ec != std::errc() || res.ptr != v->data() + v->size())
        return usage_error("--seed = \"" + *v + "\" is not a non-negative integer");
      seed = s;
    } else if (a == "--write-urdf") {
      auto v = value();
      if (!v) return usage_error("--write-urdf needs a file name");
      urdf_path = *v;
    } else if (a == "--robot") {
      auto v = value();
      if (!v) return usage_error("--robot needs a robot name");
      robot = *v;
    } else if (a == "--quiet") {
      quiet = true;
    } else {
      return usage_error("unknown argument \"" + std::string(a) + "\"");
    }
  }
  if (!urdf_path.empty()) {
    if (!scenario_path.empty() || !out_path.empty())
      return usage_error("--write-urdf does not simulate: give it without --scenario and --out");
    if (robot != "quadruped")
      return usage_error("--write-urdf needs --robot quadruped (the only robot with a generated URDF)");
    std::ofstream urdf(urdf_path, std::ios::binary);
    urdf << ftsense::sim::quadruped_urdf();
    urdf.close();
    if (!urdf) {
      std::cerr << "ftsense-sim: cannot write " << urdf_path << "\n";
      return 1;
    }
    return 0;
  }
  if (!robot.empty()) return usage_error("--robot goes with --write-urdf (a scenario names its robot)");
  if (scenario_path.empty()) return usage_error("--scenario is required");
  if (out_path.empty()) return usage_error("--out is required");

  ftsense::sim::Scenario sc;
  try {
    sc = ftsense::sim::load_scenario(scenario_path);
  } catch (const ftsense::sim::ScenarioError& e) {
    for (const auto& p : e.problems()) std::cerr << "ftsense-sim: " << p << "\n";
    return 2;
  }
  std::ofstream out(out_path, std::ios::binary);
  if (!out) {
    std::cerr << "ftsense-sim: cannot write " << out_path << "\n";
    return 1;
  }
  ftsense::sim::SimulationOptions opt;
  if (!quiet)
    opt.progress = [](double t, double T) {
      std::fprintf(stderr, "\rftsense-sim: t = %5.1f / %.1f s", t, T);
      std::fflush(stderr);
    };
  try {
    const auto sum = ftsense::sim::simulate(sc, seed.value_or(sc.seed), out, opt);
    if (!quiet) std::fprintf(stderr, "\n");
    out.close();
    if (!out) {
      std::cerr << "ftsense-sim: error writing " << out_path << "\n";
      return 1;
    }
    if (sum.fell) {
      std::cerr << "ftsense-sim: " << sum.message << "; log up to the fall written to " << out_path << "\n";
      return 1;
    }
    if (!quiet && sc.robot_kind == ftsense::sim::RobotKind::quadruped) {
      std::fprintf(stderr, "ftsense-sim: %s; %lld rows, CPU %.2f s, stance force/mg %.4f, CoM error rms %.4f m, "
                   "planned stability margin %.4f m, lift-offs/touchdowns",
                   sum.message.c_str(), static_cast<long long>(sum.ticks), sum.cpu_s, sum.quiet_stance_force_ratio,
                   sum.com_error_rms_m, sum.planned_stability_margin_m);
      for (std::size_t f = 0; f < sum.foot_names.size(); ++f)
        std::fprintf(stderr, " %s %d/%d", sum.foot_names[f].c_str(), sum.liftoffs[f], sum.touchdowns[f]);
      std::fprintf(stderr, "\n");
    } else if (!quiet)
      std::fprintf(stderr,
                   "ftsense-sim: %s; %lld rows, CPU %.2f s, stance force/mg %.4f, ZMP error rms %.4f m "
                   "max %.4f m, CoM error rms %.4f m max %.4f m\n",
                   sum.message.c_str(), static_cast<long long>(sum.ticks), sum.cpu_s,
                   sum.quiet_stance_force_ratio, sum.zmp_error_rms_m, sum.zmp_error_max_m,
                   sum.com_error_rms_m, sum.com_error_max_m);
  } catch (const std::exception& e) {
    std::cerr << "ftsense-sim: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
