#include "ftsense/config_definitions.hpp"

#include <string>
#include <vector>

namespace ftsense {
namespace {

constexpr std::string_view kPrefix = "#/definitions/";
constexpr int kMaxDepth = 32;  // definitions using definitions: deeper than this is a cycle

class Resolver {
 public:
  Resolver(const Json* definitions, Diagnostics& diag) : definitions_(definitions), diag_(diag) {}

  // Replaces the references in `value` (at `path`) in place.
  void resolve(Json& value, const std::string& path, std::vector<std::string>& using_names) {
    if (value.is_object()) {
      if (value.contains("$ref")) {
        resolve_reference(value, path, using_names);
        return;
      }
      for (auto& [key, item] : value.items()) resolve(item, json_pointer_append(path, key), using_names);
    } else if (value.is_array()) {
      for (std::size_t i = 0; i < value.size(); ++i) resolve(value[i], json_pointer_append(path, i), using_names);
    }
  }

 private:
  void resolve_reference(Json& value, const std::string& path, std::vector<std::string>& using_names) {
    const std::string at = path + "/$ref";
    if (value.size() != 1) {
      diag_.error(path, "a reference has the key \"$ref\" alone; move the other keys into the definition");
      return;
    }
    const Json& target = value["$ref"];
    if (!target.is_string() || target.get<std::string>().rfind(kPrefix, 0) != 0) {
      diag_.error(at, " = " + detail::abbreviated_dump(target) + " is not \"#/definitions/<name>\"; a config refers "
                      "only to its own top-level definitions");
      return;
    }
    const std::string name = target.get<std::string>().substr(kPrefix.size());
    std::vector<std::string> known;
    if (definitions_ != nullptr) {
      for (const auto& [key, item] : definitions_->items()) known.push_back(key);
    }
    if (definitions_ == nullptr || !definitions_->contains(name)) {
      diag_.error(at, " = \"" + target.get<std::string>() + "\": no definition named '" + name + "'" +
                          (known.empty() ? std::string("; add it under the top-level \"definitions\"")
                                         : "; " + suggest(name, known)));
      return;
    }
    for (const std::string& n : using_names) {
      if (n == name || static_cast<int>(using_names.size()) >= kMaxDepth) {
        diag_.error(at, " = \"" + target.get<std::string>() + "\" refers back to itself (through the definitions of " +
                            join_names(using_names) + "); break the cycle");
        return;
      }
    }
    Json copy = (*definitions_)[name];
    using_names.push_back(name);
    resolve(copy, path, using_names);
    using_names.pop_back();
    value = std::move(copy);
  }

  static std::string join_names(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) {
      out.append(i ? ", '" : "'").append(names[i]).append("'");
    }
    return out;
  }

  const Json* definitions_;
  Diagnostics& diag_;
};

}  // namespace

Json resolve_definitions(const Json& config, Diagnostics& diag) {
  Json out = config;
  if (!out.is_object()) return out;
  const Json* definitions = nullptr;
  if (const auto it = config.find("definitions"); it != config.end()) {
    if (!it->is_object()) {
      diag.error("/definitions", " = " + detail::abbreviated_dump(*it) +
                                     " is not an object of named values (\"<name>\": value)");
      return out;
    }
    definitions = &*it;
  }
  Resolver resolver(definitions, diag);
  std::vector<std::string> using_names;
  for (auto& [key, value] : out.items()) {
    if (key == "definitions") continue;  // resolved where they are used
    resolver.resolve(value, json_pointer_append("", key), using_names);
  }
  return out;
}

}  // namespace ftsense
