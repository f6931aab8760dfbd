#include "ftsense/report/alarms.hpp"

namespace ftsense::report {

std::vector<Alarm> channel_alarms(const std::string& channel, std::span<const double> time,
                                  std::span<const double> flag, std::span<const double> flag_type,
                                  const MetricOptions& options) {
  std::vector<Alarm> out;
  if (time.empty()) return out;
  const double t0 = time.front();
  for (std::size_t k = 0; k < time.size(); ++k) {
    if (flag[k] == 0.0) continue;
    std::size_t last = k;
    while (last + 1 < time.size() && flag[last + 1] != 0.0) ++last;
    if (time[last] - t0 >= options.warmup_s) {
      Alarm a{channel, k, last, time[k], time[last], last + 1 == time.size(), FaultType::unclassified};
      const FaultType shown = shown_type(flag, flag_type, FaultWindow{k, last, FaultType::none});
      if (shown != FaultType::none) a.type = shown;
      out.push_back(std::move(a));
    }
    k = last;
  }
  return out;
}

}  // namespace ftsense::report
