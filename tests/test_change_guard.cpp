// change_guard: the guard rises on the tick a state changes and holds exactly hold_s; any and own
// scopes; an unknown state counts as a change. With signal_validator's guard input, a landing's
// one-sample transient at 200 Hz is no spike while a spike between transients still is.

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/fault_type.hpp"
#include "ftsense/generic/change_guard.hpp"
#include "ftsense/generic/signal_validator.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
template <>
struct ContractSetup<generic::ChangeGuard> {
  static Json params() { return Json::object(); }
  static std::size_t input_dim(std::string_view) { return 3; }
  static void nominal_input(std::string_view, std::span<double> v) {
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = i % 2 == 0 ? 1.0 : 0.0;
  }
  static double sample_period_s() { return 1e-3; }
};
INSTANTIATE_TYPED_TEST_SUITE_P(Guard, PluginContract, ::testing::Types<generic::ChangeGuard>);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using generic::ChangeGuard;

TEST(ChangeGuard, HoldsExactlyHoldSecondsAfterAChangeInScope) {
  // Two contact flags at 1 kHz, hold_s = 3 ms: channel 0 lands at tick 2, channel 1 lifts at tick
  // 8, channel 0 reads NaN at tick 14 (unknown: a change) and 1 again at tick 15 (back from
  // unknown: a change). any: both channels guarded on ticks 2-4, 8-10, 14-17; own: each on its own.
  for (const auto scope : {ChangeGuard::Scope::any, ChangeGuard::Scope::own}) {
    ChangeGuard::Params p;
    p.hold_s = 0.003;
    p.scope = scope;
    ChangeGuard guard(p, StageContext(1e-3, "g", {{"state", 2}}));
    guard.reset();
    std::vector<double> state{0.0, 1.0}, out{0.0, 0.0};
    const std::span<const double> ins[] = {state};
    const std::span<double> outs[] = {out};
    for (int k = 0; k < 20; ++k) {
      state[0] = k < 2 ? 0.0 : k == 14 ? std::nan("") : 1.0;
      state[1] = k < 8 ? 1.0 : 0.0;
      guard.step(StepIO{k * 1e-3, ins, outs});
      const bool own0 = (k >= 2 && k <= 4) || (k >= 14 && k <= 17);
      const bool own1 = k >= 8 && k <= 10;
      const bool any = own0 || own1;
      const bool is_any = scope == ChangeGuard::Scope::any;
      EXPECT_EQ(out[0], (is_any ? any : own0) ? 1.0 : 0.0) << "tick " << k;
      EXPECT_EQ(out[1], (is_any ? any : own1) ? 1.0 : 0.0) << "tick " << k;
    }
  }
}

TEST(ChangeGuard, ASmallChangeWithinToleranceIsNone) {
  ChangeGuard::Params p;
  p.hold_s = 0.002;
  p.tolerance = 0.5;
  ChangeGuard guard(p, StageContext(1e-3, "g", {{"state", 1}}));
  guard.reset();
  std::vector<double> state{0.0}, out{0.0};
  const std::span<const double> ins[] = {state};
  const std::span<double> outs[] = {out};
  const double values[] = {0.0, 0.3, 0.6, 0.6, 0.6, 1.2, 1.2};
  const double expected[] = {0, 0, 0, 0, 0, 1, 1};  // 0.3 per tick is within 0.5; 0.6 is not
  for (int k = 0; k < 7; ++k) {
    state[0] = values[k];
    guard.step(StepIO{k * 1e-3, ins, outs});
    EXPECT_EQ(out[0], expected[k]) << "tick " << k;
  }
}

TEST(ChangeGuard, AHoldOfUnderHalfATickIsAConfigError) {
  ChangeGuard::Params p;
  p.hold_s = 0.002;  // 0.4 ticks at 200 Hz: no tick would be guarded
  EXPECT_THROW(ChangeGuard(p, StageContext(0.005, "g", {{"state", 1}})), ConfigError);
  p.hold_s = 0.0025;  // half a tick rounds to one (round half away from zero)
  EXPECT_NO_THROW(ChangeGuard(p, StageContext(0.005, "g", {{"state", 1}})));
}

TEST(ChangeGuard, ALandingsTransientIsNoSpikeButASpikeBetweenTransientsIs) {
  // A foot's load at 200 Hz (window 0.1 s: 20 ticks), noise sigma 0.5 N: in the air (0 N) until tick
  // 40, then a landing whose impact peak is one sample (30 at tick 40, 80 at 41, then 30.2, 30.3
  // ...: 80 is off both neighbours like a spike), a spike of 40 N at tick 100. The contact flag lands at tick 40 and
  // change_guard (hold_s 0.05 s: 10 ticks) guards ticks 40-49: the peak is no spike; the spike at
  // tick 100 is flagged one tick late, for spike_hold_s (0.1 s). Without the guard the landing is a
  // spike.
  constexpr unsigned kSeed = 31;
  std::printf("seed %u\n", kSeed);
  for (const bool with_guard : {true, false}) {
    generic::SignalValidator::Params vp;
    vp.noise_std = {0.5};
    vp.tests = {"spikes", "noise"};
    vp.spike_hold_s = 0.1;  // a lone spike's hold: one window
    vp.guard = with_guard;
    const double period = 0.005;
    generic::SignalValidator validator(
        vp, StageContext(period, "v",
                         with_guard ? std::vector<std::pair<std::string, std::size_t>>{{"signal", 1}, {"guard", 1}}
                                    : std::vector<std::pair<std::string, std::size_t>>{{"signal", 1}}));
    validator.reset();
    ChangeGuard::Params gp;
    gp.hold_s = 0.05;
    ChangeGuard guard(gp, StageContext(period, "g", {{"state", 1}}));
    guard.reset();
    std::mt19937_64 rng(kSeed);
    std::normal_distribution<double> noise(0.0, 0.5);
    std::vector<double> x{0.0}, contact{0.0}, g{0.0}, fault{0.0}, type{0.0};
    int landing_flags = 0;
    for (int k = 0; k < 160; ++k) {
      contact[0] = k >= 40 ? 1.0 : 0.0;
      const double load = k < 40 ? 0.0 : k == 41 ? 80.0 : 30.0 + 0.1 * (k - 40);
      x[0] = load + noise(rng) + (k == 100 ? 40.0 : 0.0);
      const std::span<const double> gin[] = {contact};
      const std::span<double> gout[] = {g};
      guard.step(StepIO{k * period, gin, gout});
      const std::span<double> outs[] = {fault, type};
      if (with_guard) {
        const std::span<const double> ins[] = {x, g};
        validator.step(StepIO{k * period, ins, outs});
      } else {
        const std::span<const double> ins[] = {x};
        validator.step(StepIO{k * period, ins, outs});
      }
      const auto found = static_cast<FaultType>(static_cast<int>(type[0]));
      if (k < 100) {
        landing_flags += found != FaultType::none;
        if (with_guard) {
          ASSERT_EQ(found, FaultType::none) << "tick " << k;
        }
      } else {
        ASSERT_EQ(found, k >= 101 && k < 121 ? FaultType::spikes : FaultType::none) << "guard " << with_guard << ", tick " << k;
      }
    }
    if (!with_guard) {
      EXPECT_GT(landing_flags, 0);
    }
  }
}

}  // namespace
}  // namespace ftsense
