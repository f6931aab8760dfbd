#include "cli.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ftsense/diagnostics.hpp"
#include "ftsense/text_file.hpp"

namespace ftsense::app {

std::vector<std::string> split_list(std::string_view list) {
  std::vector<std::string> items;
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    items.emplace_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

namespace {

// "--input (-i)": how messages name an option.
std::string flag_text(const OptionSpec& spec) {
  std::string text = "--" + spec.name;
  if (spec.short_name != 0) text += std::string(" (-") + spec.short_name + ")";
  return text;
}

std::string_view value_word(const OptionSpec& spec) {
  switch (spec.file) {
    case FileArg::input: return "FILE";
    case FileArg::input_list: return "FILES";
    case FileArg::output: return "PATH";
    case FileArg::output_folder: return "DIR";
    case FileArg::none: break;
  }
  return "VALUE";
}

}  // namespace

Options parse_options(std::string_view command, const std::vector<std::string>& args,
                      const std::vector<OptionSpec>& specs) {
  Options out;
  std::vector<std::string> problems;
  std::vector<std::string> known{"help"};
  for (const auto& s : specs) known.push_back(s.name);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      out["help"] = "1";
      return out;
    }
    const OptionSpec* spec = nullptr;
    std::string given;  // as typed, for the messages
    std::string value;
    bool has_inline_value = false;
    if (a.size() >= 2 && a[0] == '-' && a[1] != '-') {
      // A short flag: "-c FILE" (or "-c=FILE").
      given = a.substr(0, 2);
      if (a.size() > 2) {
        if (a[2] != '=') {
          problems.push_back("unexpected argument '" + a + "' (short flags are one letter: -c FILE)");
          continue;
        }
        value = a.substr(3);
        has_inline_value = true;
      }
      for (const auto& s : specs) {
        if (s.short_name != 0 && s.short_name == a[1]) spec = &s;
      }
      if (spec == nullptr) {
        std::string shorts;
        for (const auto& s : specs) {
          if (s.short_name != 0) shorts += (shorts.empty() ? "" : ", ") + std::string("-") + s.short_name + " (--" + s.name + ")";
        }
        problems.push_back("unknown option " + given + (shorts.empty() ? "; this verb has no short flags" : "; its short flags are " + shorts));
        continue;
      }
    } else if (a.rfind("--", 0) == 0) {
      std::string name = a.substr(2);
      if (const auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        has_inline_value = true;
      }
      given = "--" + name;
      for (const auto& s : specs) {
        if (s.name == name || std::find(s.aliases.begin(), s.aliases.end(), name) != s.aliases.end()) spec = &s;
      }
      if (spec == nullptr) {
        problems.push_back("unknown option --" + name + "; " + suggest(name, known));
        continue;
      }
    } else {
      problems.push_back("unexpected argument '" + a + "' (options start with --)");
      continue;
    }
    if (spec->takes_value && !has_inline_value) {
      if (i + 1 >= args.size()) {
        problems.push_back("option " + given + " needs a value");
        continue;
      }
      value = args[++i];
    }
    if (out.count(spec->name)) problems.push_back("option --" + spec->name + " is given twice");
    out[spec->name] = spec->takes_value ? value : "1";
  }
  for (const auto& s : specs) {
    if (s.required && !out.count(s.name)) problems.push_back("missing required option " + flag_text(s) + ": " + s.help);
  }
  if (!problems.empty()) {
    std::string message;
    for (const auto& p : problems) {
      if (!message.empty()) message += '\n';
      message.append(command).append(": ").append(p);
    }
    message += "\nsee '" + std::string(command) + " --help'";
    throw UsageError{message};
  }
  return out;
}

std::string usage_text(std::string_view command, std::string_view summary, const std::vector<OptionSpec>& specs) {
  std::ostringstream os;
  os << "usage: " << command;
  for (const auto& s : specs) {
    os << ' ' << (s.required ? "" : "[") << "--" << s.name;
    if (s.takes_value) os << ' ' << value_word(s);
    os << (s.required ? "" : "]");
  }
  os << "\n\n" << summary << "\n\noptions:\n";
  for (const auto& s : specs) {
    os << "  ";
    if (s.short_name != 0) os << '-' << s.short_name << ", ";
    os << "--" << s.name << "\n      " << s.help << '\n';
  }
  os << "  -h, --help\n      show this text\n";
  return os.str();
}

void require_existing_files(std::string_view command, const Options& options, const std::vector<OptionSpec>& specs,
                            const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    const auto given = options.find(name);
    if (given == options.end()) continue;
    for (const auto& spec : specs) {
      if (spec.name != name || (spec.file != FileArg::input && spec.file != FileArg::input_list)) continue;
      const std::vector<std::string> paths =
          spec.file == FileArg::input_list ? split_list(given->second) : std::vector<std::string>{given->second};
      for (const std::string& path : paths) {
        std::error_code ec;
        if (path.empty() || path == "-" || std::filesystem::exists(std::filesystem::symlink_status(path, ec))) continue;
        throw UsageError{"error: " + std::string(command) + ": " + flag_text(spec) + " " + path +
                         ": no such file; check the path (--" + spec.name + " wants: " + spec.help + ")"};
      }
    }
  }
}

}  // namespace ftsense::app

namespace ftsense::cli {

std::string read_text_file(const std::string& path, std::string_view what) {
  try {
    return ftsense::read_text_file(std::filesystem::path(path), what);
  } catch (const TextFileError& e) {
    throw UsageError{e.what()};
  }
}

}  // namespace ftsense::cli
