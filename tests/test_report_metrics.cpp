// The report's metrics (report/include/ftsense/report/metrics.hpp) on small hand-made series,
// with exact expected values.

#include <gtest/gtest.h>

#include <cmath>

#include "ftsense/report/metrics.hpp"
#include "ftsense/report/run_output.hpp"

namespace ftsense::report {
namespace {

// 10 samples at 1 s: easy arithmetic.
const std::vector<double> kTime{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};

TEST(ReportMetrics, RmsAndPercentile) {
  EXPECT_DOUBLE_EQ(rms(std::vector<double>{3, -4}), std::sqrt(12.5));
  EXPECT_TRUE(std::isnan(rms({})));
  EXPECT_EQ(percentile({5, 1, 4, 2, 3}, 0.5), 3.0);
  EXPECT_EQ(percentile({5, 1, 4, 2, 3}, 0.95), 4.0);  // rank floor(0.95 * 4) = 3
  EXPECT_EQ(percentile({5, 1, 4, 2, 3}, 1.0), 5.0);
  EXPECT_TRUE(std::isnan(percentile({}, 0.5)));
}

TEST(ReportMetrics, FaultWindowSpansFirstToLastFaultySample) {
  const std::vector<double> truth{0, 0, 2, 2, 0, 2, 0, 0, 0, 0};
  const auto w = fault_window(truth);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->onset, 2u);
  EXPECT_EQ(w->end, 5u);
  EXPECT_EQ(w->injected, FaultType::offset);
  EXPECT_FALSE(fault_window(std::vector<double>(10, 0.0)).has_value());
}

TEST(ReportMetrics, DetectionTypeShownAndReadmission) {
  const FaultWindow w{2, 5, FaultType::drift};
  const std::vector<double> flag{0, 0, 0, 1, 1, 1, 1, 0, 0, 0};
  const std::vector<double> type{0, 0, 0, 1, 3, 3, 3, 0, 0, 0};
  const auto d = first_detection(kTime, flag, type, w);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->delay_s, 1.0);
  EXPECT_EQ(d->type, FaultType::unclassified);
  EXPECT_EQ(shown_type(flag, type, w), FaultType::drift);  // 2 samples drift vs 1 unclassified
  EXPECT_EQ(readmission_s(kTime, flag, w), 2.0);            // end at t = 5, clear at t = 7
  const std::vector<double> never(10, 0.0);
  EXPECT_FALSE(first_detection(kTime, never, type, w).has_value());
  EXPECT_EQ(shown_type(never, type, w), FaultType::none);
  EXPECT_TRUE(std::isnan(readmission_s(kTime, std::vector<double>(10, 1.0), w)));
}

TEST(ReportMetrics, ATieOfShownTypesGoesToTheLowerCode) {
  const FaultWindow w{0, 3, FaultType::gain};
  const std::vector<double> flag{1, 1, 1, 1};
  const std::vector<double> type{5, 5, 2, 2};
  EXPECT_EQ(shown_type(flag, type, w), FaultType::offset);
}

TEST(ReportMetrics, FalseAlarmsOutsideTheWindowAndGraceAfterWarmup) {
  MetricOptions o;
  o.warmup_s = 2.0;
  o.readmit_s = 1.0;
  // Healthy: a flag during warm-up (t = 1) is not counted; two rising edges after it are.
  const std::vector<double> healthy{0, 1, 0, 1, 1, 0, 0, 1, 0, 0};
  const FalseAlarms a = false_alarms(kTime, healthy, std::nullopt, o);
  EXPECT_EQ(a.count, 2);
  EXPECT_EQ(a.time_s, 3.0);
  // Faulty over [3, 4]: flags within it and within 1 s after it (t = 5) are not false alarms.
  const std::vector<double> faulty{0, 0, 0, 1, 1, 1, 0, 1, 0, 0};
  const FalseAlarms b = false_alarms(kTime, faulty, FaultWindow{3, 4, FaultType::offset}, o);
  EXPECT_EQ(b.count, 1);
  EXPECT_EQ(b.time_s, 1.0);
}

