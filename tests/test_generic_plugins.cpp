// Generic plugins: the contract suite and analytic oracles.

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Dense>

#include <gtest/gtest.h>

#include "ftsense/generic/generic_plugins.hpp"
#include "ftsense/testing/plugin_contract.hpp"

namespace ftsense::testing {
using GenericPluginTypes =
    ::testing::Types<generic::DifferenceResidual, generic::LowPass, generic::ThresholdDetector,
                     generic::RandomWalkFaultFilter, generic::FaultRecovery>;
INSTANTIATE_TYPED_TEST_SUITE_P(Generic, PluginContract, GenericPluginTypes);
}  // namespace ftsense::testing

namespace ftsense {
namespace {

using testing::PluginHarness;

TEST(LowPass, StepResponseIsTheExactDiscreteExponential) {
  // From y_0 = 0 and a unit step, y_k = 1 - (1 - a)^k with a = 1 - exp(-2 pi f_c T): after
  // t = k T the response equals the continuous 1 - exp(-t / tau) exactly at the samples.
  generic::LowPass::Params params;
  params.cutoff_hz = 2.0;
  params.start = generic::LowPass::Start::zero;
  constexpr double kT = 1e-3;
  generic::LowPass filter(params, StageContext(kT, "lp", {{"signal", 1}}));
  filter.reset();
  std::vector<double> x{1.0};
  std::vector<double> y{0.0};
  const std::span<const double> ins[] = {x};
  const std::span<double> outs[] = {y};
  StepIO io{0.0, ins, outs};
  const double tau = 1.0 / (2.0 * std::numbers::pi * params.cutoff_hz);
  for (int k = 1; k <= 1000; ++k) {
    filter.step(io);
    EXPECT_NEAR(y[0], 1.0 - std::exp(-k * kT / tau), 1e-12) << "k = " << k;
  }
}

TEST(LowPass, NonFiniteInputHoldsTheState) {
  generic::LowPass::Params params;
  generic::LowPass filter(params, StageContext(1e-3, "lp", {{"signal", 1}}));
  filter.reset();
  std::vector<double> x{5.0};
  std::vector<double> y{0.0};
  const std::span<const double> ins[] = {x};
  const std::span<double> outs[] = {y};
  StepIO io{0.0, ins, outs};
  filter.step(io);
  EXPECT_EQ(y[0], 5.0);  // first sample initialises
  x[0] = std::nan("");
  filter.step(io);
  EXPECT_EQ(y[0], 5.0);
  x[0] = 6.0;
  filter.step(io);
  EXPECT_NEAR(y[0], 5.0 + filter.smoothing_factor(), 1e-15);
}

TEST(ThresholdDetector, OnAndOffDelaysCountTicks) {
  generic::ThresholdDetector::Params params;
  params.thresholds = {1.0};
  params.on_delay_s = 0.003;   // 3 ticks
  params.off_delay_s = 0.002;  // 2 ticks
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 1}}));
  detector.reset();
  std::vector<double> s{0.0};
  std::vector<double> fault{0.0};
  std::vector<double> type{0.0};
  const std::span<const double> ins[] = {s};
  const std::span<double> outs[] = {fault, type};
  StepIO io{0.0, ins, outs};
  const double signal[] = {0, 2, 2, -2, 2, 0, 0, 0, 2, 0};
  const double expected[] = {0, 0, 0, 1, 1, 1, 0, 0, 0, 0};
  for (std::size_t k = 0; k < std::size(signal); ++k) {
    s[0] = signal[k];
    detector.step(io);
    EXPECT_EQ(fault[0], expected[k]) << "tick " << k;
    EXPECT_EQ(type[0], expected[k]) << "tick " << k;  // 1 = unclassified
  }
}

