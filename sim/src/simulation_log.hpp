#pragma once
// What the biped and the quadruped simulations share in writing their logs (private header).
#include <charconv>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <string>

#include "ftsense/sim/scenario.hpp"

namespace ftsense::sim::detail {

/// Row-at-a-time CSV writer: shortest round-trip numbers, "nan" for NaN.
class CsvRow {
 public:
  void num(double x) {
    buf_ += ',';
    if (std::isnan(x)) {
      buf_ += "nan";
      return;
    }
    char tmp[32];
    auto res = std::to_chars(tmp, tmp + sizeof tmp, x);
    buf_.append(tmp, res.ptr);
  }
  void first(double t) {
    buf_.clear();
    char tmp[32];
    auto res = std::to_chars(tmp, tmp + sizeof tmp, t);
    buf_.append(tmp, res.ptr);
  }
  void flush(std::ostream& os) {
    buf_ += '\n';
    os.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
  }

 private:
  std::string buf_;
};

/// Ticks per logged row (the sensors sample every log_period_s); throws ScenarioError if the
/// period is not a whole multiple of the tick dt.
std::int64_t log_every_ticks(const Scenario& sc, double dt);

}  // namespace ftsense::sim::detail
