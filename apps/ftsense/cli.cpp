#include "cli.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "ftsense/diagnostics.hpp"
#include "ftsense/text_file.hpp"

namespace ftsense::cli {

std::vector<std::string> split_list(std::string_view list) {
  std::vector<std::string> items;
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    items.emplace_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

std::map<std::string, std::string> parse_options(std::string_view verb, const std::vector<std::string>& args,
                                                 const std::vector<OptionSpec>& specs) {
  std::map<std::string, std::string> out;
  std::vector<std::string> problems;
  std::vector<std::string> known{"help"};
  for (const auto& s : specs) known.push_back(s.name);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      out["help"] = "1";
      return out;
    }
    if (a.rfind("--", 0) != 0) {
      problems.push_back("unexpected argument '" + a + "' (options start with --)");
      continue;
    }
    std::string name = a.substr(2);
    std::string value;
    bool has_inline_value = false;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_inline_value = true;
    }
    const OptionSpec* spec = nullptr;
    for (const auto& s : specs) {
      if (s.name == name) spec = &s;
    }
    if (spec == nullptr) {
      problems.push_back("unknown option --" + name + "; " + suggest(name, known));
      continue;
    }
    if (spec->takes_value && !has_inline_value) {
      if (i + 1 >= args.size()) {
        problems.push_back("option --" + name + " needs a value");
        continue;
      }
      value = args[++i];
    }
    if (out.count(name)) problems.push_back("option --" + name + " is given twice");
    out[name] = spec->takes_value ? value : "1";
  }
  for (const auto& s : specs) {
    if (s.required && !out.count(s.name)) problems.push_back("missing required option --" + s.name + " (" + s.help + ")");
  }
  if (!problems.empty()) {
    std::string message;
    for (const auto& p : problems) message += (message.empty() ? "" : "\n") + std::string("ftsense ") + std::string(verb) + ": " + p;
    message += "\nsee 'ftsense " + std::string(verb) + " --help'";
    throw UsageError{message};
  }
  return out;
}

std::string usage_text(std::string_view verb, std::string_view summary,
                       const std::vector<OptionSpec>& specs) {
  std::ostringstream os;
  os << "usage: ftsense " << verb;
  for (const auto& s : specs) {
    os << ' ' << (s.required ? "" : "[") << "--" << s.name << (s.takes_value ? " VALUE" : "")
       << (s.required ? "" : "]");
  }
  os << "\n\n" << summary << "\n\noptions:\n";
  for (const auto& s : specs) os << "  --" << s.name << "\n      " << s.help << '\n';
  os << "  --help\n      show this text\n";
  return os.str();
}

std::string read_text_file(const std::string& path, std::string_view what) {
  try {
    return ftsense::read_text_file(std::filesystem::path(path), what);
  } catch (const TextFileError& e) {
    throw UsageError{e.what()};
  }
}

}  // namespace ftsense::cli
