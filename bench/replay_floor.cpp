// ftsense-replay-floor: about the least a replay of a CSV log can cost on one thread, to set
// `ftsense run`'s wall time against (bench/replay_throughput.sh runs both on the same log).
//
// It reads the log in 1 MiB blocks, parses every cell of every row with std::from_chars (each
// cell must be a whole number, as ftsense's reader requires; an empty cell is NaN), and writes
// per row COLUMNS numbers with std::to_chars (shortest round trip, "nan" for NaN, as ftsense's
// writer), taking the row's cells in turn: the rows and columns of `ftsense run`'s output with
// no pipeline, no per-row checks and no second thread.
//
// Usage: ftsense-replay-floor INPUT.csv OUTPUT.csv COLUMNS
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

// Appends COLUMNS numbers taken from `row` in turn, then a newline.
void write_row(const std::vector<double>& row, std::size_t columns, std::string& out) {
  char buffer[32];
  for (std::size_t j = 0; j < columns; ++j) {
    if (j) out += ',';
    const double v = row[j % row.size()];
    if (std::isnan(v)) {
      out += "nan";
    } else {
      const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
      out.append(buffer, ec == std::errc() ? end : buffer);
    }
  }
  out += '\n';
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: ftsense-replay-floor INPUT.csv OUTPUT.csv COLUMNS\n");
    return 2;
  }
  const std::size_t columns = std::strtoull(argv[3], nullptr, 10);
  if (columns == 0) fail(std::string("COLUMNS '") + argv[3] + "' is not a positive count");
  std::FILE* in = std::fopen(argv[1], "rb");
  if (!in) fail(std::string("cannot open ") + argv[1]);
  std::FILE* out = std::fopen(argv[2], "wb");
  if (!out) fail(std::string("cannot create ") + argv[2]);

  std::string header;
  for (std::size_t j = 0; j < columns; ++j) header += (j ? ",c" : "c") + std::to_string(j);
  header += '\n';
  std::fwrite(header.data(), 1, header.size(), out);

  constexpr std::size_t kBlock = 1 << 20;
  std::vector<char> buffer(2 * kBlock);
  std::size_t held = 0;  // bytes of an unfinished line carried over from the previous block
  std::vector<double> row;
  std::string text;
  text.reserve(kBlock + 4096);
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
        write_row(row, columns, text);
        if (text.size() >= kBlock) {
          std::fwrite(text.data(), 1, text.size(), out);
          text.clear();
        }
      }
      p = eol == end ? end : eol + 1;
      if (p == end) break;
    }
    held = static_cast<std::size_t>(end - p);
    std::memmove(buffer.data(), p, held);
  }
  std::fwrite(text.data(), 1, text.size(), out);
  if (std::fclose(out) != 0) fail(std::string("writing ") + argv[2] + " failed");
  std::fclose(in);
  std::printf("%zu rows\n", line > 0 ? line - 1 : 0);
  return 0;
}