TEST(ThresholdDetector, NoThresholdFlagsDuringWarmUp) {
  generic::ThresholdDetector::Params params;
  params.thresholds = {1.0};
  params.warmup_s = 0.003;  // 3 ticks from the first step's time
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 1}}));
  detector.reset();
  std::vector<double> s{5.0};
  std::vector<double> fault{0.0};
  std::vector<double> type{0.0};
  const std::span<const double> ins[] = {s};
  const std::span<double> outs[] = {fault, type};
  for (int k = 0; k < 5; ++k) {
    detector.step(StepIO{10.0 + k * 1e-3, ins, outs});
    EXPECT_EQ(fault[0], k >= 3 ? 1.0 : 0.0) << "tick " << k;
  }
}

TEST(ThresholdDetector, NonFiniteSignalIsFlaggedInvalidAtOnce) {
  generic::ThresholdDetector::Params params;
  params.thresholds = {1.0, 1.0};
  params.on_delay_s = 1.0;
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 2}}));
  detector.reset();
  std::vector<double> s{std::nan(""), 0.0};
  std::vector<double> fault{0.0, 0.0};
  std::vector<double> type{0.0, 0.0};
  const std::span<const double> ins[] = {s};
  const std::span<double> outs[] = {fault, type};
  detector.step(StepIO{0.0, ins, outs});
  EXPECT_EQ(fault[0], 1.0);
  EXPECT_EQ(type[0], 8.0);
  EXPECT_EQ(fault[1], 0.0);
}

TEST(ThresholdDetector, NonFiniteMeasuredValueIsFlaggedInvalidWhenChecked) {
  // The fault filter holds its estimate while a reading is NaN, so the signal alone never shows
  // it; with check_measured the reading itself raises 'invalid' on that tick and clears after.
  generic::ThresholdDetector::Params params;
  params.thresholds = {100.0};
  params.warmup_s = 1.0;  // invalid readings are flagged during the warm-up too
  params.check_measured = true;
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 3}, {"measured", 3}}));
  ASSERT_EQ(detector.ports().inputs().size(), 2u);
  EXPECT_EQ(detector.ports().inputs()[1].name, "measured");
  detector.reset();
  std::vector<double> s{0.0, 0.0, 0.0};
  std::vector<double> measured{std::nan(""), -std::numeric_limits<double>::infinity(), 250.0};
  std::vector<double> fault(3, 0.0), type(3, 0.0);
  const std::span<const double> ins[] = {s, measured};
  const std::span<double> outs[] = {fault, type};
  detector.step(StepIO{0.0, ins, outs});
  EXPECT_EQ(fault, (std::vector<double>{1.0, 1.0, 0.0}));
  EXPECT_EQ(type, (std::vector<double>{8.0, 8.0, 0.0}));
  measured = {240.0, 250.0, 250.0};
  detector.step(StepIO{0.001, ins, outs});
  EXPECT_EQ(fault, (std::vector<double>{0.0, 0.0, 0.0}));

  params.check_measured = false;  // without it the input does not exist
  generic::ThresholdDetector plain(params, StageContext(1e-3, "d", {{"signal", 3}}));
  EXPECT_EQ(plain.ports().inputs().size(), 1u);
}

TEST(ThresholdDetector, PerChannelThresholds) {
  generic::ThresholdDetector::Params params;
  params.thresholds = {1.0, 10.0};
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 2}}));
  detector.reset();
  std::vector<double> s{5.0, 5.0};
  std::vector<double> fault{0.0, 0.0};
  std::vector<double> type{0.0, 0.0};
  const std::span<const double> ins[] = {s};
  const std::span<double> outs[] = {fault, type};
  detector.step(StepIO{0.0, ins, outs});
  EXPECT_EQ(fault[0], 1.0);
  EXPECT_EQ(fault[1], 0.0);
}