TEST(ReportMetrics, ChannelMetricsOfAnOffsetFault) {
  // truth 100 N; a +10 N offset from t = 3 to t = 6; flagged t = 4..6 as offset; the fault
  // estimate is exact from t = 5; recovered is off by 1 N everywhere in the window.
  const std::vector<double> truth(10, 100.0);
  const std::vector<double> code{0, 0, 0, 2, 2, 2, 2, 0, 0, 0};
  std::vector<double> measured(10, 100.0), estimate(10, 0.0), recovered(10, 100.0);
  for (std::size_t k = 3; k <= 6; ++k) {
    measured[k] = 110.0;
    recovered[k] = 101.0;
  }
  estimate[5] = estimate[6] = 10.0;
  const std::vector<double> virtual_value(10, 104.0);
  const std::vector<double> flag{0, 0, 0, 0, 1, 1, 1, 0, 0, 0};
  const std::vector<double> type{0, 0, 0, 0, 2, 2, 2, 0, 0, 0};
  const std::vector<double> contact{1, 1, 1, 1, 1, 1, 1, 1, 0, 0};
  MetricOptions o;
  o.warmup_s = 2.0;
  o.settle_s = 2.0;
  const ChannelSeries s{measured, virtual_value, estimate, recovered, flag, type, truth, code, contact};
  const ChannelMetrics m = channel_metrics("c1", kTime, s, o);
  EXPECT_EQ(m.injected_type, FaultType::offset);
  EXPECT_EQ(m.onset_s, 3.0);
  EXPECT_EQ(m.end_s, 6.0);
  EXPECT_EQ(m.detection_delay_s, 1.0);
  EXPECT_EQ(m.detected_type, FaultType::offset);
  EXPECT_EQ(m.shown_type, FaultType::offset);
  EXPECT_TRUE(m.type_correct());
  EXPECT_EQ(m.readmission_s, 1.0);
  EXPECT_TRUE(m.fault_ended);
  EXPECT_EQ(m.loaded_delay_s, 1.0);
  EXPECT_EQ(m.fault_size, 10.0);
  EXPECT_DOUBLE_EQ(m.fault_slope, 0.0);
  EXPECT_EQ(m.fault_estimate_rmse, 0.0);  // scored at t = 5, 6 only
  EXPECT_EQ(m.recovered_rmse, 1.0);
  EXPECT_EQ(m.measured_rmse, 10.0);
  EXPECT_EQ(m.false_alarms, 0);
  EXPECT_EQ(m.vfs_rmse, 4.0);  // t = 2..7 in contact after warm-up, |104 - 100|
  EXPECT_EQ(m.vfs_p95, 4.0);
  EXPECT_EQ(m.vfs_missing_share, 0.0);
  // A virtual value that is not a number (cannot judge) is counted apart, not scored: 2 of the 6.
  std::vector<double> virtual_gaps = virtual_value;
  virtual_gaps[3] = virtual_gaps[7] = std::nan("");
  const ChannelSeries gaps{measured, virtual_gaps, estimate, recovered, flag, type, truth, code, contact};
  const ChannelMetrics g = channel_metrics("c1", kTime, gaps, o);
  EXPECT_EQ(g.vfs_rmse, 4.0);
  EXPECT_EQ(g.vfs_p95, 4.0);
  EXPECT_EQ(g.vfs_missing_share, 2.0 / 6.0);
  const RunTotals t = totals({m, channel_metrics("c2", kTime, {truth, truth, truth, truth, std::vector<double>(10, 0.0),
                                                                std::vector<double>(10, 0.0), truth, {}, {}},
                                                  o)});
  EXPECT_EQ(t.faulty_channels, 1);
  EXPECT_EQ(t.detected, 1);
  EXPECT_EQ(t.types_correct, 1);
  EXPECT_EQ(t.false_alarms, 0);
}

TEST(ReportMetrics, LoadedDelayCountsOnlyTheTimeInContact) {
  const FaultWindow w{2, 8, FaultType::offset};
  const std::vector<double> flag{0, 0, 0, 0, 0, 0, 1, 1, 1, 0};
  // Onset t = 2, first flag t = 6: 4 s in all, of which t = 3..4 and 5..6 in contact (2 s).
  const std::vector<double> contact{1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
  EXPECT_EQ(loaded_delay_s(kTime, flag, contact, w), 2.0);
  EXPECT_EQ(loaded_delay_s(kTime, flag, {}, w), 4.0);  // no contact column: the whole delay
  EXPECT_TRUE(std::isnan(loaded_delay_s(kTime, std::vector<double>(10, 0.0), contact, w)));
  const std::vector<double> at_onset{0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(loaded_delay_s(kTime, at_onset, contact, w), 0.0);
}

TEST(ReportMetrics, FaultShapeOfADriftAndOfIntermittentOffsets) {
  // A drift of 3 per s from t = 4 on a truth of 100; a NaN reading is left out.
  std::vector<double> truth(10, 100.0), measured(10, 100.0), code(10, 0.0);
  for (std::size_t k = 4; k < 10; ++k) {
    measured[k] = 100.0 + 3.0 * (kTime[k] - 4.0);
    code[k] = 3.0;
  }
  measured[6] = std::nan("");
  const FaultShape drift = fault_shape(kTime, measured, truth, code);
  EXPECT_DOUBLE_EQ(drift.slope, 3.0);
  EXPECT_EQ(drift.size, 9.0);  // |f| = 0, 3, 9, 12, 15: the median
  // Two bursts of -40 with healthy samples between them: the size is the bursts', not diluted.
  std::vector<double> bursts(10, 100.0), burst_code(10, 0.0);
  for (std::size_t k : {2u, 3u, 7u, 8u}) {
    bursts[k] = 60.0;
    burst_code[k] = 2.0;
  }
  const FaultShape offset = fault_shape(kTime, bursts, truth, burst_code);
  EXPECT_EQ(offset.size, 40.0);
  EXPECT_DOUBLE_EQ(offset.slope, 0.0);
  const FaultShape none = fault_shape(kTime, truth, truth, std::vector<double>(10, 0.0));
  EXPECT_TRUE(std::isnan(none.size));
  EXPECT_TRUE(std::isnan(none.slope));
}

TEST(ReportMetrics, ContactColumnIsFoundByTheChannelsPath) {
  LogTable truth;
  truth.names = {"time_s", "truth/l_foot/contact", "truth/r_foot/p2/contact"};
  truth.columns = {{0.0}, {1.0}, {0.0}};
  EXPECT_EQ(contact_column(truth, "l_foot/p1"), &truth.columns[1]);
  EXPECT_EQ(contact_column(truth, "r_foot/p2"), &truth.columns[2]);  // its own beats its foot's
  EXPECT_EQ(contact_column(truth, "r_foot/p1"), nullptr);
  EXPECT_EQ(contact_column(truth, "lf"), nullptr);
}

}  // namespace
}  // namespace ftsense::report
