#pragma once
// CSV logs (design.md): first column the time (`time_s` unless the reader is told another name
// and unit: `__time` in ns, say; the reader converts it to seconds), strictly increasing; then
// named columns. Cells
// are decimal numbers; `nan`, `inf` and an empty cell (a dropped sample) read as NaN/Inf.
//
// The reader streams: one row at a time into a caller-owned vector, no allocation per row once
// the line buffer has grown. Problems throw LogError with "file:line: what; what to do".

#include <charconv>
#include <cstddef>
#include <fstream>
#include <istream>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/io/output_file.hpp"

namespace ftsense::io {

class LogError : public std::runtime_error {
 public:
  enum class Kind { cannot_open, bad_header, bad_row };
  LogError(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  [[nodiscard]] Kind kind() const noexcept { return kind_; }

 private:
  Kind kind_;
};

// The log's time column: its name and unit (seconds per unit: 1e-9 for ns).
struct TimeColumn {
  std::string name = "time_s";
  std::string unit = "s";
  double seconds_per_unit = 1.0;
};

class CsvLogReader {
 public:
  // Opens `path` and reads the header; throws LogError when the file is missing, empty, or the
  // header does not start with the time column or has empty or repeated names.
  explicit CsvLogReader(const std::string& path, TimeColumn time = {});
  // Reads a log from `in` (which must outlive the reader); `name` stands for the file in
  // messages. Same header checks and errors as above, except cannot_open.
  CsvLogReader(std::istream& in, std::string name, TimeColumn time = {});

  [[nodiscard]] const std::vector<std::string>& columns() const noexcept { return columns_; }
  [[nodiscard]] std::optional<std::size_t> find_column(std::string_view name) const noexcept;
  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  // 1-based line number of the row read last (the header is line 1).
  [[nodiscard]] std::size_t line() const noexcept { return line_; }

  // Reads the next data row into `values` (resized to columns().size() on first use; values[0] is
  // the time in seconds). Returns
  // false at the end of the file. Throws LogError on a malformed row (field count, non-numeric
  // cell, time not strictly increasing), naming line and column.
  bool next(std::vector<double>& values);

 private:
  [[noreturn]] void fail(const std::string& what) const;
  void read_header();
  std::istream& in() noexcept { return stream_ != nullptr ? *stream_ : file_; }

  std::string path_;
  TimeColumn time_;
  std::ifstream file_;             // when opened from a path
  std::istream* stream_ = nullptr;  // when reading a caller's stream
  std::vector<std::string> columns_;
  std::string line_buffer_;
  std::size_t line_ = 1;
  std::optional<double> last_time_;
};

// Writes a CSV log with shortest round-trip number formatting (std::to_chars). The file is whole
// or absent (output_file.hpp): rows go to a temporary file that commit() renames onto `path`.
class CsvLogWriter {
 public:
  // Throws OutputError when the file cannot be created or is one of `inputs` (or links to it).
  CsvLogWriter(const std::string& path, const std::vector<std::string>& columns,
               const std::vector<std::string>& inputs = {});
  void write_row(std::span<const double> values);
  // Throws OutputError when a write failed (disk full).
  void flush();
  // Flushes and puts the file under its name; without it the destructor removes what was written.
  void commit();

 private:
  OutputFile file_;
  // Longest std::to_chars of a double (shortest round trip), "-2.2250738585072014e-308", and a comma.
  static constexpr std::size_t kMaxCellChars = 25;
  std::size_t column_count_;
  std::vector<char> row_;
};

}  // namespace ftsense::io