TEST(ThresholdDetector, CentredBandJudgesBothSignsAgainstTheSameMargin) {
  // Fault-free band [20, 80] of channel 0: centre 50, half-width 30. A fault of -40 (s = 10) and
  // one of +40 (s = 90) both leave it; with the plain |s| > 60 only the positive one would.
  generic::ThresholdDetector::Params params;
  params.thresholds = {30.0, 60.0};
  params.centers = {50.0, 0.0};
  generic::ThresholdDetector detector(params, StageContext(1e-3, "d", {{"signal", 2}}));
  detector.reset();
  std::vector<double> s{0.0, 0.0};
  std::vector<double> fault{0.0, 0.0};
  std::vector<double> type{0.0, 0.0};
  const std::span<const double> ins[] = {s};
  const std::span<double> outs[] = {fault, type};
  const double signal[] = {50.0, 79.0, 21.0, 10.0, 90.0, 81.0, 19.0};
  const double expected[] = {0, 0, 0, 1, 1, 1, 1};
  for (std::size_t k = 0; k < std::size(signal); ++k) {
    s = {signal[k], signal[k]};
    detector.step(StepIO{k * 1e-3, ins, outs});
    EXPECT_EQ(fault[0], expected[k]) << "centred channel, s = " << signal[k];
    EXPECT_EQ(fault[1], std::abs(signal[k]) > 60.0 ? 1.0 : 0.0) << "plain channel, s = " << signal[k];
  }

  params.centers = {1.0, 2.0, 3.0};  // neither one nor one per channel
  EXPECT_THROW(generic::ThresholdDetector(params, StageContext(1e-3, "d", {{"signal", 2}})), ConfigError);
}

// A single-channel harness for the fault filter.
struct FaultFilterRig {
  explicit FaultFilterRig(const generic::RandomWalkFaultFilter::Params& p)
      : filter(p, StageContext(1e-3, "kf", {{"measured", 1}, {"virtual", 1}})) {
    filter.reset();
  }
  void step(double measured_value, double virtual_value) {
    measured[0] = measured_value;
    estimate[0] = virtual_value;
    const std::span<const double> ins[] = {measured, estimate};
    const std::span<double> outs[] = {fault, truth, ready, variance, resets};
    filter.step(StepIO{0.0, ins, outs});
  }
  generic::RandomWalkFaultFilter filter;
  std::vector<double> measured{0.0}, estimate{0.0}, fault{0.0}, truth{0.0}, ready{0.0}, variance{0.0},
      resets{0.0};
};

TEST(RandomWalkFaultFilter, SteadyStateGainSolvesTheDiscreteRiccatiEquation) {
  generic::RandomWalkFaultFilter::Params p;  // the paper's Q = 1e-10 I, R = 1e-4
  FaultFilterRig rig(p);
  for (int k = 0; k < 20000; ++k) rig.step(100.0, 100.0);

  // Oracle: iterate the full-matrix Riccati recursion of the model to its fixed point.
  const Eigen::Matrix2d A{{1.0, 0.0}, {-1.0, 0.0}};
  const Eigen::RowVector2d H{0.0, 1.0};
  const Eigen::Matrix2d Q = Eigen::Vector2d(p.fault_process_noise, p.force_process_noise).asDiagonal();
  Eigen::Matrix2d P = Eigen::Matrix2d::Identity() * p.initial_fault_variance;
  Eigen::Vector2d K = Eigen::Vector2d::Zero();
  for (int k = 0; k < 200000; ++k) {
    const Eigen::Matrix2d prior = A * P * A.transpose() + Q;
    const double S = (H * prior * H.transpose())(0, 0) + p.measurement_noise;
    K = prior * H.transpose() / S;
    P = (Eigen::Matrix2d::Identity() - K * H) * prior;
    P = (0.5 * (P + P.transpose())).eval();  // evaluated first: in place, P^T would read written entries
  }
  EXPECT_NEAR(rig.filter.fault_gain(0), K(0), 1e-9 * std::abs(K(0)));
  EXPECT_NEAR(rig.filter.steady_state_fault_gain(), K(0), 1e-9 * std::abs(K(0)));
  EXPECT_NEAR(rig.filter.fault_variance(0), P(0, 0), 1e-9 * P(0, 0));
  // About -1e-3 per tick with the paper's values: a time constant near 1 s at 1 kHz.
  EXPECT_NEAR(K(0), -1e-3, 1e-4);
  EXPECT_EQ(rig.ready[0], 1.0);
}

