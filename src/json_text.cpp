#include "ftsense/json_text.hpp"

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace ftsense {

namespace {

struct ParseFrame {
  bool is_object = false;
  std::set<std::string> keys;
  std::string key;
  std::size_t next_index = 0;
  [[nodiscard]] std::string token() const {
    return is_object ? json_pointer_token(key) : std::to_string(next_index - 1);
  }
};

std::pair<std::size_t, std::size_t> line_column(std::string_view text, std::size_t byte) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// Calls `visit(byte)` for every byte of `text` outside string literals, until it returns true;
// returns that byte's index, or npos.
template <class Visit>
std::size_t find_outside_strings(std::string_view text, Visit visit) {
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (visit(i)) {
      return i;
    }
  }
  return std::string_view::npos;
}

bool is_number_char(char c) {
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
}

std::string position(std::string_view text, std::size_t byte, std::string_view source_name) {
  const auto [line, column] = line_column(text, byte);
  return std::string(source_name) + ":" + std::to_string(line) + ":" + std::to_string(column);
}

}  // namespace

Json parse_json_text(std::string_view text, std::string_view source_name) {
  // nlohmann stops at a NUL byte as at the end of the text: whatever follows would be ignored.
  if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
    throw ConfigError(position(text, nul, source_name),
                      "not valid JSON: a NUL byte; is this a text file (or a truncated one)?");
  }
  // Nesting is limited before parsing: JSON values are copied, compared and printed
  // recursively, so a deep enough text ("[[[[...") would overflow the stack.
  std::size_t depth = 0;
  const std::size_t too_deep = find_outside_strings(text, [&](std::size_t i) {
    if (text[i] == '[' || text[i] == '{') return ++depth > kMaxJsonDepth;
    if ((text[i] == ']' || text[i] == '}') && depth > 0) --depth;
    return false;
  });
  if (too_deep != std::string_view::npos) {
    throw ConfigError(position(text, too_deep, source_name),
                      "not valid JSON: nested deeper than " + std::to_string(kMaxJsonDepth) +
                          " arrays or objects; a config needs a handful of levels");
  }
  std::vector<ParseFrame> stack;
  std::vector<Diagnostic> duplicates;
  auto on_element = [&stack] {
    if (!stack.empty() && !stack.back().is_object) ++stack.back().next_index;
  };
  auto callback = [&](int /*depth*/, Json::parse_event_t event, Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        on_element();
        stack.push_back(ParseFrame{event == Json::parse_event_t::object_start, {}, {}, 0});
        break;
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        if (!stack.empty()) stack.pop_back();
        break;
      case Json::parse_event_t::key: {
        if (stack.empty()) break;
        const std::string key = parsed.get<std::string>();
        ParseFrame& top = stack.back();
        if (!top.keys.insert(key).second) {
          std::string path;
          for (std::size_t i = 0; i + 1 < stack.size(); ++i) {
            path += '/';
            path += stack[i].token();
          }
          duplicates.push_back({path + "/" + json_pointer_token(key),
                                "duplicate key '" + key +
                                    "' (JSON keeps only the last one); remove or rename one"});
        }
        top.key = key;
        break;
      }
      case Json::parse_event_t::value:
        on_element();
        break;
    }
    return true;
  };
  Json document;
  try {
    document = Json::parse(text.begin(), text.end(), callback, /*allow_exceptions=*/true,
                           /*ignore_comments=*/false);
  } catch (const Json::parse_error& e) {
    const auto [line, column] = line_column(text, e.byte == 0 ? 0 : e.byte - 1);
    std::string what = e.what();
    // nlohmann's text: "[json.exception.parse_error.101] parse error at line 1, column 2: ..."
    if (const auto colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    throw ConfigError(std::string(source_name) + ":" + std::to_string(line) + ":" +
                          std::to_string(column),
                      "not valid JSON: " + what);
  } catch (const Json::out_of_range& e) {
    // A number beyond the range of a double ("1e400"): nlohmann says "number overflow parsing
    // '1e400'" without a position; the first number token spelled so is the one.
    std::string what = e.what();
    if (const auto colon = what.find("] "); colon != std::string::npos) what = what.substr(colon + 2);
    const auto open = what.find('\'');
    const auto close = what.rfind('\'');
    const std::string token = open < close ? what.substr(open + 1, close - open - 1) : std::string();
    const std::size_t at = find_outside_strings(text, [&](std::size_t i) {
      return !token.empty() && text.substr(i, token.size()) == token && (i == 0 || !is_number_char(text[i - 1])) &&
             (i + token.size() == text.size() || !is_number_char(text[i + token.size()]));
    });
    throw ConfigError(position(text, at == std::string_view::npos ? 0 : at, source_name),
                      "not valid JSON: " + what + " (beyond the range of a double)");
  }
  if (!duplicates.empty()) {
    for (auto& d : duplicates) d.message += " (in " + std::string(source_name) + ")";
    throw ConfigError(std::move(duplicates));
  }
  return document;
}

}  // namespace ftsense
