#pragma once
// The alarms of a run, for a log without truth (every real log): nothing to score against, so
// each alarm is listed, not called right or wrong.
//
// An alarm is a maximal stretch of samples whose flag (`<channel>/fault`) is raised: it starts at
// the first flagged sample and ends at the last one (still raised at the end of the log: `open`).
// Alarms that end before the warm-up does are not listed (the filters settle then; the same
// warm-up as the metrics' false alarms). The type named is the fault type the channel shows most
// during the alarm (ties: the lower code), as metrics.hpp's "type shown".

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "ftsense/fault_type.hpp"
#include "ftsense/report/metrics.hpp"

namespace ftsense::report {

struct Alarm {
  std::string channel;
  std::size_t first = 0, last = 0;  // sample indices, inclusive
  double start_s = 0.0, end_s = 0.0;
  bool open = false;  // still raised at the end of the log
  FaultType type = FaultType::unclassified;
};

// The alarms of one channel, in time order.
[[nodiscard]] std::vector<Alarm> channel_alarms(const std::string& channel, std::span<const double> time,
                                                std::span<const double> flag, std::span<const double> flag_type,
                                                const MetricOptions& options);

}  // namespace ftsense::report
