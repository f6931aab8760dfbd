#include <algorithm>
#include <filesystem>
#include <iostream>

#include "cli.hpp"
#include "log_runner.hpp"

namespace ftsense::cli {

int check_command(const std::vector<std::string>& args, const Context& context) {
  const std::string command = context.command("check");
  const std::vector<OptionSpec> specs{{"config", true, true, "pipeline config (JSON) to check", 'c', {}, FileArg::input}};
  const auto options = parse_options(command, args, specs);
  if (options.count("help")) {
    std::cout << usage_text(command,
                            "Builds the pipeline of --config without running it and lists every\n"
                            "problem (exit 2) or says ok (exit 0).",
                            specs);
    return kExitOk;
  }
  const std::string& path = options.at("config");
  require_existing_files(command, options, specs, {"config"});
  const Pipeline pipeline = load_pipeline(context, path);
  std::cout << "ok: " << path << ": " << pipeline.inputs().size() << " inputs, " << pipeline.stage_count()
            << " stages";
  if (pipeline.has_monitor()) std::cout << ", " << pipeline.monitor().channels.size() << " monitored channels";
  std::cout << '\n';
  return kExitOk;
}

Pipeline load_pipeline(const Context& context, const std::string& config_path, const std::string& thresholds_path) {
  std::vector<std::string> from_thresholds;  // config pointers whose values the thresholds file set
  try {
    Json config = parse_json_text(read_text_file(config_path, "config file"), config_path);
    if (!thresholds_path.empty()) {
      from_thresholds = apply_thresholds(
          config, parse_json_text(read_text_file(thresholds_path, "thresholds file"), thresholds_path), thresholds_path);
    }
    Pipeline pipeline = Pipeline::build(config, context.registry,
                                        std::filesystem::path(config_path).parent_path());
    for (const auto& w : pipeline.warnings()) std::cerr << "warning: " << config_path << ":" << w.text() << '\n';
    return pipeline;
  } catch (const ConfigError& e) {
    std::vector<Diagnostic> problems = e.problems();
    for (auto& p : problems) {
      if (p.path.find(':') != std::string::npos) continue;
      const bool calibrated = std::any_of(from_thresholds.begin(), from_thresholds.end(), [&](const std::string& f) {
        return p.path == f || p.path.rfind(f + "/", 0) == 0;
      });
      // A value from the thresholds file is reported there: the config does not hold it.
      if (calibrated) p.message += " (the value comes from " + thresholds_path + "; calibrate again or fix it there)";
      p.path = config_path + ":" + p.path;
    }
    throw ConfigError(std::move(problems));
  }
}

}  // namespace ftsense::cli
