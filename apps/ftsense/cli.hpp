#pragma once
// Helpers shared by the verbs of the `ftsense` program (the ftsense::app library). The option
// conventions and exit codes are public (include/ftsense/app/options.hpp).

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/app/app.hpp"
#include "ftsense/app/options.hpp"
#include "ftsense/pipeline.hpp"

namespace ftsense::cli {

using app::Context;
using app::FileArg;
using app::kExitOk;
using app::kExitRuntime;
using app::kExitUsage;
using app::OptionSpec;
using app::parse_options;
using app::require_existing_files;
using app::split_list;
using app::usage_text;
using app::UsageError;

// Reads a whole text file; throws UsageError when it cannot.
std::string read_text_file(const std::string& path, std::string_view what);

// Reads, parses and builds a pipeline config with the program's plugins; problems come back as
// one ConfigError whose paths start with the file name. Warnings go to stderr.
// With a thresholds file, its thresholds are applied to the config first.
Pipeline load_pipeline(const Context& context, const std::string& config_path, const std::string& thresholds_path = {});

int run_command(const std::vector<std::string>& args, const Context& context);
int check_command(const std::vector<std::string>& args, const Context& context);
int calibrate_command(const std::vector<std::string>& args, const Context& context);
int inject_command(const std::vector<std::string>& args, const Context& context);
int plugins_command(const std::vector<std::string>& args, const Context& context);
// The ftsense program's own verbs (main.cpp): the SURALP simulator and the paper's demo.
int simulate_command(const std::vector<std::string>& args);
int demo_command(const std::vector<std::string>& args, const Context& context);

}  // namespace ftsense::cli
