// limb_inertia_correction: exact values on feet and trunk in uniform acceleration (the
// second difference of a doubly low-passed parabola is the parabola's once the filters' start
// has decayed), at two rates, and its refusals.

#include <cmath>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/biped/limb_inertia_correction.hpp"

namespace ftsense::biped {
namespace {

struct Stage {
  LimbInertiaCorrection plugin;
  std::vector<double> force = std::vector<double>(3, 0.0);
  std::vector<double> feet;
  std::vector<double> out = std::vector<double>(3, 0.0);
  Stage(const LimbInertiaCorrection::Params& p, double period_s, std::size_t feet_count)
      : plugin(p, StageContext(period_s, "legs", {{"foot_pos", 3 * feet_count}})), feet(3 * feet_count, 0.0) {
    plugin.reset();
  }
  void step(double t) {
    const std::span<const double> ins[] = {force, feet};
    std::vector<std::span<double>> outs = {out};
    plugin.step(StepIO{t, ins, outs});
  }
};

LimbInertiaCorrection::Params legs(double leg_effective_mass_kg) {
  LimbInertiaCorrection::Params p;
  p.mass_kg = 114.0;
  p.leg_effective_mass_kg = leg_effective_mass_kg;
  p.cutoff_hz = 10.0;
  return p;
}

// Trunk accelerating up at a_t (F = M (a_t + g) e_z), foot 0 at a_t + a_z up and a_x forward,
// foot 1 moving with the trunk, for 3 s at period T: the last output.
std::vector<double> uniform_acceleration(double leg_effective_mass_kg, double period_s, double a_t, double a_z, double a_x) {
  Stage s(legs(leg_effective_mass_kg), period_s, 2);
  const int ticks = static_cast<int>(std::lround(3.0 / period_s));
  for (int k = 0; k <= ticks; ++k) {
    const double t = k * period_s;
    s.force = {0.0, 0.0, 114.0 * (a_t + 9.806)};
    s.feet = {0.5 * a_x * t * t, 0.1, 0.5 * (a_t + a_z) * t * t, 0.0, -0.1, 0.5 * a_t * t * t};
    s.step(t);
  }
  return s.out;
}

TEST(LimbInertiaCorrection, AddsTheLegsAccelerationBeyondTheTrunks) {
  // Foot 0 accelerates 3 m/s^2 up and 2 m/s^2 forward beyond the trunk (which accelerates 1 m/s^2
  // up), foot 1 with the trunk: F' = F + 16 kg x (2, 0, 3) m/s^2. The filters' start decays as
  // 0.939^k over 3000 ticks; the positions' rounding (metres, second differences of 1e-6 of them)
  // leaves about 1e-8 N.
  for (const double period : {1e-3, 5e-3}) {
    SCOPED_TRACE("T = " + std::to_string(period));
    const auto out = uniform_acceleration(16.0, period, 1.0, 3.0, 2.0);
    EXPECT_NEAR(out[0], 16.0 * 2.0, 1e-6);
    EXPECT_NEAR(out[1], 0.0, 1e-6);
    EXPECT_NEAR(out[2], 114.0 * (1.0 + 9.806) + 16.0 * 3.0, 1e-6);
  }
}

TEST(LimbInertiaCorrection, LegsMovingWithTheTrunkOrMasslessChangeNothing) {
  const auto with_trunk = uniform_acceleration(16.0, 1e-3, 2.0, 0.0, 0.0);
  EXPECT_NEAR(with_trunk[2], 114.0 * (2.0 + 9.806), 1e-6);
  EXPECT_NEAR(with_trunk[0], 0.0, 1e-6);
  const auto massless = uniform_acceleration(0.0, 1e-3, 1.0, 3.0, 2.0);
  EXPECT_EQ(massless[2], 114.0 * (1.0 + 9.806));
  EXPECT_EQ(massless[0], 0.0);
}

TEST(LimbInertiaCorrection, NoCorrectionUntilThreeSamplesAndNaNWhileAnInputIsNot) {
  Stage s(legs(16.0), 1e-3, 1);
  s.force = {0.0, 0.0, 1000.0};
  for (int k = 0; k < 2; ++k) {
    s.feet = {0.0, 0.0, 0.01 * k};  // moving, but two samples have no second difference
    s.step(k * 1e-3);
    EXPECT_EQ(s.out[2], 1000.0) << "tick " << k;
  }
  s.feet[2] = std::nan("");
  s.step(2e-3);
  for (double v : s.out) EXPECT_TRUE(std::isnan(v));
  // The NaN tick left the filters alone: the next finite tick is their third sample.
  s.feet = {0.0, 0.0, 0.02};
  s.step(3e-3);
  EXPECT_TRUE(std::isfinite(s.out[2]));
  EXPECT_NE(s.out[2], 1000.0);
}

TEST(LimbInertiaCorrection, RefusesALegHeavierThanTheRobotAndACutoffAboveNyquist) {
  EXPECT_THROW(LimbInertiaCorrection(legs(114.0), StageContext(1e-3, "legs", {{"foot_pos", 6}})), ConfigError);
  auto p = legs(16.0);
  p.cutoff_hz = 100.0;
  EXPECT_THROW(LimbInertiaCorrection(p, StageContext(5e-3, "legs", {{"foot_pos", 6}})), ConfigError);
  EXPECT_THROW(LimbInertiaCorrection(legs(16.0), StageContext(1e-3, "legs", {{"foot_pos", 4}})), ConfigError);
}

}  // namespace
}  // namespace ftsense::biped
