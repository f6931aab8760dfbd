#pragma once
// Small command-line helpers shared by the verbs of the `ftsense` program.
//
// Exit codes (design.md): 0 success, 2 usage or configuration error, 1 runtime failure. Errors
// go to stderr, one line per problem, never a stack dump.

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/pipeline.hpp"

namespace ftsense::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;

// Thrown for a usage problem; main() prints it and exits 2.
struct UsageError {
  std::string message;
};

struct OptionSpec {
  std::string name;  // without the leading "--"
  bool takes_value = true;
  bool required = false;
  std::string help;
};

// Parses "--name value" and "--flag" arguments against `specs`; "--help" sets "help".
// Throws UsageError naming every unknown, repeated or missing option.
std::map<std::string, std::string> parse_options(std::string_view verb, const std::vector<std::string>& args,
                                                 const std::vector<OptionSpec>& specs);

std::string usage_text(std::string_view verb, std::string_view summary,
                       const std::vector<OptionSpec>& specs);

// The comma-separated items of an option's value, in order; empty items are kept (the caller
// says what an empty one means).
std::vector<std::string> split_list(std::string_view list);

// Reads a whole text file; throws UsageError when it cannot.
std::string read_text_file(const std::string& path, std::string_view what);

// Reads, parses and builds a pipeline config with the reference plugins; problems come back as
// one ConfigError whose paths start with the file name. Warnings go to stderr.
// With a thresholds file, its thresholds are applied to the config first.
Pipeline load_pipeline(const std::string& config_path, const std::string& thresholds_path = {});

int run_command(const std::vector<std::string>& args);
int check_command(const std::vector<std::string>& args);
int calibrate_command(const std::vector<std::string>& args);
int simulate_command(const std::vector<std::string>& args);
int inject_command(const std::vector<std::string>& args);
int demo_command(const std::vector<std::string>& args);
int plugins_command(const std::vector<std::string>& args);

}  // namespace ftsense::cli