TEST(RandomWalkFaultFilter, ConstantOffsetWithinTwoPercentAfterFiveTimeConstants) {
  constexpr std::uint64_t kSeed = 424242;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> vfs_noise(0.0, 5.0);  // a virtual sensor 5 N RMS off
  std::normal_distribution<double> cell_noise(0.0, 1.0);
  generic::RandomWalkFaultFilter::Params p;
  FaultFilterRig rig(p);
  const double gain = rig.filter.steady_state_fault_gain();
  const int tau_ticks = static_cast<int>(std::ceil(-1.0 / std::log1p(gain)));
  constexpr double kOffset = 50.0;
  for (int k = 0; k < 5 * tau_ticks; ++k) {
    const double load = 300.0 + 100.0 * std::sin(2.0 * std::numbers::pi * 0.8 * k * 1e-3);
    rig.step(load + kOffset + cell_noise(rng), load + vfs_noise(rng));
  }
  std::cout << "time constant " << tau_ticks << " ticks, eta_hat = " << rig.fault[0] << " N\n";
  EXPECT_NEAR(rig.fault[0], kOffset, 0.02 * kOffset);
}

TEST(RandomWalkFaultFilter, NotReadyDuringTheInitialTransient) {
  generic::RandomWalkFaultFilter::Params p;
  FaultFilterRig rig(p);
  rig.step(1.0, 1.0);
  EXPECT_EQ(rig.ready[0], 0.0);
}

TEST(RandomWalkFaultFilter, NonFiniteInputHoldsTheEstimate) {
  generic::RandomWalkFaultFilter::Params p;
  FaultFilterRig rig(p);
  for (int k = 0; k < 3000; ++k) rig.step(120.0, 100.0);
  const double before = rig.fault[0];
  rig.step(std::nan(""), 100.0);
  EXPECT_EQ(rig.fault[0], before);
  EXPECT_EQ(rig.truth[0], 100.0);  // falls back on the virtual sensor
  EXPECT_EQ(rig.filter.covariance_resets(), 0u);
}

TEST(RandomWalkFaultFilter, VirtualSensorNotReadyHoldsTheStateAndClearsReady) {
  generic::RandomWalkFaultFilter::Params p;
  FaultFilterRig rig(p);
  for (int k = 0; k < 20000; ++k) rig.step(120.0, 100.0);
  ASSERT_EQ(rig.ready[0], 1.0);
  const double fault_before = rig.fault[0];
  const double variance_before = rig.variance[0];
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    rig.step(120.0, bad);
    EXPECT_EQ(rig.ready[0], 0.0);  // the virtual sensor is not ready: nothing is judged
    EXPECT_EQ(rig.fault[0], fault_before);
    EXPECT_EQ(rig.variance[0], variance_before);
    EXPECT_EQ(rig.truth[0], 120.0 - fault_before);
  }
  rig.step(120.0, 100.0);
  EXPECT_EQ(rig.ready[0], 1.0);
}

TEST(RandomWalkFaultFilter, VarianceOutputIsTheSteadyStateAndStaysBounded) {
  generic::RandomWalkFaultFilter::Params p;
  FaultFilterRig rig(p);
  double largest = 0.0;
  for (int k = 0; k < 20000; ++k) {
    rig.step(300.0 + 50.0 * std::sin(1e-3 * k), 290.0);
    largest = std::max(largest, rig.variance[0]);
    ASSERT_GT(rig.variance[0], 0.0) << "tick " << k;
  }
  // From P0 = 1e-4 the variance only shrinks towards the Riccati fixed point (below P0 + q).
  EXPECT_LE(largest, p.initial_fault_variance + p.fault_process_noise);
  EXPECT_NEAR(rig.variance[0], rig.filter.steady_state_fault_variance(),
              1e-6 * rig.filter.steady_state_fault_variance());
}

