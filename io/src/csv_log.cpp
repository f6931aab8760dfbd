#include "ftsense/io/csv_log.hpp"

#include <charconv>

#include <cerrno>
#include <filesystem>
#include <system_error>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>
#include <utility>

namespace ftsense::io {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Parses one cell; false when it is not a number. Empty cells are dropped samples: NaN.
bool parse_cell(std::string_view cell, double& out) {
  cell = trim(cell);
  if (cell.empty()) {
    out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  if (cell.front() == '+') {
    cell.remove_prefix(1);
    if (!cell.empty() && (cell.front() == '-' || cell.front() == '+')) return false;  // "+-1"
  }
  const char* end = cell.data() + cell.size();
  const auto [ptr, ec] = std::from_chars(cell.data(), end, out);
  if (ec == std::errc::result_out_of_range) {
    // from_chars says the same for 1e400 and 1e-400; strtod tells them apart (rare path): a
    // magnitude beyond double's range becomes a signed infinity the sanity checks then catch, one
    // below its smallest denormal the nearest double, a signed zero.
    if (ptr != end) return false;
    const std::string text(cell);
    out = std::strtod(text.c_str(), nullptr);
    return true;
  }
  return ec == std::errc() && ptr == end;
}

}  // namespace

CsvLogReader::CsvLogReader(const std::string& path, TimeColumn time) : path_(path), time_(std::move(time)) {
  // A log is a file or a pipe (a logger streaming into ftsense); a directory or a device
  // (/dev/zero) is refused before reading.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) {
    throw LogError(LogError::Kind::cannot_open, path + ": is a directory, not a log file; give the file inside it");
  }
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
      !std::filesystem::is_fifo(status)) {
    throw LogError(LogError::Kind::cannot_open,
                   path + ": is not a regular file or a pipe (a device or socket); give the log as a file");
  }
  if (ec.value() == ELOOP) {
    throw LogError(LogError::Kind::cannot_open, path + ": is a loop of symbolic links; point the link at the log");
  }
  file_.open(path);
  if (!file_) {
    throw LogError(LogError::Kind::cannot_open,
                   path + ": cannot open the log file; check the path and read permission");
  }
  read_header();
}

CsvLogReader::CsvLogReader(std::istream& in, std::string name, TimeColumn time)
    : path_(std::move(name)), time_(std::move(time)), stream_(&in) {
  read_header();
}

namespace {
// Seconds in the shortest form that reads back exactly (1 ms steps stay apart on epoch time).
std::string format_seconds(double t) {
  char text[40];
  const auto result = std::to_chars(text, text + sizeof text, t);
  return std::string(text, result.ptr);
}
}  // namespace

void CsvLogReader::read_header() {
  if (!std::getline(in(), line_buffer_)) {
    throw LogError(LogError::Kind::bad_header,
                   path_ + ":1: the file is empty; a log starts with a header line '" + time_.name + ",...'");
  }
  std::string_view header = line_buffer_;
  if (header.size() >= 3 && static_cast<unsigned char>(header[0]) == 0xEF &&
      static_cast<unsigned char>(header[1]) == 0xBB && static_cast<unsigned char>(header[2]) == 0xBF) {
    header.remove_prefix(3);  // UTF-8 byte order mark
  }
  std::set<std::string> seen;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = header.find(',', start);
    const std::string name(trim(header.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (name.empty()) {
      fail("column " + std::to_string(columns_.size() + 1) + " of the header has no name");
    }
    if (!seen.insert(name).second) fail("column '" + name + "' appears twice in the header");
    columns_.push_back(name);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (columns_.front() != time_.name) {
    fail("the first column is '" + columns_.front() + "'; a log's first column must be its time, '" + time_.name +
         "'" + (time_.name == "time_s" ? " (if '" + columns_.front() + "' is the time, say so in the config: \"time\": {\"column\": \"" +
                                             columns_.front() + "\", \"unit\": \"s\"}, or ms, us, ns)"
                                       : std::string(" (the config's time.column)")));
  }
}

std::optional<std::size_t> CsvLogReader::find_column(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (columns_[i] == name) return i;
  }
  return std::nullopt;
}

void CsvLogReader::fail(const std::string& what) const {
  throw LogError(line_ == 1 ? LogError::Kind::bad_header : LogError::Kind::bad_row,
                 path_ + ":" + std::to_string(line_) + ": " + what);
}

bool CsvLogReader::next(std::vector<double>& values) {
  while (true) {
    if (!std::getline(in(), line_buffer_)) return false;
    ++line_;
    if (in().eof() && !trim(line_buffer_).empty()) {
      // The last line has no line end: a logger stopped mid-row may have cut its last number
      // ("12.5" written as "1"), which would read as a wrong value rather than a missing one.
      fail("the last row has no line end, so it may be cut mid-row; if it is complete, end the file with a "
           "newline, else delete the row");
    }
    if (!trim(line_buffer_).empty()) break;  // blank lines (e.g. a trailing newline) are skipped
  }
  values.resize(columns_.size());
  std::string_view row = line_buffer_;
  std::size_t start = 0;
  std::size_t column = 0;
  while (true) {
    const std::size_t comma = row.find(',', start);
    const std::string_view cell = row.substr(start, comma == std::string_view::npos ? comma : comma - start);
    if (column >= columns_.size()) {
      fail("row has more fields than the header's " + std::to_string(columns_.size()));
    }
    if (!parse_cell(cell, values[column])) {
      fail("column '" + columns_[column] + "' (field " + std::to_string(column + 1) + ") = '" +
           std::string(trim(cell)) + "' is not a number");
    }
    ++column;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (column != columns_.size()) {
    fail("row has " + std::to_string(column) + " fields but the header has " +
         std::to_string(columns_.size()));
  }
  if (time_.seconds_per_unit != 1.0) values[0] *= time_.seconds_per_unit;
  const double t = values[0];
  if (!std::isfinite(t)) fail(time_.name + " is not a finite number");
  if (last_time_ && !(t > *last_time_)) {
    fail(time_.name + " = " + format_seconds(t) + " s is not after the previous row's " + format_seconds(*last_time_) +
         " s; time must be strictly increasing (sort or de-duplicate the log)");
  }
  last_time_ = t;
  return true;
}

CsvLogWriter::CsvLogWriter(const std::string& path, const std::vector<std::string>& columns,
                           const std::vector<std::string>& inputs)
    : file_(path, inputs), column_count_(columns.size()), row_(columns.size() * kMaxCellChars + 1) {
  for (std::size_t i = 0; i < columns.size(); ++i) file_.stream() << (i ? "," : "") << columns[i];
  file_.stream() << '\n';
}

void CsvLogWriter::write_row(std::span<const double> values) {
  // Formatted straight into the row buffer, which has room for the longest cell of every column.
  char* out = row_.data();
  char* const end = row_.data() + row_.size();
  for (std::size_t i = 0; i < values.size() && i < column_count_; ++i) {
    if (i) *out++ = ',';
    const double v = values[i];
    if (std::isnan(v)) {
      out = std::copy_n("nan", 3, out);
    } else {
      const auto [next, ec] = std::to_chars(out, end, v);
      if (ec == std::errc()) out = next;
    }
  }
  *out++ = '\n';
  file_.stream().write(row_.data(), out - row_.data());
}

void CsvLogWriter::flush() {
  file_.stream().flush();
  if (!file_.stream()) throw OutputError(file_.target().string() + ": writing failed (disk full?); nothing was written under that name");
}

void CsvLogWriter::commit() { file_.commit(); }

}  // namespace ftsense::io
