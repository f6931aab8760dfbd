#include "ftsense/report/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace ftsense::report {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A code as written in a fault column; codes that name no type read as unclassified.
FaultType type_of_code(double code) { return fault_type_from_code(code).value_or(FaultType::unclassified); }
}  // namespace

double rms(std::span<const double> values) {
  if (values.empty()) return kNaN;
  double s = 0.0;
  for (double x : values) s += x * x;
  return std::sqrt(s / static_cast<double>(values.size()));
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return kNaN;
  const double last = static_cast<double>(values.size() - 1);
  const auto k = static_cast<std::size_t>(std::clamp(p * last, 0.0, last));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

std::optional<FaultWindow> fault_window(std::span<const double> true_fault) {
  std::optional<FaultWindow> window;
  for (std::size_t k = 0; k < true_fault.size(); ++k) {
    if (true_fault[k] == 0.0) continue;
    if (!window) window = FaultWindow{k, k, type_of_code(true_fault[k])};
    window->end = k;
  }
  return window;
}

std::optional<Detection> first_detection(std::span<const double> time, std::span<const double> flag,
                                         std::span<const double> flag_type, const FaultWindow& window) {
  for (std::size_t k = window.onset; k < time.size(); ++k) {
    if (flag[k] != 0.0) return Detection{time[k] - time[window.onset], type_of_code(flag_type[k])};
  }
  return std::nullopt;
}

FaultType shown_type(std::span<const double> flag, std::span<const double> flag_type, const FaultWindow& window) {
  std::map<int, int> shown;  // code -> samples; ordered, so a tie goes to the lower code
  for (std::size_t k = window.onset; k <= window.end && k < flag.size(); ++k) {
    if (flag[k] != 0.0 && std::isfinite(flag_type[k])) ++shown[static_cast<int>(flag_type[k])];
  }
  int best = 0;
  FaultType type = FaultType::none;
  for (const auto& [code, count] : shown) {
    if (count > best) {
      best = count;
      type = type_of_code(code);
    }
  }
  return type;
}

double readmission_s(std::span<const double> time, std::span<const double> flag, const FaultWindow& window) {
  for (std::size_t k = window.end + 1; k < time.size(); ++k) {
    if (flag[k] == 0.0) return time[k] - time[window.end];
  }
  return kNaN;
}

double loaded_delay_s(std::span<const double> time, std::span<const double> flag, std::span<const double> contact,
                      const FaultWindow& window) {
  double loaded = 0.0;
  for (std::size_t k = window.onset; k < time.size() && k < flag.size(); ++k) {
    if (flag[k] != 0.0) return loaded;
    const bool in_contact = contact.empty() || (k < contact.size() && contact[k] > 0.5);
    if (in_contact && k + 1 < time.size()) loaded += time[k + 1] - time[k];
  }
  return kNaN;
}

FaultShape fault_shape(std::span<const double> time, std::span<const double> measured, std::span<const double> true_force,
                       std::span<const double> true_fault) {
  std::vector<double> size;
  double n = 0.0, st = 0.0, sf = 0.0, stt = 0.0, stf = 0.0;
  const std::size_t count = std::min({time.size(), measured.size(), true_force.size(), true_fault.size()});
  const double t0 = count > 0 ? time.front() : 0.0;  // centred sums: no cancellation at large t
  for (std::size_t k = 0; k < count; ++k) {
    if (true_fault[k] == 0.0) continue;
    const double f = measured[k] - true_force[k];
    if (!std::isfinite(f)) continue;
    const double t = time[k] - t0;
    size.push_back(std::abs(f));
    n += 1.0;
    st += t;
    sf += f;
    stt += t * t;
    stf += t * f;
  }
  FaultShape shape{percentile(size, 0.5), kNaN};
  const double spread = n * stt - st * st;  // n^2 var(t): 0 for fewer than two distinct times
  if (n >= 2.0 && spread > 0.0) shape.slope = (n * stf - st * sf) / spread;
  return shape;
}

FalseAlarms false_alarms(std::span<const double> time, std::span<const double> flag,
                         const std::optional<FaultWindow>& window, const MetricOptions& options) {
  FalseAlarms out;
  if (time.empty()) return out;
  const double t0 = time.front();
  const double dt = time.size() > 1 ? (time.back() - t0) / static_cast<double>(time.size() - 1) : 1e-3;
  // The window reaches readmit_s past the end of a fault that ends before the log does.
  std::size_t grace_end = window ? window->end : 0;
  if (window && window->end + 1 < time.size()) {
    while (grace_end + 1 < time.size() && time[grace_end + 1] - time[window->end] <= options.readmit_s) ++grace_end;
  }
  bool previous = false;
  for (std::size_t k = 0; k < time.size(); ++k) {
    const bool in_window = window && k >= window->onset && k <= grace_end;
    const bool raised = flag[k] != 0.0 && time[k] - t0 >= options.warmup_s && !in_window;
    if (raised && !previous) ++out.count;
    if (raised) out.time_s += dt;
    previous = raised;
  }
  return out;
}

bool ChannelMetrics::detected() const noexcept { return faulty() && std::isfinite(detection_delay_s); }

ChannelMetrics channel_metrics(std::string channel, std::span<const double> time, const ChannelSeries& s,
                               const MetricOptions& options) {
  ChannelMetrics m;
  m.channel = std::move(channel);
  const std::optional<FaultWindow> window = s.true_fault.empty() ? std::nullopt : fault_window(s.true_fault);
  m.onset_s = m.end_s = m.detection_delay_s = m.readmission_s = m.loaded_delay_s = m.fault_size = m.fault_slope = kNaN;
  if (window) {
    m.injected_type = window->injected;
    m.onset_s = time[window->onset];
    m.end_s = time[window->end];
    if (const auto d = first_detection(time, s.fault, s.fault_type, *window)) {
      m.detection_delay_s = d->delay_s;
      m.detected_type = d->type;
    }
    m.shown_type = shown_type(s.fault, s.fault_type, *window);
    m.readmission_s = readmission_s(time, s.fault, *window);
    m.fault_ended = window->end + 1 < time.size();
    m.loaded_delay_s = loaded_delay_s(time, s.fault, s.contact, *window);
    if (!s.true_force.empty()) {
      const FaultShape shape = fault_shape(time, s.measured, s.true_force, s.true_fault);
      m.fault_size = shape.size;
      m.fault_slope = shape.slope;
    }
  }
  const FalseAlarms alarms = false_alarms(time, s.fault, window, options);
  m.false_alarms = alarms.count;
  m.false_alarm_time_s = alarms.time_s;

  std::vector<double> estimate_error, recovered_error, measured_error, vfs_error;
  std::size_t vfs_missing = 0;
  if (!s.true_force.empty()) {
    const double t0 = time.empty() ? 0.0 : time.front();
    for (std::size_t k = 0; k < time.size(); ++k) {
      const double truth = s.true_force[k];
      if (!std::isfinite(truth)) continue;
      const bool after_warmup = time[k] - t0 >= options.warmup_s;
      if (window && k >= window->onset && k <= window->end) {
        if (time[k] - time[window->onset] >= options.settle_s && std::isfinite(s.measured[k])) {
          estimate_error.push_back(s.fault_estimate[k] - (s.measured[k] - truth));
        }
        recovered_error.push_back(s.recovered[k] - truth);
        if (std::isfinite(s.measured[k])) measured_error.push_back(s.measured[k] - truth);
      } else if (!window && after_warmup) {
        recovered_error.push_back(s.recovered[k] - truth);
        if (std::isfinite(s.measured[k])) measured_error.push_back(s.measured[k] - truth);
      }
      if (after_warmup && (s.contact.empty() || s.contact[k] > 0.5)) {
        // A virtual value that is not a number is no estimate (not ready, or cannot judge): it is
        // counted apart, not scored (a NaN would make the RMS NaN and the percentile's order UB).
        if (std::isfinite(s.virtual_value[k])) {
          vfs_error.push_back(std::abs(s.virtual_value[k] - truth));
        } else {
          ++vfs_missing;
        }
      }
    }
  }
  m.fault_estimate_rmse = rms(estimate_error);
  m.recovered_rmse = rms(recovered_error);
  m.measured_rmse = rms(measured_error);
  m.vfs_rmse = rms(vfs_error);
  m.vfs_p95 = percentile(vfs_error, 0.95);
  const std::size_t vfs_samples = vfs_error.size() + vfs_missing;
  m.vfs_missing_share = vfs_samples > 0 ? static_cast<double>(vfs_missing) / static_cast<double>(vfs_samples) : kNaN;
  return m;
}

RunTotals totals(const std::vector<ChannelMetrics>& channels) {
  RunTotals t;
  for (const ChannelMetrics& m : channels) {
    t.faulty_channels += m.faulty();
    t.detected += m.detected();
    t.types_correct += m.type_correct();
    t.false_alarms += m.false_alarms;
  }
  return t;
}

}  // namespace ftsense::report