TEST(RandomWalkFaultFilter, OverflowingInputsResetTheCovarianceAndSayHowOften) {
  // Finite but huge readings overflow the innovation to Inf; the channel resets (estimate and
  // covariance) instead of carrying Inf or NaN forward, and the reset is counted per channel.
  generic::RandomWalkFaultFilter::Params p;
  FaultFilterRig rig(p);
  for (int k = 0; k < 100; ++k) rig.step(100.0, 100.0);
  EXPECT_EQ(rig.resets[0], 0.0);
  rig.step(1e308, -1e308);
  EXPECT_EQ(rig.resets[0], 1.0);
  EXPECT_EQ(rig.filter.covariance_resets(), 1u);
  EXPECT_TRUE(std::isfinite(rig.fault[0]));
  EXPECT_EQ(rig.variance[0], p.initial_fault_variance);
  rig.step(1e308, -1e308);
  EXPECT_EQ(rig.resets[0], 2.0);
  for (int k = 0; k < 100; ++k) rig.step(100.0, 100.0);
  EXPECT_EQ(rig.resets[0], 2.0);  // cumulative until reset()
  EXPECT_TRUE(std::isfinite(rig.fault[0]));
  rig.filter.reset();
  rig.step(100.0, 100.0);
  EXPECT_EQ(rig.resets[0], 0.0);
}

struct RecoveryRig {
  explicit RecoveryRig(const generic::FaultRecovery::Params& p)
      : recovery(p, StageContext(1e-3, "rec", {{"measured", 1}})) {
    recovery.reset();
  }
  double step(double m, double eta, double v, double f, double type) {
    measured[0] = m, fault_estimate[0] = eta, estimate[0] = v, fault[0] = f, fault_type[0] = type;
    const std::span<const double> ins[] = {measured, fault_estimate, estimate, fault, fault_type};
    const std::span<double> outs[] = {out, correction, substituted};
    recovery.step(StepIO{0.0, ins, outs});
    return out[0];
  }
  generic::FaultRecovery recovery;
  std::vector<double> measured{0}, fault_estimate{0}, estimate{0}, fault{0}, fault_type{0}, out{0}, correction{0}, substituted{0};
};

TEST(FaultRecovery, SubtractsTheEstimateOrSubstitutesTheVirtualValue) {
  RecoveryRig rig(generic::FaultRecovery::Params{});
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, 2.0), 100.0);   // offset: measured - eta
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 0.0, 0.0), 100.0);   // paper: always subtract
  EXPECT_EQ(rig.step(0.0, -80.0, 90.0, 1.0, 4.0), 90.0);     // frozen: the virtual value
  EXPECT_EQ(rig.step(std::nan(""), 0.0, 90.0, 1.0, 8.0), 90.0);  // invalid
  EXPECT_EQ(rig.step(std::nan(""), 0.0, std::nan(""), 1.0, 8.0), 90.0);  // nothing valid: hold
}

TEST(FaultRecovery, WhenFlaggedPassesHealthyChannelsThrough) {
  generic::FaultRecovery::Params p;
  p.correction = generic::FaultRecovery::Correction::when_flagged;
  RecoveryRig rig(p);
  EXPECT_EQ(rig.step(150.0, 3.0, 90.0, 0.0, 0.0), 150.0);
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, 2.0), 100.0);
}

TEST(FaultRecovery, ACodeOutsideTheTableCountsAsInvalid) {
  // Found by fuzzing: a fault-type input of 1e300 was cast to int (undefined behaviour).
  RecoveryRig rig(generic::FaultRecovery::Params{});
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, 1e300), 90.0);
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, -3.0), 90.0);
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, 2.5), 90.0);
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, 42.0), 90.0);  // an integer, but no fault type's code
}

TEST(FaultRecovery, ABlendedChannelTakesTheVirtualValuePlusALowPassOfTheDifference) {
  // d_k = measured - virtual = 10 + 40 (-1)^k from k = 1, the low-pass started at d_0 = 10:
  // y_k = 10 + 40 a (-1)^k (1 - (a - 1)^k) / (2 - a), a = 1 - exp(-2 pi 10 Hz 1 ms) (closed form
  // of the recursion y_k = y_{k-1} + a (d_k - y_{k-1}) for an alternating input).
  generic::FaultRecovery::Params p;
  p.blend_types = {"noise"};
  RecoveryRig rig(p);
  const double a = 1.0 - std::exp(-2.0 * std::numbers::pi * 10.0 * 1e-3);
  EXPECT_EQ(rig.step(110.0, 0.0, 100.0, 0.0, 0.0), 110.0);  // healthy: passes through
  for (int k = 1; k <= 50; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    const double expected = 110.0 + 40.0 * a * sign * (1.0 - std::pow(a - 1.0, k)) / (2.0 - a);
    ASSERT_NEAR(rig.step(110.0 + 40.0 * sign, 0.0, 100.0, 1.0, 6.0), expected, 1e-9) << "tick " << k;
  }
  // Spikes are not in blend_types: the estimate is subtracted as before.
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, 7.0), 100.0);
}

