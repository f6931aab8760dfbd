#pragma once
// Metrics of a run against the ground truth, as pure functions of the per-sample series.
//
// Per channel (docs/results.md repeats these definitions):
//   - fault window [onset, end]: first and last sample whose truth fault code is not 0; the
//     injected type is the code at onset; injected fault = measured - truth;
//   - detection delay: first flag at or after onset, minus onset (missed: no flag before the end
//     of the log); the detected type is the fault_type output at that sample;
//   - type shown: the fault type the channel shows most while the fault is active and flagged
//     (ties: the lower code);
//   - fault estimate error: RMS of (fault_estimate - injected) from onset + settle_s to the end
//     of the fault (settle_s = 5 s = 5 time constants of the paper's filter);
//   - recovered RMSE: RMS of (recovered - truth) from onset to the end of the fault, or over the
//     whole run after warm-up for a healthy channel; measured RMSE the same for the reading;
//   - re-admission: seconds from the end of a fault that ends before the log does until the flag
//     clears (the goal is under 1 s);
//   - loaded delay: the part of the detection delay during which the channel was in contact (the
//     truth's contact column; the whole delay when there is none): a fault that begins in the air
//     has until the landing plus the delay to be seen;
//   - fault size: median of |injected fault| over the faulty samples (those with a truth fault
//     code); fault slope: least-squares slope of the injected fault on time over them (a drift's
//     rate, in the run's unit per second);
//   - false alarms: rising edges of the flag after warm-up outside [onset, end + readmit_s];
//     false-alarm time: samples flagged there times the mean sample period;
//   - VFS error: RMS and 95th percentile of |virtual - truth| after warm-up while the channel is
//     in contact (every sample when the log has no contact column for it).
// Times in s; errors in the run's unit. NaN stands for "not defined" (no fault, missed, ...).

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "ftsense/fault_type.hpp"

namespace ftsense::report {

struct MetricOptions {
  double warmup_s = 2.0;   // no false alarm and no healthy error counted before this time
  double settle_s = 5.0;   // the fault estimate is scored from this long after onset
  double readmit_s = 1.0;  // a flag this long after a fault ends is not a false alarm
};

// Root mean square; NaN for no samples.
[[nodiscard]] double rms(std::span<const double> values);
// The p-quantile (0..1) by the nearest lower rank; NaN for no samples.
[[nodiscard]] double percentile(std::vector<double> values, double p);

struct FaultWindow {
  std::size_t onset = 0;  // first faulty sample
  std::size_t end = 0;    // last faulty sample (inclusive)
  FaultType injected = FaultType::none;
};
// The window of the injected fault from truth fault codes; nullopt for a healthy channel.
[[nodiscard]] std::optional<FaultWindow> fault_window(std::span<const double> true_fault);

struct Detection {
  double delay_s = 0.0;
  FaultType type = FaultType::none;  // the fault_type output when first flagged
};
// The first flag at or after onset; nullopt when the fault is missed.
[[nodiscard]] std::optional<Detection> first_detection(std::span<const double> time, std::span<const double> flag,
                                                       std::span<const double> flag_type, const FaultWindow& window);

// The type flagged most within the window (none when never flagged there).
[[nodiscard]] FaultType shown_type(std::span<const double> flag, std::span<const double> flag_type,
                                   const FaultWindow& window);

// Seconds in contact (contact > 0.5; every sample when `contact` is empty) from the onset until
// the flag is first raised; NaN when it never is.
[[nodiscard]] double loaded_delay_s(std::span<const double> time, std::span<const double> flag,
                                    std::span<const double> contact, const FaultWindow& window);

struct FaultShape {
  double size = 0.0;   // median |measured - truth| over the faulty samples
  double slope = 0.0;  // least-squares slope of (measured - truth) on time over them, per s
};
// The injected fault's size and slope over the samples with a nonzero truth fault code and a
// finite reading (NaN where there are too few: none for the size, under two for the slope).
[[nodiscard]] FaultShape fault_shape(std::span<const double> time, std::span<const double> measured,
                                     std::span<const double> true_force, std::span<const double> true_fault);

// Seconds from the end of the fault until the flag clears; NaN when the fault lasts to the end
// of the log or the flag never clears.
[[nodiscard]] double readmission_s(std::span<const double> time, std::span<const double> flag,
                                   const FaultWindow& window);

struct FalseAlarms {
  int count = 0;        // rising edges
  double time_s = 0.0;  // time flagged
};
// Flags after warm-up outside the fault window and its re-admission grace.
[[nodiscard]] FalseAlarms false_alarms(std::span<const double> time, std::span<const double> flag,
                                       const std::optional<FaultWindow>& window, const MetricOptions& options);

// Every series of one channel, each as long as the run's time column; truth series are empty
// when there is no truth, `contact` when the truth has no contact column for the channel.
struct ChannelSeries {
  std::span<const double> measured, virtual_value, fault_estimate, recovered, fault, fault_type;
  std::span<const double> true_force, true_fault, contact;
};

struct ChannelMetrics {
  std::string channel;
  FaultType injected_type = FaultType::none;  // none: healthy
  double onset_s = 0.0, end_s = 0.0;          // NaN: healthy
  double detection_delay_s = 0.0;             // NaN: missed or healthy
  FaultType detected_type = FaultType::none;
  FaultType shown_type = FaultType::none;
  double fault_estimate_rmse = 0.0;
  double recovered_rmse = 0.0;
  double readmission_s = 0.0;
  bool fault_ended = false;      // the fault's last sample is before the log's last sample
  double loaded_delay_s = 0.0;   // NaN: missed or healthy
  double fault_size = 0.0;       // NaN: healthy, or no finite reading while faulty
  double fault_slope = 0.0;      // per s; NaN: fewer than two faulty samples with a reading
  int false_alarms = 0;
  double false_alarm_time_s = 0.0;
  // |virtual - truth| in contact after the warm-up, over the samples with a virtual value; the
  // share of those samples without one (NaN: not ready, or the relation cannot judge).
  double vfs_rmse = 0.0, vfs_p95 = 0.0;
  double vfs_missing_share = 0.0;
  double measured_rmse = 0.0;  // |measured - truth| over the same samples as recovered_rmse

  [[nodiscard]] bool faulty() const noexcept { return injected_type != FaultType::none; }
  [[nodiscard]] bool detected() const noexcept;
  [[nodiscard]] bool type_correct() const noexcept { return faulty() && shown_type == injected_type; }
};

[[nodiscard]] ChannelMetrics channel_metrics(std::string channel, std::span<const double> time,
                                             const ChannelSeries& series, const MetricOptions& options);

struct RunTotals {
  int faulty_channels = 0;
  int detected = 0;
  int types_correct = 0;
  int false_alarms = 0;
};
[[nodiscard]] RunTotals totals(const std::vector<ChannelMetrics>& channels);

}  // namespace ftsense::report
