// The targets check (report/include/ftsense/report/fdi_targets.hpp) on hand-made metrics.json
// runs: which faults each target applies to, which meet it, and the shortfalls it lists.

#include <gtest/gtest.h>

#include "ftsense/report/fdi_targets.hpp"

namespace ftsense::report {
namespace {

Json channel(const std::string& name, const std::string& injected, const Json& fields) {
  Json c = {{"channel", name}, {"injected_type", injected}};
  c.update(fields);
  return c;
}

const TargetCheck& find(const std::vector<TargetCheck>& checks, const std::string& prefix) {
  for (const TargetCheck& c : checks) {
    if (c.target.rfind(prefix, 0) == 0) return c;
  }
  throw std::runtime_error("no target " + prefix);
}

std::vector<ScoredRunMetrics> runs() {
  Json faults = {{"summary", {{"false_alarms_after_warmup", 1}}}, {"channels", Json::array()}};
  auto& ch = faults["channels"];
  // A 150 N offset seen after 0.3 s of loaded time, recovered 20 N; never re-admitted.
  ch.push_back(channel("a", "offset", {{"fault_size", 150.0}, {"loaded_delay_s", 0.3}, {"detection_delay_s", 0.9},
                                       {"type_correct", true}, {"shown_type", "offset"}, {"recovered_rmse", 20.0},
                                       {"fault_ended", true}, {"readmission_s", nullptr}}));
  // A 25 N offset (below the 40 N the target applies to), missed.
  ch.push_back(channel("b", "offset", {{"fault_size", 25.0}, {"loaded_delay_s", nullptr}, {"detection_delay_s", nullptr},
                                       {"type_correct", false}, {"shown_type", "-"}, {"recovered_rmse", 25.0},
                                       {"fault_ended", true}}));
  // A frozen channel in time, re-admitted 0.2 s after it ends.
  ch.push_back(channel("c", "frozen", {{"loaded_delay_s", 0.01}, {"detection_delay_s", 0.01}, {"type_correct", true},
                                       {"shown_type", "frozen"}, {"recovered_rmse", 10.0}, {"fault_ended", true},
                                       {"readmission_s", 0.2}}));
  // Drifts: -16 N/s after 2.5 s (limit 2 s), 6 N/s after 3 s (limit 5 s), 3 N/s (no limit).
  ch.push_back(channel("d", "drift", {{"fault_slope_per_s", -16.0}, {"detection_delay_s", 2.5}, {"type_correct", true},
                                      {"shown_type", "drift"}, {"recovered_rmse", 5.0}, {"fault_ended", false}}));
  ch.push_back(channel("e", "drift", {{"fault_slope_per_s", 6.0}, {"detection_delay_s", 3.0}, {"type_correct", false},
                                      {"shown_type", "offset"}, {"recovered_rmse", 5.0}, {"fault_ended", true},
                                      {"readmission_s", 0.7}}));
  ch.push_back(channel("f", "drift", {{"fault_slope_per_s", 3.0}, {"detection_delay_s", 9.0}, {"type_correct", true},
                                      {"shown_type", "drift"}, {"recovered_rmse", 5.0}, {"fault_ended", false}}));
  ch.push_back(channel("g", "-", {{"false_alarms", 1}}));
  Json quiet = {{"summary", {{"false_alarms_after_warmup", 0}}}};
  Json noisy = {{"summary", {{"false_alarms_after_warmup", 2}}}, {"channels", Json::array()}};
  Json unscored = {{"summary", {{"scored", false}}}};  // no truth: neither met nor missed
  return {{"faults", faults}, {"clean", quiet}, {"clean_200hz", noisy}, {"real_log", unscored}};
}

TEST(FdiTargets, EachTargetCountsTheFaultsItAppliesToAndListsTheMisses) {
  const std::vector<TargetCheck> checks = check_targets(runs());
  ASSERT_EQ(checks.size(), 7u);

  const TargetCheck& detect = find(checks, "offsets of 40 N or more");
  EXPECT_EQ(detect.checked, 2);  // a (150 N) and c (frozen); b is under 40
  EXPECT_EQ(detect.met, 1);
  EXPECT_FALSE(detect.passed);
  ASSERT_EQ(detect.shortfalls.size(), 1u);
  EXPECT_EQ(detect.shortfalls[0], "faults a (offset 150): 0.300 s");

  const TargetCheck& drift = find(checks, "drifts");
  EXPECT_EQ(drift.checked, 2);  // f at 3 N/s has no limit
  EXPECT_EQ(drift.met, 1);
  ASSERT_EQ(drift.shortfalls.size(), 1u);
  EXPECT_EQ(drift.shortfalls[0], "faults d (drift) 16.0 N/s: 2.500 s (limit 2 s)");

  const TargetCheck& type = find(checks, "fault type");
  EXPECT_EQ(type.checked, 6);
  EXPECT_EQ(type.met, 4);
  EXPECT_FALSE(type.passed);  // 4/6 < 95 %
  EXPECT_EQ(type.shortfalls[0], "faults b (offset): shown -");

  const TargetCheck& recovered = find(checks, "recovered RMSE");
  EXPECT_EQ(recovered.checked, 6);
  EXPECT_EQ(recovered.met, 4);
  EXPECT_EQ(recovered.shortfalls[1], "faults b (offset): 25.0 N");

  const TargetCheck& readmitted = find(checks, "re-admitted");
  EXPECT_EQ(readmitted.checked, 3);  // a, c, e: detected and ended (b is missed)
  EXPECT_EQ(readmitted.met, 1);
  EXPECT_EQ(readmitted.shortfalls[0], "faults a (offset): never");
  EXPECT_EQ(readmitted.shortfalls[1], "faults e (drift): 0.700 s");

  const TargetCheck& quiet = find(checks, "no false alarm on fault-free");
  EXPECT_EQ(quiet.checked, 2);
  EXPECT_EQ(quiet.met, 1);
  EXPECT_EQ(quiet.shortfalls[0], "clean_200hz: 2");
  const TargetCheck& quiet_faulty = find(checks, "no false alarm on runs with faults");
  EXPECT_EQ(quiet_faulty.checked, 1);
  EXPECT_EQ(quiet_faulty.met, 0);
}

TEST(FdiTargets, TheTypeShareHoldsAtNinetyFivePercent) {
  Json run = {{"summary", {{"false_alarms_after_warmup", 0}}}, {"channels", Json::array()}};
  for (int i = 0; i < 20; ++i) {
    std::string name = "c";
    name += std::to_string(i);
    run["channels"].push_back(channel(name, "spikes",
                                      {{"type_correct", i != 0}, {"shown_type", i != 0 ? "spikes" : "noise"}}));
  }
  EXPECT_TRUE(find(check_targets({{"r", run}}), "fault type").passed);  // 19/20
  run["channels"][1]["type_correct"] = false;
  EXPECT_FALSE(find(check_targets({{"r", run}}), "fault type").passed);  // 18/20
}

TEST(FdiTargets, TableHasARowPerTarget) {
  const Table t = targets_table(check_targets(runs()));
  ASSERT_EQ(t.rows.size(), 7u);
  EXPECT_EQ(t.rows[0][1], "2");
  EXPECT_EQ(t.rows[0][2], "1");
  EXPECT_EQ(t.rows[0][3], "no");
  EXPECT_EQ(t.rows[0][4], "faults a (offset 150): 0.300 s");
  EXPECT_EQ(t.rows[5][4], "clean_200hz: 2");
}

}  // namespace
}  // namespace ftsense::report