TEST(FaultRecovery, ABlendedChannelFollowsARampThatItsLowPassWouldLag) {
  // A 3 N-per-tick load read by a noise-burst channel whose virtual value is 5 N high: the
  // difference is -5 N on every tick, so the recovered value is the load itself, where a 10 Hz
  // low-pass of the reading would lag it by 3 N x 15.9 ticks (48 N).
  generic::FaultRecovery::Params p;
  p.blend_types = {"noise"};
  RecoveryRig rig(p);
  for (int k = 0; k < 200; ++k) {
    const double load = 3.0 * k;
    ASSERT_NEAR(rig.step(load, 0.0, load + 5.0, 1.0, 6.0), load, 1e-9) << "tick " << k;
  }
  // A reading that is not a number is substituted, whatever its type.
  EXPECT_EQ(rig.step(std::nan(""), 0.0, 605.0, 1.0, 6.0), 605.0);
}

TEST(FaultRecovery, ASpikyChannelTakesTheMedianOfItsLastThreeReadings) {
  generic::FaultRecovery::Params p;
  p.median_types = {"spikes"};
  RecoveryRig rig(p);
  // A ramp of 1 per tick with a +100 spike on tick 3 and a -100 one on tick 6, typed spikes from
  // tick 2 on: the median drops each spike on its own tick and lags the ramp by at most two
  // ticks (its neighbours stand in for the spike).
  const double readings[] = {0.0, 1.0, 2.0, 103.0, 4.0, 5.0, -94.0, 7.0, 8.0};
  const double expected[] = {0.0, 1.0, 1.0, 2.0, 4.0, 5.0, 4.0, 5.0, 7.0};
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(rig.step(readings[k], 0.0, -1.0, k >= 2 ? 1.0 : 0.0, k >= 2 ? 7.0 : 0.0), expected[k]) << "tick " << k;
  }
  // A NaN reading is substituted, and the readings before it are no neighbours of those after
  // it: the reading itself until two more have come.
  EXPECT_EQ(rig.step(std::nan(""), 0.0, 9.0, 1.0, 7.0), 9.0);
  EXPECT_EQ(rig.step(10.0, 0.0, -1.0, 1.0, 7.0), 10.0);
  EXPECT_EQ(rig.step(11.0, 0.0, -1.0, 1.0, 7.0), 11.0);
  EXPECT_EQ(rig.step(12.0, 0.0, -1.0, 1.0, 7.0), 11.0);
}

