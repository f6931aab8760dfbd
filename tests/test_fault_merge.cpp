// fault_merge: exact merged flags, types, sources and "cannot judge" on small cases; the type order
// (default and the user's); config errors that name the entry to fix.

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/fault_merge.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::FaultMerge> {
  static Json params() { return {{"cannot_judge", true}}; }
  static std::size_t input_dim(std::string_view port) { return port == "cannot_judge" ? 3 : 6; }
  static void nominal_input(std::string_view port, std::span<double> v) {
    // Source 1 flags channel 0 as noise, source 2 flags channel 1 as an offset.
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = 0.0;
    if (port == "fault") v[0] = v[4] = 1.0;
    if (port == "fault_type") {
      v[0] = fault_code(FaultType::noise);
      v[4] = fault_code(FaultType::offset);
    }
  }
  static double sample_period_s() { return 1e-3; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(Merge, PluginContract, ::testing::Types<generic::FaultMerge>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::FaultMerge;
constexpr double kNotANumber = std::numeric_limits<double>::quiet_NaN();

struct Merged {
  std::vector<double> fault, type, source, cannot_judge;
};

double code(FaultType t) { return fault_code(t); }

// One step; `flags` and `types` hold the sources one after another.
Merged merge_once(const FaultMerge::Params& p, const std::vector<double>& flags, const std::vector<double>& types,
                  const std::vector<double>& cannot_judge = {}) {
  const std::size_t channels = flags.size() / static_cast<std::size_t>(p.sources);
  std::vector<std::pair<std::string, std::size_t>> dims{{"fault", flags.size()}, {"fault_type", types.size()}};
  if (p.cannot_judge) dims.emplace_back("cannot_judge", channels);
  FaultMerge stage(p, StageContext(1e-3, "merge", dims));
  stage.reset();
  Merged m{std::vector<double>(channels, -1.0), std::vector<double>(channels, -1.0),
           std::vector<double>(channels, -1.0), std::vector<double>(channels, -1.0)};
  std::vector<std::span<const double>> ins{flags, types};
  if (p.cannot_judge) ins.emplace_back(cannot_judge);
  std::vector<std::span<double>> outs{m.fault, m.type, m.source};
  if (p.cannot_judge) outs.emplace_back(m.cannot_judge);
  stage.step(StepIO{0.0, ins, outs});
  return m;
}

TEST(FaultMerge, NothingFlaggedIsHealthy) {
  const Merged m = merge_once({}, {0, 0, 0, 0}, {code(FaultType::none), 0, 0, 0});
  EXPECT_EQ(m.fault, (std::vector<double>{0, 0}));
  EXPECT_EQ(m.type, (std::vector<double>{code(FaultType::none), code(FaultType::none)}));
  EXPECT_EQ(m.source, (std::vector<double>{0, 0}));
}

TEST(FaultMerge, TheMostSpecificTypeOfTheFlaggingSourcesIsTaken) {
  // Three channels, two sources (a validator, then an isolator with its classifier):
  //   ch 0: noise (1) and gain (2)   -> gain, from source 2 (a gain raises the noise too)
  //   ch 1: only source 2, offset    -> offset, source 2
  //   ch 2: spikes (1), unclassified -> spikes, source 1 (a named type before an unknown one)
  const Merged m = merge_once({}, {1, 0, 1, /**/ 1, 1, 1},
                              {code(FaultType::noise), code(FaultType::none), code(FaultType::spikes),  //
                               code(FaultType::gain), code(FaultType::offset), code(FaultType::unclassified)});
  EXPECT_EQ(m.fault, (std::vector<double>{1, 1, 1}));
  EXPECT_EQ(m.type, (std::vector<double>{code(FaultType::gain), code(FaultType::offset), code(FaultType::spikes)}));
  EXPECT_EQ(m.source, (std::vector<double>{2, 2, 1}));
}

TEST(FaultMerge, DefaultOrderPutsCertainEvidenceFirst) {
  // Each pair: source 1 names the first type, source 2 the second; the merged type is the first.
  const std::vector<std::pair<FaultType, FaultType>> pairs{
      {FaultType::invalid, FaultType::saturation}, {FaultType::saturation, FaultType::frozen},
      {FaultType::frozen, FaultType::gain},        {FaultType::gain, FaultType::drift},
      {FaultType::drift, FaultType::offset},       {FaultType::offset, FaultType::noise},
      {FaultType::noise, FaultType::spikes},       {FaultType::spikes, FaultType::unclassified}};
  for (const auto& [first, second] : pairs) {
    for (const bool swapped : {false, true}) {
      const FaultType a = swapped ? second : first, b = swapped ? first : second;
      const Merged m = merge_once({}, {1, 1}, {code(a), code(b)});
      EXPECT_EQ(m.type[0], code(first)) << to_string(first) << " before " << to_string(second);
      EXPECT_EQ(m.source[0], swapped ? 2.0 : 1.0);
    }
  }
}

TEST(FaultMerge, AFlagWithoutATypeIsUnclassifiedAndANaNFlagIsNoFlag) {
  // ch 0: flagged with code none; ch 1: flagged with a code that is no type (42);
  // ch 2: flag NaN with a type (not a flag); ch 3: flag Inf (not a flag).
  const Merged m = merge_once({}, {1, 1, kNotANumber, std::numeric_limits<double>::infinity(), 0, 0, 0, 0},
                              {code(FaultType::none), 42.0, code(FaultType::offset), code(FaultType::offset),  //
                               0, 0, 0, 0});
  EXPECT_EQ(m.fault, (std::vector<double>{1, 1, 0, 0}));
  EXPECT_EQ(m.type, (std::vector<double>{code(FaultType::unclassified), code(FaultType::unclassified),
                                         code(FaultType::none), code(FaultType::none)}));
  EXPECT_EQ(m.source, (std::vector<double>{1, 1, 0, 0}));
}

TEST(FaultMerge, EqualTypesTakeTheFirstSourceAndThreeSourcesMerge) {
  FaultMerge::Params p;
  p.sources = 3;
  // ch 0: drift from sources 2 and 3 -> source 2; ch 1: only source 3, frozen.
  const Merged m = merge_once(p, {0, 0, 1, 0, 1, 1},
                              {0, 0, code(FaultType::drift), 0, code(FaultType::drift), code(FaultType::frozen)});
  EXPECT_EQ(m.type, (std::vector<double>{code(FaultType::drift), code(FaultType::frozen)}));
  EXPECT_EQ(m.source, (std::vector<double>{2, 3}));
}

TEST(FaultMerge, TheUsersOrderComesFirstThenTheOtherTypesInCodeOrder) {
  FaultMerge::Params p;
  p.type_priority = {"noise"};
  // ch 0: noise vs gain -> noise (listed); ch 1: gain (code 5) vs spikes (code 7) -> gain, code order;
  // ch 2: unclassified vs gain (unlisted) -> gain: a named type before an unknown one.
  const Merged m = merge_once(p, {1, 1, 1, 1, 1, 1},
                              {code(FaultType::noise), code(FaultType::spikes), code(FaultType::unclassified),
                               code(FaultType::gain), code(FaultType::gain), code(FaultType::gain)});
  EXPECT_EQ(m.type, (std::vector<double>{code(FaultType::noise), code(FaultType::gain), code(FaultType::gain)}));
  EXPECT_EQ(m.source, (std::vector<double>{1, 2, 2}));
}

TEST(FaultMerge, CannotJudgeHoldsOnlyWhileNoSourceFlagsTheChannel) {
  FaultMerge::Params p;
  p.cannot_judge = true;
  // ch 0: cannot judge, unflagged -> 1; ch 1: cannot judge but source 1 flags it -> 0;
  // ch 2: judged -> 0; ch 3: NaN -> 0; ch 4: 0.5 (nonzero) -> 1; ch 5: Inf -> 0.
  const double inf = std::numeric_limits<double>::infinity();
  const Merged m = merge_once(p, {0, 1, 0, 0, 0, 0, /**/ 0, 0, 0, 0, 0, 0},
                              {0, code(FaultType::invalid), 0, 0, 0, 0, /**/ 0, 0, 0, 0, 0, 0}, {1, 1, 0, kNotANumber, 0.5, inf});
  EXPECT_EQ(m.cannot_judge, (std::vector<double>{1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(m.type[1], code(FaultType::invalid));
}

TEST(FaultMerge, ConfigErrorsNameTheEntryToFix) {
  {
    Diagnostics d;
    (void)load_params<FaultMerge::Params>(Json::parse(R"({"type_priority": ["frozn", "gain", "gain", "none"]})"),
                                          "/stages/6/params", "fault_merge", d);
    ASSERT_EQ(d.errors().size(), 3u);
    EXPECT_EQ(d.errors()[0].path, "/stages/6/params/type_priority/0");
    EXPECT_NE(d.errors()[0].message.find("did you mean 'frozen'?"), std::string::npos);
    EXPECT_EQ(d.errors()[1].path, "/stages/6/params/type_priority/2");
    EXPECT_NE(d.errors()[1].message.find("twice"), std::string::npos);
    EXPECT_EQ(d.errors()[2].path, "/stages/6/params/type_priority/3");
  }
  {
    Diagnostics d;
    (void)load_params<FaultMerge::Params>(Json::parse(R"({"sources": 1})"), "/stages/6/params", "fault_merge", d);
    ASSERT_EQ(d.errors().size(), 1u);
    EXPECT_EQ(d.errors()[0].path, "/stages/6/params/sources");
  }
  FaultMerge::Params p;
  p.sources = 3;
  EXPECT_THROW(FaultMerge(p, StageContext(1e-3, "merge", {{"fault", 4}, {"fault_type", 4}})), ConfigError);
}

}  // namespace
}  // namespace ftsense
