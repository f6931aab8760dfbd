#pragma once
// The command-line conventions of the ftsense verbs, for a program's own verbs too (app.hpp).
//
// One spelling per option, across verbs: "--name VALUE" or "--name=VALUE"; the common options
// also have a short flag ("-c FILE" config, "-i FILE" input, "-o PATH" output, "-t FILE" truth);
// an old spelling stays accepted as a hidden alias (--out for --output). "--help" / "-h" asks for
// the verb's usage.
//
// Exit codes (design.md): 0 success, 2 usage or configuration error, 1 runtime failure. Errors go
// to stderr, one line per problem, never a stack dump.

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace ftsense::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;

// Thrown for a usage problem; the program prints it and exits 2.
struct UsageError {
  std::string message;
};

// What a file option names; the usage text shows it (FILE, FILES, PATH, DIR) and
// require_existing_files() checks the input kinds.
enum class FileArg {
  none,          // not a file: VALUE
  input,         // a file that must exist ("-" is standard input where the verb says so)
  input_list,    // comma-separated files that must exist
  output,        // a file to write
  output_folder  // a folder to write into
};

struct OptionSpec {
  std::string name;  // without the leading "--"
  bool takes_value = true;
  bool required = false;
  std::string help;
  char short_name = 0;               // e.g. 'c' for -c; 0: none
  std::vector<std::string> aliases = {};  // hidden old spellings, without "--"; still accepted
  FileArg file = FileArg::none;
};

// Option name (the spec's name, whichever spelling was given) -> value ("1" for a flag);
// "help" when --help or -h was given.
using Options = std::map<std::string, std::string>;

// Parses `args` against `specs`. `command` is what the messages name, e.g. "ftsense run".
// Throws UsageError naming every unknown, repeated or missing option.
Options parse_options(std::string_view command, const std::vector<std::string>& args,
                      const std::vector<OptionSpec>& specs);

std::string usage_text(std::string_view command, std::string_view summary, const std::vector<OptionSpec>& specs);

// Throws UsageError when a file option (FileArg::input or input_list) among `names` names a path
// that does not exist; the message says which option, which path, and what the option wants.
// Options not given are skipped; "-" (standard input) is not checked. Verbs call it when they are
// about to read the files, so that a config's own problems are listed first.
void require_existing_files(std::string_view command, const Options& options, const std::vector<OptionSpec>& specs,
                            const std::vector<std::string>& names);

// The comma-separated items of an option's value, in order; empty items are kept (the caller
// says what an empty one means).
std::vector<std::string> split_list(std::string_view list);

}  // namespace ftsense::app