// The correction a relation's other channels subtract: measured - recovered where the recovered
// value is the reading less a lasting fault model's estimate (offset, drift, gain), else 0; and
// `substituted` 1 where the recovered value is the virtual one (the reading stands for nothing).
TEST(FaultRecovery, TheCorrectionIsWhatTheChannelsOwnReadingsGive) {
  generic::FaultRecovery::Params p;
  p.correction = generic::FaultRecovery::Correction::when_flagged;
  p.blend_types = {"noise"};
  p.median_types = {"spikes"};
  RecoveryRig rig(p);
  const auto told = [&rig] { return std::pair{rig.correction[0], rig.substituted[0]}; };
  using Told = std::pair<double, double>;
  EXPECT_EQ(rig.step(150.0, 3.0, 90.0, 0.0, 0.0), 150.0);  // healthy: passes through
  EXPECT_EQ(told(), (Told{0.0, 0.0}));
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, 2.0), 100.0);  // offset
  EXPECT_EQ(told(), (Told{50.0, 0.0}));
  EXPECT_EQ(rig.step(150.0, 30.0, 90.0, 1.0, 5.0), 120.0);  // gain: x (1 - 1/k) with k = 1.25
  EXPECT_EQ(told(), (Told{30.0, 0.0}));
  EXPECT_EQ(rig.step(150.0, 4.5, 90.0, 1.0, 3.0), 145.5);   // drift
  EXPECT_EQ(told(), (Told{4.5, 0.0}));
  EXPECT_EQ(rig.step(150.0, 60.0, 90.0, 1.0, 4.0), 90.0);   // frozen: substituted
  EXPECT_EQ(told(), (Told{0.0, 1.0}));
  (void)rig.step(150.0, 0.0, 90.0, 1.0, 6.0);                // noise: blended, the reading as it is
  EXPECT_EQ(told(), (Told{0.0, 0.0}));
  EXPECT_EQ(rig.step(250.0, 0.0, 90.0, 1.0, 7.0), 150.0);   // spikes: the median of 150, 150, 250
  EXPECT_EQ(told(), (Told{0.0, 0.0}));  // its own tick's: a tick late it would move the spike
  EXPECT_EQ(rig.step(std::nan(""), 0.0, 90.0, 1.0, 2.0), 90.0);  // no reading: substituted
  EXPECT_EQ(told(), (Told{0.0, 1.0}));
  // Not yet named: the classifier's estimate is x - v, so the value is the virtual one again.
  EXPECT_EQ(rig.step(150.0, 60.0, 90.0, 1.0, 1.0), 90.0);
  EXPECT_EQ(told(), (Told{0.0, 1.0}));
  // An offset whose estimate is not a number falls back on the virtual value.
  EXPECT_EQ(rig.step(150.0, std::nan(""), 90.0, 1.0, 2.0), 90.0);
  EXPECT_EQ(told(), (Told{0.0, 1.0}));
  // A frozen channel whose virtual value is not a number falls back on its corrected reading,
  // which stands for nothing either.
  EXPECT_EQ(rig.step(150.0, 60.0, std::nan(""), 1.0, 4.0), 90.0);
  EXPECT_EQ(told(), (Told{0.0, 1.0}));
}

TEST(FaultRecovery, AFlaggedChannelIsRecoveredWithinWhatTheQuantityCanTake) {
  generic::FaultRecovery::Params p;
  p.correction = generic::FaultRecovery::Correction::when_flagged;
  p.floor = {0.0};
  p.ceiling = {500.0};
  RecoveryRig rig(p);
  // Healthy: the reading as it is, below the floor too (its noise is the sensor's).
  EXPECT_EQ(rig.step(-3.0, 0.0, 90.0, 0.0, 0.0), -3.0);
  // Not yet named, no virtual value: the fallback on the reading is held at the floor.
  EXPECT_EQ(rig.step(-8.7, -8.7, std::nan(""), 1.0, 1.0), 0.0);
  EXPECT_EQ(rig.substituted[0], 1.0);
  // An offset whose correction overshoots: at the floor, its correction the model's (x - (x - b)).
  EXPECT_EQ(rig.step(30.0, 40.0, 90.0, 1.0, 2.0), 0.0);
  EXPECT_EQ(rig.correction[0], 40.0);
  // A virtual value above the ceiling, substituted: at the ceiling.
  EXPECT_EQ(rig.step(0.0, 0.0, 650.0, 1.0, 4.0), 500.0);
  // Within the bounds: unchanged.
  EXPECT_EQ(rig.step(150.0, 50.0, 90.0, 1.0, 2.0), 100.0);
  // A ceiling not above the floor is refused.
  p.ceiling = {0.0};
  EXPECT_THROW((void)generic::FaultRecovery(p, StageContext(1e-3, "rec", {{"measured", 1}})), ConfigError);
}

