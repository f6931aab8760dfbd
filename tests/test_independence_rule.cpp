// The independence rule alone (independence_rule.hpp): dependence sets, the leave-one-out
// exception and the message, with exact expected values.

#include <gtest/gtest.h>

#include "ftsense/independence_rule.hpp"

namespace ftsense {
namespace {

using Names = std::set<std::string>;

TEST(IndependenceRule, AnInputDependsOnWhatItIsDerivedFromTransitively) {
  const std::vector<InputDerivation> inputs{{"zmp", {"forces"}}, {"forces", {"cells"}}, {"cells", {}}, {"imu", {}}};
  EXPECT_EQ(input_dependencies("zmp", inputs), (Names{"cells", "forces", "zmp"}));
  EXPECT_EQ(input_dependencies("imu", inputs), (Names{"imu"}));
  // A cycle of derivations ends instead of recursing for ever.
  const std::vector<InputDerivation> loop{{"a", {"b"}}, {"b", {"a"}}};
  EXPECT_EQ(input_dependencies("a", loop), (Names{"a", "b"}));
}

TEST(IndependenceRule, AVirtualSignalSharingASensorBreaksTheRule) {
  WireDependence virtual_wire;
  virtual_wire.add({{"imu", "forces"}, {}});
  EXPECT_EQ(virtual_wire.shared_with({"forces"}), (Names{"forces"}));
  EXPECT_TRUE(virtual_wire.shared_with({"encoders"}).empty());
}

TEST(IndependenceRule, ALeaveOneOutEstimateOfExactlyTheMeasuredSignalIsIndependent) {
  WireDependence loo;
  loo.add({{"cells", "imu"}, {"cells"}});
  EXPECT_TRUE(loo.shared_with({"cells"}).empty());
  // Judged against another signal made of the same sensors, it is not exempt.
  EXPECT_EQ(loo.shared_with({"cells", "imu"}), (Names{"cells", "imu"}));
}

TEST(IndependenceRule, AWireMixingALeaveOneOutOutputWithAnOrdinaryOneIsNotExempt) {
  WireDependence mixed;
  mixed.add({{"cells"}, {"cells"}});
  mixed.add({{"cells"}, {}});
  EXPECT_EQ(mixed.shared_with({"cells"}), (Names{"cells"}));
}

TEST(IndependenceRule, TheMessageNamesTheSharedInputsAndWhatToDo) {
  EXPECT_EQ(independence_breach("'virtual' of stage 'r'", "'measured'", {"a"}),
            "independence rule: the virtual sensor 'virtual' of stage 'r' is computed from input 'a', which is "
            "what 'measured' measures; a fault of that sensor would leak into its own reference (method.md "
            "section 0). Feed the virtual sensor from other signals (planned ZMP, kinematics)");
  EXPECT_NE(independence_breach("v", "m", {"a", "b"}).find("computed from inputs 'a', 'b', which"), std::string::npos);
}

}  // namespace
}  // namespace ftsense
