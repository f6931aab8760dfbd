#pragma once
// Problems found while loading or building something from user input.
//
// ftsense separates three kinds of failure (docs/architecture.md):
//   - user/config errors: collected here, thrown together as one ConfigError;
//   - programmer errors: always-on FTSENSE_DEMAND checks (std::logic_error);
//   - sensing outcomes (fault, infeasible, not ready): data returned by step().
//
// Every problem carries where it is (a JSON Pointer such as "/stages/2/params/cutoff_hz", or
// "file:line:column") and a sentence that says what is wrong and, where possible, what to do.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ftsense {

struct Diagnostic {
  std::string path;     // JSON Pointer or file position; empty for the document itself
  std::string message;  // what is wrong and what to do, without the path

  // "path: message", or "path = value violates rule" when the message starts with " = ".
  [[nodiscard]] std::string text() const;
};

// Collects problems, keeps going, and reports them all at once.
class Diagnostics {
 public:
  void error(std::string path, std::string message);
  void warning(std::string path, std::string message);
  // Appends another collection with every path prefixed (used to place a stage's relative
  // paths under "/stages/3").
  void merge(const Diagnostics& other, std::string_view path_prefix = {});

  [[nodiscard]] bool has_errors() const { return !errors_.empty(); }
  [[nodiscard]] const std::vector<Diagnostic>& errors() const { return errors_; }
  [[nodiscard]] const std::vector<Diagnostic>& warnings() const { return warnings_; }

  // Throws ConfigError carrying every error collected so far, if there is any.
  void throw_if_errors() const;

 private:
  std::vector<Diagnostic> errors_;
  std::vector<Diagnostic> warnings_;
};

// A user or configuration error: one or more problems, each on its own line in what().
class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(std::vector<Diagnostic> problems);
  ConfigError(std::string path, std::string message);
  [[nodiscard]] const std::vector<Diagnostic>& problems() const { return problems_; }

 private:
  std::vector<Diagnostic> problems_;
};

// Programmer-error check that stays on in release builds.
[[noreturn]] void demand_failed(const char* condition, const char* file, int line,
                                std::string_view message);

// Escapes one JSON Pointer reference token (RFC 6901: "~" -> "~0", "/" -> "~1").
[[nodiscard]] std::string json_pointer_token(std::string_view key);
[[nodiscard]] std::string json_pointer_append(std::string_view base, std::string_view key);
[[nodiscard]] std::string json_pointer_append(std::string_view base, std::size_t index);

// Shortest text that reads back as the same double ("0", "500", "0.001", "1e-10").
[[nodiscard]] std::string format_number(double value);

// The candidate closest to `name` by edit distance, or empty when nothing is reasonably close.
[[nodiscard]] std::string closest_match(std::string_view name,
                                        const std::vector<std::string>& candidates);
// "did you mean 'x'? " (or empty) followed by "known: a, b, c".
[[nodiscard]] std::string suggest(std::string_view name, const std::vector<std::string>& candidates);

}  // namespace ftsense

#define FTSENSE_DEMAND(condition, message)                                     \
  do {                                                                         \
    if (!(condition)) {                                                        \
      ::ftsense::demand_failed(#condition, __FILE__, __LINE__, (message));     \
    }                                                                          \
  } while (false)