TEST(FaultRecovery, ASaturatedReadingBoundsItsRecoveredValueFromBelow) {
  // Saturation (code 9) substituted and a lower bound: a virtual value below the clipped 350 N
  // gives the reading, which stands for itself; one above it is the value, substituted. Not
  // flagged, or without the list, the bound does nothing.
  generic::FaultRecovery::Params p;
  p.correction = generic::FaultRecovery::Correction::when_flagged;
  p.substitute_types = {"frozen", "invalid", "saturation"};
  p.lower_bound_types = {"saturation"};
  const double saturation = fault_code(FaultType::saturation);
  ASSERT_EQ(saturation, 9.0);
  RecoveryRig rig(p);
  EXPECT_EQ(rig.step(350.0, 0.0, 280.0, 1.0, saturation), 350.0);
  EXPECT_EQ(rig.substituted[0], 0.0);
  EXPECT_EQ(rig.correction[0], 0.0);
  EXPECT_EQ(rig.step(350.0, 0.0, 420.0, 1.0, saturation), 420.0);
  EXPECT_EQ(rig.substituted[0], 1.0);
  EXPECT_EQ(rig.step(350.0, 0.0, std::nan(""), 1.0, saturation), 350.0);  // no virtual value: the bound
  EXPECT_EQ(rig.substituted[0], 0.0);
  EXPECT_EQ(rig.step(300.0, 0.0, 280.0, 0.0, 0.0), 300.0);
  EXPECT_EQ(rig.step(350.0, 0.0, 280.0, 1.0, fault_code(FaultType::frozen)), 280.0);  // frozen: no bound
  p.lower_bound_types = {};
  RecoveryRig without(p);
  EXPECT_EQ(without.step(350.0, 0.0, 280.0, 1.0, saturation), 280.0);
  EXPECT_EQ(without.substituted[0], 1.0);
  Diagnostics d;
  (void)load_params<generic::FaultRecovery::Params>(Json::parse(R"({"lower_bound_types": ["saturaton"]})"),
                                                    "/stages/4/params", "fault_recovery", d);
  ASSERT_EQ(d.errors().size(), 1u);
  EXPECT_EQ(d.errors()[0].path, "/stages/4/params/lower_bound_types/0");
}

TEST(FaultRecovery, ATypeRecoveredTwoWaysOrABlendAboveNyquistIsAConfigError) {
  Diagnostics d;
  (void)load_params<generic::FaultRecovery::Params>(
      Json::parse(R"({"substitute_types": ["frozen", "noise"], "blend_types": ["noise", "nois"],
                      "median_types": ["frozen"]})"),
      "/stages/4/params", "fault_recovery", d);
  ASSERT_EQ(d.errors().size(), 3u);
  EXPECT_EQ(d.errors()[0].path, "/stages/4/params/blend_types/1");
  EXPECT_NE(d.errors()[0].message.find("did you mean 'noise'?"), std::string::npos);
  EXPECT_EQ(d.errors()[1].path, "/stages/4/params/blend_types/0");
  EXPECT_NE(d.errors()[1].message.find("also in substitute_types"), std::string::npos);
  EXPECT_EQ(d.errors()[2].path, "/stages/4/params/median_types/0");

  generic::FaultRecovery::Params p;
  p.blend_cutoff_hz = 150.0;  // Nyquist at 200 Hz is 100 Hz
  try {
    generic::FaultRecovery recovery(p, StageContext(0.005, "rec", {{"measured", 1}}));
    FAIL() << "a cut-off above the Nyquist frequency was accepted";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].path, "/params/blend_cutoff_hz");
  }
}

TEST(FaultRecovery, UnknownSubstituteTypeIsAConfigError) {
  Diagnostics d;
  (void)load_params<generic::FaultRecovery::Params>(Json::parse(R"({"substitute_types": ["frozn"]})"),
                                                    "/stages/4/params", "fault_recovery", d);
  ASSERT_EQ(d.errors().size(), 1u);
  EXPECT_EQ(d.errors()[0].path, "/stages/4/params/substitute_types/0");
  EXPECT_NE(d.errors()[0].message.find("did you mean 'frozen'?"), std::string::npos);
}

}  // namespace
}  // namespace ftsense
