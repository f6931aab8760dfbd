// ftsense-replay-floor: about the least a replay of a CSV log can cost on one thread, to set
// `ftsense run`'s wall time against (bench/replay_throughput.sh runs both on the same log).
//
// It reads the log in 1 MiB blocks, parses every cell of every row with std::from_chars (each
// cell must be a whole number, as ftsense's reader requires; an empty cell is NaN), and writes
// one row per row with std::to_chars (shortest round trip, "nan" for NaN, as ftsense's writer):
// output column j holds input column COLUMNS[j]. replay_throughput.sh picks, for each column of
// `ftsense run`'s output, the input column whose numbers are about as long, so the floor writes
// as many columns and about as many bytes, with no pipeline, no per-row checks and no second
// thread.
//
// Usage: ftsense-replay-floor INPUT.csv OUTPUT.csv COLUMNS   (COLUMNS: comma-separated indices)
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

namespace {

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "ftsense-replay-floor: %s\n", what.c_str());
  std::exit(1);
}

// Longest std::to_chars of a double (shortest round trip), "-2.2250738585072014e-308", and a comma.
constexpr std::size_t kMaxCellChars = 25;

// Writes one output row at `out`, column j from input cell columns[j], then a newline; returns
// the end. `out` has room for kMaxCellChars per column and the newline.
char* write_row(const std::vector<double>& row, const std::vector<std::size_t>& columns, char* out) {
  char* const end = out + columns.size() * kMaxCellChars + 1;
  for (std::size_t j = 0; j < columns.size(); ++j) {
    if (j) *out++ = ',';
    const double v = row[columns[j]];
    if (std::isnan(v)) {
      out = std::copy_n("nan", 3, out);
    } else {
      const auto [next, ec] = std::to_chars(out, end, v);
      if (ec == std::errc()) out = next;
    }
  }
  *out++ = '\n';
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: ftsense-replay-floor INPUT.csv OUTPUT.csv COLUMNS\n");
    return 2;
  }
  std::vector<std::size_t> columns;
  std::size_t widest = 0;
  for (const char* p = argv[3];; ++p) {
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(p, p + std::strlen(p), index);
    if (ec != std::errc() || (*end != ',' && *end != '\0')) fail(std::string("COLUMNS '") + argv[3] + "' is not a list of indices");
    columns.push_back(index);
    widest = std::max(widest, index);
    p = end;
    if (*p == '\0') break;
  }
  std::FILE* in = std::fopen(argv[1], "rb");
  if (!in) fail(std::string("cannot open ") + argv[1]);
  std::FILE* out = std::fopen(argv[2], "wb");
  if (!out) fail(std::string("cannot create ") + argv[2]);
  std::string header;
  for (std::size_t j = 0; j < columns.size(); ++j) header += (j ? ",c" : "c") + std::to_string(columns[j]);
  header += '\n';
  std::fwrite(header.data(), 1, header.size(), out);

  constexpr std::size_t kBlock = 1 << 20;
  std::vector<char> buffer(2 * kBlock);
  std::size_t held = 0;  // bytes of an unfinished line carried over from the previous block
  std::vector<double> row;
  std::vector<char> text(kBlock + columns.size() * kMaxCellChars + 1);  // output, flushed per block
  char* text_end = text.data();
  std::size_t line = 0;
  bool at_end = false;
  while (!at_end) {
    if (held == buffer.size()) buffer.resize(2 * buffer.size());  // a line longer than the buffer
    const std::size_t got = std::fread(buffer.data() + held, 1, buffer.size() - held, in);
    at_end = got == 0;
    const char* p = buffer.data();
    const char* const end = buffer.data() + held + got;
    while (true) {
      const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
      if (!eol) {
        if (!at_end || p == end) break;
        eol = end;  // last line without a newline
      }
      const char* stop = (eol > p && eol[-1] == '\r') ? eol - 1 : eol;
      if (line++ > 0 && stop > p) {  // the header is skipped
        row.clear();
        for (const char* cell = p;;) {
          const char* comma = static_cast<const char*>(std::memchr(cell, ',', static_cast<std::size_t>(stop - cell)));
          const char* cell_end = comma ? comma : stop;
          double v = std::numeric_limits<double>::quiet_NaN();
          if (cell_end != cell) {
            const auto [ptr, ec] = std::from_chars(cell, cell_end, v);
            if (ec != std::errc() || ptr != cell_end) fail("line " + std::to_string(line) + ": a cell is not a number");
          }
          row.push_back(v);
          if (!comma) break;
          cell = comma + 1;
        }
        if (row.size() <= widest) fail("line " + std::to_string(line) + ": fewer cells than COLUMNS needs");
        text_end = write_row(row, columns, text_end);
        if (static_cast<std::size_t>(text_end - text.data()) >= kBlock) {
          std::fwrite(text.data(), 1, static_cast<std::size_t>(text_end - text.data()), out);
          text_end = text.data();
        }
      }
      p = eol == end ? end : eol + 1;
      if (p == end) break;
    }
    held = static_cast<std::size_t>(end - p);
    std::memmove(buffer.data(), p, held);
  }
  std::fwrite(text.data(), 1, static_cast<std::size_t>(text_end - text.data()), out);
  if (std::fclose(out) != 0) fail(std::string("writing ") + argv[2] + " failed");
  std::fclose(in);
  std::printf("%zu rows\n", line > 0 ? line - 1 : 0);
  return 0;
}
