#include "ftsense/diagnostics.hpp"

#include <algorithm>
#include <charconv>
#include <limits>
#include <sstream>

namespace ftsense {

std::string Diagnostic::text() const {
  if (path.empty()) return message;
  if (message.rfind(" = ", 0) == 0) return path + message;
  return path + ": " + message;
}

void Diagnostics::error(std::string path, std::string message) {
  errors_.push_back({std::move(path), std::move(message)});
}

void Diagnostics::warning(std::string path, std::string message) {
  warnings_.push_back({std::move(path), std::move(message)});
}

void Diagnostics::merge(const Diagnostics& other, std::string_view path_prefix) {
  for (const auto& d : other.errors_) errors_.push_back({std::string(path_prefix) + d.path, d.message});
  for (const auto& d : other.warnings_)
    warnings_.push_back({std::string(path_prefix) + d.path, d.message});
}

void Diagnostics::throw_if_errors() const {
  if (has_errors()) throw ConfigError(errors_);
}

namespace {
std::string join_problems(const std::vector<Diagnostic>& problems) {
  std::string out;
  for (const auto& p : problems) {
    if (!out.empty()) out += '\n';
    out += p.text();
  }
  return out;
}
}  // namespace

ConfigError::ConfigError(std::vector<Diagnostic> problems)
    : std::runtime_error(join_problems(problems)), problems_(std::move(problems)) {}

ConfigError::ConfigError(std::string path, std::string message)
    : ConfigError(std::vector<Diagnostic>{{std::move(path), std::move(message)}}) {}

void demand_failed(const char* condition, const char* file, int line, std::string_view message) {
  std::ostringstream os;
  os << file << ':' << line << ": ftsense internal check failed: " << condition << ": " << message;
  throw std::logic_error(os.str());
}

std::string json_pointer_token(std::string_view key) {
  std::string out;
  out.reserve(key.size());
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string json_pointer_append(std::string_view base, std::string_view key) {
  return std::string(base) + "/" + json_pointer_token(key);
}

std::string json_pointer_append(std::string_view base, std::size_t index) {
  return std::string(base) + "/" + std::to_string(index);
}

namespace {
// Optimal string alignment distance: insertions, deletions, substitutions and transpositions of
// neighbours ("rnu" -> "run") each cost 1.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}
}  // namespace

std::string format_number(double value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

std::string closest_match(std::string_view name, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  // Close means: at most a third of the longer name differs (typos, not different words).
  const std::size_t longer = std::max(name.size(), best.size());
  if (best.empty() || best_distance * 3 > longer + 1) return {};
  return best;
}

std::string suggest(std::string_view name, const std::vector<std::string>& candidates) {
  std::string out;
  const std::string best = closest_match(name, candidates);
  if (!best.empty()) out += "did you mean '" + best + "'? ";
  out += "known: ";
  if (candidates.empty()) {
    out += "(none)";
  } else {
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (i > 0) out += ", ";
      out += candidates[i];
    }
  }
  return out;
}

}  // namespace ftsense
