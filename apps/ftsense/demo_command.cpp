#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli.hpp"
#include "report.hpp"

#ifndef FTSENSE_SOURCE_DIR
#define FTSENSE_SOURCE_DIR "."
#endif

namespace ftsense::cli {

namespace {

// A copy of a scenario with another duration (for --quick), written into the demo folder.
std::string scenario_copy(const std::string& source, const std::string& target, double duration_s) {
  Json s = parse_json_text(read_text_file(source, "scenario"), source);
  if (duration_s > 0.0) s["duration_s"] = duration_s;
  std::ofstream(target) << s.dump(2) << '\n';
  return target;
}

void step_line(int index, int total, const std::string& what) {
  std::cout << "\n[" << index << "/" << total << "] " << what << std::endl;
}

}  // namespace

int demo_command(const std::vector<std::string>& args) {
  const std::vector<OptionSpec> specs{
      {"out", true, false, "output folder (default out/demo)"},
      {"configs", true, false, "the configs folder (default: the source tree's configs/)"},
      {"quick", false, false, "short walks (9 s) for a smoke test; the numbers are not the published ones"}};
  const auto options = parse_options("demo", args, specs);
  if (options.count("help")) {
    std::cout << usage_text("demo",
                            "The paper's experiment end to end: simulate a fault-free walk and the paper's\n"
                            "fault scenario (MuJoCo), calibrate the thresholds on the fault-free walk, run\n"
                            "the reference pipeline (configs/suralp.json) and the paper's literal measured-ZMP\n"
                            "variant on the faulty walk, and write logs, metrics, figures and a report.",
                            specs);
    return kExitOk;
  }
  const std::string out = options.count("out") ? options.at("out") : "out/demo";
  const std::string configs = options.count("configs") ? options.at("configs") : FTSENSE_SOURCE_DIR "/configs";
  const bool quick = options.count("quick") > 0;
  std::filesystem::create_directories(out);
  const double duration = quick ? 9.0 : 0.0;  // 0: the scenario's own
  const int total = 6;

  step_line(1, total, "simulating the fault-free walk (MuJoCo)");
  const std::string clean = scenario_copy(configs + "/scenarios/clean.json", out + "/clean_scenario.json", duration);
  if (int rc = simulate_command({"--scenario", clean, "--out", out + "/clean.csv"}); rc != kExitOk) return rc;

  step_line(2, total, "simulating the paper's fault scenario");
  const std::string paper = scenario_copy(configs + "/scenarios/paper.json", out + "/paper_scenario.json", duration);
  if (int rc = simulate_command({"--scenario", paper, "--out", out + "/paper.csv"}); rc != kExitOk) return rc;

  struct Variant {
    std::string name, config, title;
  };
  const Variant variants[] = {
      {"reference", configs + "/suralp.json", "Reference pipeline (configs/suralp.json, planned ZMP)"},
      {"measured_zmp", configs + "/suralp_measured_zmp.json",
       "Paper's literal choice (configs/suralp_measured_zmp.json, measured ZMP into the CoM estimator)"}};
  Json metrics = {{"quick", quick}, {"variants", Json::object()}};
  std::string tables;
  int index = 3;
  for (const auto& v : variants) {
    step_line(index++, total, "calibrating and running: " + v.title);
    const std::string thresholds = out + "/thresholds_" + v.name + ".json";
    if (int rc = calibrate_command({"--config", v.config, "--input", out + "/clean.csv", "--output", thresholds}); rc) return rc;
    for (const std::string log : {"clean", "paper"}) {
      const std::string run_out = out + "/" + log + "_run_" + v.name + ".csv";
      if (int rc = run_command({"--config", v.config, "--thresholds", thresholds, "--input", out + "/" + log + ".csv",
                                "--output", run_out});
          rc != kExitOk) {
        return rc;
      }
      ReportOptions ro;
      ro.title = v.title + ", " + log + " walk";
      ro.figures = v.name == "reference" && log == "paper";
      const std::string report_dir = out + "/" + v.name + "_" + log;
      const Report r = make_report(run_out, out + "/" + log + ".csv", report_dir, ro);
      metrics["variants"][v.name][log] = r.json;
      tables += "\n" + ro.title + ":\n" + r.table;
    }
  }
  step_line(total, total, "writing the metrics and the report");
  std::ofstream(out + "/metrics.json") << metrics.dump(2) << '\n';
  std::ofstream md(out + "/report.md");
  md << "# ftsense demo: the paper's experiment\n\n"
     << (quick ? "**Quick run (9 s walks): a smoke test, not the published numbers.**\n\n" : "")
     << "- Reference pipeline on the paper's faults: [reference_paper/report.md](reference_paper/report.md) "
        "(with the four figures)\n"
     << "- Reference pipeline on the fault-free walk: [reference_clean/report.md](reference_clean/report.md)\n"
     << "- Measured-ZMP variant: [measured_zmp_paper/report.md](measured_zmp_paper/report.md), "
        "[measured_zmp_clean/report.md](measured_zmp_clean/report.md)\n\n"
     << "![Fig. 4](reference_paper/fig4_virtual_vs_true.png)\n\n![Fig. 5](reference_paper/fig5_fault_estimate.png)\n\n"
     << "![Fig. 6](reference_paper/fig6_recovered.png)\n\n![Fig. 7](reference_paper/fig7_detection_flags.png)\n\n"
     << "```\n" << tables << "```\n";
  std::cout << tables << "\nftsense demo: wrote " << out << "/report.md, " << out << "/metrics.json and the figures in "
            << out << "/reference_paper/\n";
  return kExitOk;
}

}  // namespace ftsense::cli
