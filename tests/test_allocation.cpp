// The per-tick path allocates nothing: a three-stage pipeline over 10,000 ticks, counted with the
// replaced global operator new of ftsense::testing.

#include <cmath>

#include <gtest/gtest.h>

#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/testing/allocation_counter.hpp"
#include "test_configs.hpp"

namespace ftsense {
namespace {

TEST(Allocation, CounterSeesAllocations) {
  // The oracle itself must be able to fail.
  static std::vector<std::unique_ptr<std::vector<int>>> sink;  // escapes: no allocation elision
  testing::AllocationScope scope;
  sink.push_back(std::make_unique<std::vector<int>>(100));
  EXPECT_GE(scope.allocations(), 2u);
}

TEST(Allocation, PipelineTicksAllocateNothing) {
  // Concatenated wires too, so the gather path is covered.
  Json config = test::base_config();
  config["inputs"]["extra"] = Json::parse(R"({"columns": ["e"], "unit": "N"})");
  config["stages"].push_back(Json::parse(R"({"name": "wide", "plugin": "low_pass",
      "inputs": {"signal": ["smooth.filtered", "input.extra"]}})"));
  Pipeline pipeline = Pipeline::build(config, reference_plugins::registry());
  ASSERT_GE(pipeline.stage_count(), 3u);
  pipeline.step(0.0);

  testing::AllocationScope scope;
  for (int k = 1; k <= 10000; ++k) {
    const double t = k * 1e-3;
    for (std::size_t i = 0; i < pipeline.inputs().size(); ++i) {
      for (double& v : pipeline.input_values(i)) v = 100.0 * std::sin(t) + (k > 5000 ? 30.0 : 0.0) * (i == 1);
    }
    pipeline.step(t);
  }
  const std::size_t allocations_while_stepping = scope.allocations();
  // The run did real work: the late +30 N offset on "measured" is flagged on every channel.
  ASSERT_EQ(pipeline.inputs()[1].name, "measured");
  for (double f : pipeline.values(pipeline.monitor()[MonitorColumn::fault])) EXPECT_EQ(f, 1.0);
  pipeline.reset();
  EXPECT_EQ(allocations_while_stepping, 0u);
  EXPECT_EQ(scope.allocations(), 0u) << "reset() allocated";
}

}  // namespace
}  // namespace ftsense
