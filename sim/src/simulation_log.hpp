#pragma once
// What the biped and the quadruped simulations share (private header): the CSV writer, the log
// period, and the fall test that ends a run.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <locale>
#include <ostream>
#include <sstream>
#include <string>

#include "ftsense/sim/scenario.hpp"
#include "ftsense/sim/simulator.hpp"

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

/// The fall test: a torso below min_height_m, tilted past max_tilt_rad, or of no finite height
/// ends the run; the summary then says when and why. Returns true on a fall.
inline bool record_fall(double t, double height, double tilt, double min_height_m, double max_tilt_rad,
                        SimulationSummary& sum) {
  if (!(height < min_height_m || tilt > max_tilt_rad || !std::isfinite(height))) return false;
  sum.fell = true;
  sum.fall_time_s = t;
  std::ostringstream msg;
  msg.imbue(std::locale::classic());
  msg << "robot fell at t = " << t << " s (torso height " << height << " m, tilt " << tilt
      << " rad; limits: height >= " << min_height_m << " m, tilt <= " << max_tilt_rad << " rad)";
  sum.message = msg.str();
  return true;
}

}  // namespace ftsense::sim::detail
