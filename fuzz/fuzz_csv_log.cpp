// libFuzzer target: the CSV log reader (io/). Any byte string is a log; the reader must read
// every row or throw io::LogError. Anything else (another exception, a sanitizer report, a
// hang) is a bug. Also checked: a row the reader accepts has a finite, strictly increasing
// time_s and exactly one value per column.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "ftsense/io/csv_log.hpp"

namespace {

[[noreturn]] void contract_broken(const char* what, std::size_t line) {
  std::fprintf(stderr, "fuzz_csv_log: contract broken at line %zu: %s\n", line, what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    ftsense::io::CsvLogReader reader(in, "fuzz.csv");
    if (reader.columns().empty() || reader.columns().front() != "time_s") {
      contract_broken("header accepted without time_s first", reader.line());
    }
    std::vector<double> row;
    bool have_time = false;
    double last_time = 0.0;
    while (reader.next(row)) {
      if (row.size() != reader.columns().size()) contract_broken("row size != column count", reader.line());
      if (!std::isfinite(row[0])) contract_broken("non-finite time_s accepted", reader.line());
      if (have_time && !(row[0] > last_time)) contract_broken("time_s not increasing", reader.line());
      have_time = true;
      last_time = row[0];
    }
  } catch (const ftsense::io::LogError&) {
    // The reader's documented answer to a malformed log.
  }
  return 0;
}
