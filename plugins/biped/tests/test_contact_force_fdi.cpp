// contact_force_fdi: the tests that must hold at any log rate and quantisation (issue 13) fire on
// the tick they should on deterministic traces: the frozen run length follows the sensors'
// resolution, noise, rate and false-alarm target; an unloaded pad on its zero level is no
// evidence; the noise test tells white jitter from a fast smooth load and from a chattering foot;
// a jump must be a surprise.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/biped/contact_force_fdi.hpp"
#include "ftsense/fault_type.hpp"

namespace ftsense::biped {
namespace {

constexpr std::size_t kChannels = 8;

// Both feet flat on the ground (or the left one lifted), eight pads driven tick by tick.
struct Feet {
  ContactForceFdi fdi;
  double period;
  double t = 0.0;
  std::vector<double> measured = std::vector<double>(kChannels, 0.0);
  std::vector<double> total = {0.0, 0.0, 0.0};
  std::vector<double> height = std::vector<double>(kChannels, 0.0);  // pads above the ground [m]
  std::vector<std::vector<double>> outs;

  Feet(const ContactForceFdi::Params& p, double period_s) : fdi(p, StageContext(period_s, "fdi")), period(period_s) {
    for (const auto& port : fdi.ports().outputs()) outs.emplace_back(port.dim, 0.0);
    fdi.reset();
  }
  // One tick; F_z is the pads' sum unless given (or unknown: NaN, the virtual sensor not ready).
  void step(double fz = std::nan(""), bool total_known = true) {
    double sum = 0.0;
    for (double x : measured) {
      if (std::isfinite(x)) sum += x;
    }
    total[2] = !total_known ? std::nan("") : std::isnan(fz) ? sum : fz;
    const std::span<const double> ins[] = {measured, total, height};
    std::vector<std::span<double>> out_spans(outs.begin(), outs.end());
    fdi.step(StepIO{t, ins, out_spans});
    t += period;
  }
  // The left foot's four pads at height h.
  void left_foot_at(double h) { std::fill(height.begin(), height.begin() + 4, h); }
  [[nodiscard]] FaultType type(std::size_t channel) const {
    return fault_type_from_code(outs[ContactForceFdi::kFaultType][channel]).value_or(FaultType::unclassified);
  }
};

ContactForceFdi::Params suralp(double resolution_N = 0.0) {
  ContactForceFdi::Params p;
  p.points_per_foot = 4;
  p.noise_std_N = 2.0;
  p.sum_threshold_N = 80.0;  // configs/suralp_robust.json's load thresholds
  p.gain_min_load_N = 30.0;
  p.resolution_N = resolution_N;
  return p;
}

// Healthy loaded pads that never repeat a quantisation level: each moves by 3 q / 4 + 1 N per tick,
// alternately up and down, around its own load.
double moving(std::size_t channel, int tick, double q) {
  return 200.0 + 10.0 * static_cast<double>(channel) + (tick % 2 == 0 ? 0.0 : 0.75 * q + 1.0);
}

// The run length n_f of the header: ln alpha / ln p, p = erf(q / (2 sqrt(2) sigma)).
int expected_frozen_ticks(double q, double sigma, double period_s, double interval_s, double min_s) {
  const double p = std::erf(q / (2.0 * std::sqrt(2.0) * sigma));
  const double run = p > 0.0 ? std::log(period_s / interval_s) / std::log(p) : 0.0;
  return static_cast<int>(std::ceil(std::max(min_s / period_s, run) - 1e-9));
}

// A loaded pad stuck on one level from tick `stuck_at`: frozen exactly n_f ticks later.
void expect_frozen_after(double q, double period_s, int n_f) {
  SCOPED_TRACE("q = " + std::to_string(q) + " N, T = " + std::to_string(period_s) + " s, n_f = " + std::to_string(n_f));
  Feet feet(suralp(q), period_s);
  const int stuck_at = 50;
  for (int k = 0; k < stuck_at + n_f + 1; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, q);
    if (k >= stuck_at) feet.measured[2] = 150.0;  // below its largest reading: frozen, not saturated
    feet.step();
    const FaultType expected = k >= stuck_at + n_f ? FaultType::frozen : FaultType::none;
    ASSERT_EQ(feet.type(2), expected) << "tick " << k;
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 2) {
        ASSERT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
}

TEST(ContactForceFdi, FrozenRunLengthFollowsResolutionNoiseRateAndFalseAlarmTarget) {
  // 5 N steps, 2 N noise: a healthy reading stays on its level with p = erf(0.884) = 0.79 per
  // tick, so a day between false alarms at 1 kHz takes ln(1.157e-8) / ln(0.7887) = 76.97 -> 77 ticks.
  const int quantised = expected_frozen_ticks(5.0, 2.0, 1e-3, 86400.0, 0.02);
  EXPECT_EQ(quantised, 77);
  expect_frozen_after(5.0, 1e-3, quantised);
  // Continuous readings never repeat: frozen_min_s decides, 20 ticks at 1 kHz, 4 at 200 Hz.
  expect_frozen_after(0.0, 1e-3, 20);
  expect_frozen_after(0.0, 5e-3, 4);
  // 1 N steps under 2 N noise repeat rarely (p = 0.197): frozen_min_s still decides.
  EXPECT_EQ(expected_frozen_ticks(1.0, 2.0, 1e-3, 86400.0, 0.02), 20);
  expect_frozen_after(1.0, 1e-3, 20);
}

TEST(ContactForceFdi, ANoiseTooSmallToDitherItsQuantiserTurnsTheRepeatTestOff) {
  // 10 N steps under 0.7 N of noise (a true statement of a coarse ADC): a healthy reading under
  // a steady load stays on one level with p = erf(10 / (2 sqrt(2) 0.7)) = 1 - 1e-12 per tick,
  // so no run length tells it from a stuck one. The config loads, and a reading that sits on one
  // level for 20 s while its load stays is not flagged (before: a config error).
  // The same steady loads under a stated 2 N of noise, which would dither the levels, are flagged
  // once they have sat still for n_f ticks (p = erf(1.768) = 0.9876: 1463 ticks).
  for (const double sigma : {0.7, 2.0}) {
    auto p = suralp(10.0);
    p.noise_std_N = sigma;
    Feet feet(p, 1e-3);
    const int n_f = sigma < 1.0 ? -1 : expected_frozen_ticks(10.0, sigma, 1e-3, 86400.0, 0.02);
    int first_flag = -1;
    for (int k = 0; k < 20000 && first_flag < 0; ++k) {
      for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = 200.0 + 10.0 * static_cast<double>(j);
      feet.step();
      for (std::size_t j = 0; j < kChannels; ++j) {
        if (feet.type(j) != FaultType::none) first_flag = k;
      }
    }
    std::printf("sigma %.1f N: n_f %d ticks, first flag at tick %d\n", sigma, n_f, first_flag);
    if (sigma < 1.0) {
      EXPECT_EQ(first_flag, -1);
      // With the repeat test off, a reading at the top of a stated range is saturation on its tick.
      auto ranged = p;
      ranged.upper_limit_N = 500.0;
      Feet clipped(ranged, 1e-3);
      for (int k = 0; k < 300; ++k) {
        for (std::size_t j = 0; j < kChannels; ++j) clipped.measured[j] = 200.0 + 10.0 * static_cast<double>(j);
        if (k >= 250) clipped.measured[2] = 500.0;
        clipped.step();
        ASSERT_EQ(clipped.type(2), k >= 250 ? FaultType::saturation : FaultType::none) << "tick " << k;
      }
    } else {
      EXPECT_EQ(n_f, 1463);
      EXPECT_EQ(first_flag, n_f);
    }
  }
}

// Without the total force no channel can be judged against the sum: every channel not flagged
// says so (cannot_judge 1) for exactly the ticks F_z is unknown, and a flagged one keeps its flag.
TEST(ContactForceFdi, ChannelsSayTheyCannotBeJudgedWhileTheTotalForceIsUnknown) {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 300; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    if (k >= 100) feet.measured[5] = std::nan("");  // a dropout: flagged invalid, judged
    const bool unknown = k >= 200 && k < 250;
    feet.step(std::nan(""), !unknown);
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double expected = unknown && j != 5 ? 1.0 : 0.0;
      ASSERT_EQ(feet.outs[ContactForceFdi::kCannotJudge][j], expected) << "channel " << j << ", tick " << k;
    }
  }
}

// The corrected sum residual is what no flagged channel's correction explains: when it leaves
// its bound, the channels not flagged cannot be judged, even while another channel is flagged
// (here an airborne pad that reads NaN, flagged invalid, and a total force 150 N off: a fault of
// the reference no pad can be blamed for). Raised on the exact tick the 1 Hz low-passed residual
// crosses sum_threshold_N (80 N).
TEST(ContactForceFdi, AnUnexplainedSumResidualIsUnjudgedEvenWhileAnotherChannelIsFlagged) {
  const auto p = suralp();
  Feet feet(p, 1e-3);
  feet.left_foot_at(0.1);
  const int step_at = 100;
  const double a = -std::expm1(-2.0 * std::numbers::pi * p.sum_cutoff_hz * 1e-3);
  double filtered = 0.0;
  int crossed = -1;
  for (int k = 0; k < 400; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = j < 4 ? 0.0 : moving(j, k, 0.0);
    feet.measured[0] = std::nan("");  // the airborne left pad 1: invalid from the first tick
    double sum = 0.0;
    for (std::size_t j = 4; j < kChannels; ++j) sum += feet.measured[j];
    const double error = k >= step_at ? 150.0 : 0.0;
    feet.step(sum + error);
    // The detector's residual is sum - F_z (its first tick starts the filter).
    filtered = k == 0 ? -error : filtered + a * (-error - filtered);
    if (crossed < 0 && std::abs(filtered) > p.sum_threshold_N) crossed = k;
    const double expected = crossed >= 0 ? 1.0 : 0.0;
    ASSERT_EQ(feet.type(0), FaultType::invalid) << "tick " << k;
    ASSERT_EQ(feet.outs[ContactForceFdi::kUnisolated][0], expected) << "tick " << k;
    for (std::size_t j = 1; j < kChannels; ++j) {
      ASSERT_EQ(feet.outs[ContactForceFdi::kFault][j], 0.0) << "channel " << j << ", tick " << k;
      ASSERT_EQ(feet.outs[ContactForceFdi::kCannotJudge][j], expected) << "channel " << j << ", tick " << k;
    }
    ASSERT_EQ(feet.outs[ContactForceFdi::kCannotJudge][0], 0.0) << "tick " << k;
  }
  // 1 - exp(-2 pi f_c T m) > 80 / 150 from the m = 122nd tick of the step on (m > 121.3).
  EXPECT_EQ(crossed, step_at + 121);
}

// A residual that does not vary with any reading is no gain fault: here the total force is
// 100 N above the pads' sum for 3 s (a reference off by a constant, or an offset the other tests
// have not seen) while pad 2 carries a steady 300 N and the others swing by 100 N. Fitted
// through the origin, r = beta N_2 would explain the constant r exactly and blame pad 2 as a
// gain of k = 1.5 after the 2 s window; with the intercept the constant is b and no pad's reading
// explains any of what varies.
TEST(ContactForceFdi, AConstantResidualIsNoGainOfASteadilyLoadedPad) {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 3000; ++k) {
    const double t = k * 1e-3;
    double sum = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = j == 2 ? 300.0 + (k % 2 == 0 ? 0.0 : 1.0)  // steady (not frozen: it varies)
                                : 200.0 + 100.0 * std::sin(2.0 * std::numbers::pi * (0.7 * t + 0.125 * j));
      sum += feet.measured[j];
    }
    feet.step(sum + 100.0);
    for (std::size_t j = 0; j < kChannels; ++j) {
      ASSERT_EQ(feet.outs[ContactForceFdi::kFault][j], 0.0) << "channel " << j << ", tick " << k;
    }
  }
  EXPECT_EQ(feet.outs[ContactForceFdi::kUnisolated][0], 1.0);  // off by 100 N with no one to blame
}

// A robot standing still: every pad carries a steady load (reading noise N(0, 2 N), the total
// force the true sum + N(0, 2 N) + total_error(k), std::mt19937(seed)); pad 2 reads fault(k) on
// top, pad 5 other(k) (0: healthy, and counted among the others).
struct StillStand {
  FaultType first_type = FaultType::none;
  int raised_at = -1;
  double first_error_N = 0.0;  // recovered - true load on the tick it was raised
  double end_error_N = 0.0;    // ... its mean over the last 1000 ticks (the readings' noise averages out)
  double end_estimate_N = 0.0;
  FaultType end_type = FaultType::none;
  FaultType pad5_end_type = FaultType::none;
  int others_flagged = 0;  // ticks x channels flagged other than pad 2 (and pad 5 when it is faulty)
};
double no_error(int) { return 0.0; }
template <class Fault, class TotalError = double (*)(int), class OtherFault = double (*)(int)>
StillStand standing_with(const Fault& fault, unsigned seed, int ticks = 16000, const TotalError& total_error = no_error,
                         const OtherFault& other = no_error, bool other_faulty = false) {
  Feet feet(suralp(), 1e-3);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 2.0);
  StillStand out;
  for (int k = 0; k < ticks; ++k) {
    double sum = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = 100.0 + 5.0 * static_cast<double>(j);
      feet.measured[j] = load + noise(rng) + (j == 2 ? fault(k) : 0.0) + (j == 5 ? other(k) : 0.0);
      sum += load;
    }
    feet.step(sum + noise(rng) + total_error(k));
    for (std::size_t j = 0; j < kChannels; ++j) {
      out.others_flagged += j != 2 && !(j == 5 && other_faulty) && feet.type(j) != FaultType::none;
    }
    if (out.raised_at < 0 && feet.type(2) != FaultType::none) {
      out.raised_at = k;
      out.first_type = feet.type(2);
      out.first_error_N = feet.outs[ContactForceFdi::kRecovered][2] - 110.0;
    }
    if (k >= ticks - 1000) out.end_error_N += (feet.outs[ContactForceFdi::kRecovered][2] - 110.0) / 1000.0;
  }
  out.end_estimate_N = feet.outs[ContactForceFdi::kFaultEstimate][2];
  out.end_type = feet.type(2);
  out.pad5_end_type = feet.type(5);
  return out;
}

TEST(ContactForceFdi, ASlowDriftOfAStillPadIsADriftSizedByTheResidualsHistoryNotAGain) {
  for (const double rate : {3.0, 10.0}) {
    const auto drifts = [rate](int k) { return k < 8000 ? 0.0 : rate * (k - 8000) * 1e-3; };
    const StillStand s = standing_with(drifts, 5);
    std::printf("seed 5, %.0f N/s: raised at tick %d as %s, first error %.2f N, end error %.2f N (estimate %.2f N)\n", rate,
                s.raised_at, std::string(to_string(s.first_type)).c_str(), s.first_error_N, s.end_error_N, s.end_estimate_N);
    EXPECT_GT(s.raised_at, 8000);
    EXPECT_EQ(s.first_type, FaultType::drift);
    EXPECT_LT(std::abs(s.first_error_N), 5.0);   // before: a gain k = 10, recovered 12 N of 110 N
    EXPECT_LT(std::abs(s.end_error_N), 5.0);
    EXPECT_EQ(s.others_flagged, 0);
  }
}

TEST(ContactForceFdi, AStepUnderTheJumpThresholdOnAStillPadIsAnOffsetOfItsSize) {
  for (const double b : {15.0, -15.0}) {  // under jump_threshold_N (10 sigma: 20 N)
    const StillStand s = standing_with([b](int k) { return k < 8000 ? 0.0 : b; }, 5);
    std::printf("seed 5, %+.0f N step: raised at tick %d as %s, first error %.2f N, estimate %.2f N\n", b, s.raised_at,
                std::string(to_string(s.first_type)).c_str(), s.first_error_N, s.end_estimate_N);
    EXPECT_EQ(s.first_type, FaultType::offset);
    EXPECT_NEAR(s.end_estimate_N, b, 3.0);
    EXPECT_LT(std::abs(s.end_error_N), 3.0);
    EXPECT_EQ(s.others_flagged, 0);
  }
}

// A drift that ended while the robot stood, seen by the gain test only after its end (the step
// back moved r and the reading together: beta near 1): the sum residual's level is back at its
// healthy level by then, and there is no fault left to raise. (Before: a gain, k = 10.)
TEST(ContactForceFdi, ADriftThatEndedBeforeItsRaiseRaisesNothing) {
  for (const auto& [rate, ticks] : {std::pair{5.0, 2800}, std::pair{3.0, 5000}}) {
    const auto came_and_went = [=](int k) { return k < 8000 || k >= 8000 + ticks ? 0.0 : rate * (k - 8000) * 1e-3; };
    const StillStand s = standing_with(came_and_went, 5, 20000);
    std::printf("seed 5, %.0f N/s for %d ticks from tick 8000: raised at tick %d as %s\n", rate, ticks, s.raised_at,
                std::string(to_string(s.first_type)).c_str());
    EXPECT_EQ(s.raised_at, -1);
    EXPECT_EQ(s.others_flagged, 0);
    // The control: the same drift going on is raised, as a drift (the gain test fires on it).
    const StillStand going_on = standing_with([=](int k) { return k < 8000 ? 0.0 : rate * (k - 8000) * 1e-3; }, 5, 20000);
    EXPECT_EQ(going_on.first_type, FaultType::drift);
  }
}

// The same on a robot standing with the total force 30 N off either way (the residual's healthy
// level): a step on pad 2 is an offset of its size, a drift that ended before its raise is nothing.
// Beside another flagged pad (pad 5 held as a +50 N offset since tick 3000) the still-load test
// raises nothing: a drift raised there could not be held at its plateau (a review's probe: 78 N
// off at 20 s).
TEST(ContactForceFdi, AStillPadsFaultIsSizedFromTheResidualsHealthyLevelAndNotRaisedBesideAnotherFlag) {
  const auto step = [](int k) { return k < 8000 ? 0.0 : 15.0; };
  const auto came_and_went = [](int k) { return k < 8000 || k >= 10800 ? 0.0 : 5.0 * (k - 8000) * 1e-3; };
  for (const double bias : {30.0, -30.0}) {
    const auto off = [=](int) { return bias; };
    const StillStand s = standing_with(step, 5, 16000, off);
    std::printf("seed 5, total force %+.0f N off, +15 N step: raised at tick %d as %s, estimate %.2f N\n", bias,
                s.raised_at, std::string(to_string(s.first_type)).c_str(), s.end_estimate_N);
    EXPECT_EQ(s.first_type, FaultType::offset);
    EXPECT_NEAR(s.end_estimate_N, 15.0, 3.0);
    EXPECT_EQ(s.others_flagged, 0);
    const StillStand ended = standing_with(came_and_went, 5, 20000, off);
    EXPECT_EQ(ended.raised_at, -1);
    EXPECT_EQ(ended.others_flagged, 0);
  }
  const auto pad5_held = [](int k) { return k < 3000 ? 0.0 : 50.0; };
  const auto stopped = [](int k) { return k < 8000 ? 0.0 : 10.0 * std::min(k - 8000, 4000) * 1e-3; };
  for (const auto& fault : {std::function<double(int)>(step), std::function<double(int)>(came_and_went),
                            std::function<double(int)>(stopped)}) {
    const StillStand s = standing_with(fault, 5, 20000, no_error, pad5_held, true);
    EXPECT_EQ(s.pad5_end_type, FaultType::offset);
    EXPECT_EQ(s.raised_at, -1);
    EXPECT_EQ(s.others_flagged, 0);
  }
}

// A drift that stops on a still pad, its reading held where it got to: a drift first, then an
// offset of that plateau. 40 N is beyond gain_min_load_N (30 N here); 13.5 and 13.2 N are under
// it, held because the drift was raised from the residual's ramp on a still load (plateau_bar:
// z of the residual's measured noise). The 13.5 N drift stopped 0.29 s before its raise.
// (Before: a gain, k = 10, dropped again, the fault missed; without plateau_bar the 13.5 N drift
// was extrapolated and re-admitted at tick 18750 with its 13.5 N still there.)
TEST(ContactForceFdi, ADriftThatStopsOnAStillPadIsHeldAtItsPlateau) {
  // The 13.5 N one again with the total force 30 N off either way: its lead is taken from the
  // residual's healthy level (a review's probe: held at -16.4 and 43.6 N without).
  struct Case {
    double rate;
    int ticks;
    double bias;
  };
  for (const auto& [rate, ticks, bias] : {Case{10.0, 4000, 0.0}, Case{5.0, 2700, 0.0}, Case{12.0, 1100, 0.0},
                                          Case{5.0, 2700, 30.0}, Case{5.0, 2700, -30.0}}) {
    const double plateau = rate * ticks * 1e-3;
    const auto stopped = [=](int k) { return k < 8000 ? 0.0 : rate * std::min(k - 8000, ticks) * 1e-3; };
    const StillStand s = standing_with(stopped, 5, 20000, [=](int) { return bias; });
    std::printf("seed 5, %.0f N/s from tick 8000, held at %.1f N from tick %d, total force %+.0f N off: raised at tick %d "
                "as %s, end %s, estimate %.2f N, end error %.2f N\n",
                rate, plateau, 8000 + ticks, bias, s.raised_at, std::string(to_string(s.first_type)).c_str(),
                std::string(to_string(s.end_type)).c_str(), s.end_estimate_N, s.end_error_N);
    EXPECT_EQ(s.first_type, FaultType::drift);
    EXPECT_EQ(s.end_type, FaultType::offset);
    EXPECT_NEAR(s.end_estimate_N, plateau, 1.5);
    EXPECT_LT(std::abs(s.end_error_N), 1.5);
    EXPECT_EQ(s.others_flagged, 0);
  }
}

TEST(ContactForceFdi, AHealthyStillStandIsNoFaultEvenWithTheTotalForceWandering) {
  // The total force's error wanders by 60 N (within sum_threshold_N, 80 N) over 20 s.
  const auto wanders = [](int k) { return 60.0 * std::sin(2.0 * std::numbers::pi * k * 1e-3 / 20.0); };
  const StillStand s = standing_with(no_error, 5, 30000, wanders);
  EXPECT_EQ(s.raised_at, -1);
  EXPECT_EQ(s.others_flagged, 0);
}

// An offset that begins as its pad lands is no gain. The left foot swings (its pads read 0) and
// lands at 1 s; from its landing pad 0 reads its load + 120 N, the total force exact. Across the
// landing, r (0, then 120 N) and pad 0's reading (0, then load + 120 N) lie on one line, a gain of
// about 1.5 to a fit over the whole window; within the stance r stays 120 N while the load swings
// by 100 N, which no gain explains: the gain test does not raise it (3 s, past its 2 s window).
FaultType after_an_offset_from_landing() {
  Feet feet(suralp(), 1e-3);
  FaultType worst = FaultType::none;
  for (int k = 0; k < 4000; ++k) {
    const double t = k * 1e-3;
    const bool airborne = k < 1000;
    feet.left_foot_at(airborne ? 0.1 : 0.0);
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = 200.0 + 100.0 * std::sin(2.0 * std::numbers::pi * (1.3 * t + 0.17 * j));
      feet.measured[j] = j < 4 && airborne ? 0.0 : load;
      truth += feet.measured[j];
    }
    if (!airborne) feet.measured[0] += 120.0;
    feet.step(truth);
    if (feet.type(0) == FaultType::gain) worst = FaultType::gain;
  }
  return worst;
}

TEST(ContactForceFdi, AnOffsetThatBeginsAsItsPadLandsIsNoGain) {
  EXPECT_NE(after_an_offset_from_landing(), FaultType::gain);
}

TEST(ContactForceFdi, UnloadedPadOnItsZeroLevelIsNoEvidenceOfAFrozenSensor) {
  Feet feet(suralp(), 1e-3);
  feet.left_foot_at(0.1);  // the left foot in the air: its pads carry nothing
  for (int k = 0; k < 500; ++k) {
    for (std::size_t j = 4; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    feet.measured[0] = 0.0;  // a sensor that clips at zero: exact zeros, healthy
    feet.measured[1] = 1.3;  // a sensor stuck at 1.3 N: no noisy sensor repeats that
    feet.measured[2] = k % 2 == 0 ? 0.5 : -0.5;
    feet.measured[3] = 0.0;
    feet.step();
    ASSERT_EQ(feet.type(0), FaultType::none) << "tick " << k;
    ASSERT_EQ(feet.type(1), k >= 20 ? FaultType::frozen : FaultType::none) << "tick " << k;
  }
}

TEST(ContactForceFdi, AZeroIsFrozenEvidenceOnlyWhereTheLoadSurelyExceedsADriversZeroClamp) {
  // Both feet on the ground; pad 0 reads exactly 0 from the start while the total force leaves it
  // `load` N (its leave-one-out force). n_f = 20 ticks at 1 kHz (frozen_min_s). A zero says only
  // that the load is under the driver's clamp (zero_clamp_N, 0 when none is known), and the
  // leave-one-out force is known within sum_threshold_N = 80 N: 12 N is no evidence; 200 N is,
  // frozen on tick 20; 100 N is under a 30 N clamp but not under none.
  struct Case {
    double clamp_N, load_N;
    bool frozen;
  };
  for (const Case& c : {Case{0.0, 12.0, false}, Case{0.0, 200.0, true}, Case{0.0, 100.0, true}, Case{30.0, 100.0, false},
                        Case{30.0, 200.0, true}}) {
    SCOPED_TRACE("zero_clamp_N " + std::to_string(c.clamp_N) + ", load " + std::to_string(c.load_N) + " N");
    ContactForceFdi::Params p = suralp();
    p.zero_clamp_N = c.clamp_N;
    Feet feet(p, 1e-3);
    for (int k = 0; k < 500; ++k) {
      double sum = 0.0;
      for (std::size_t j = 1; j < kChannels; ++j) sum += feet.measured[j] = moving(j, k, 0.0);
      feet.measured[0] = 0.0;
      feet.step(sum + c.load_N);
      ASSERT_EQ(feet.type(0), c.frozen && k >= 20 ? FaultType::frozen : FaultType::none) << "tick " << k;
    }
  }
}

TEST(ContactForceFdi, NoiseTestTellsWhiteJitterFromAFastSmoothLoadAndFromAChatteringFoot) {
  // 200 Hz: the 0.05 s window is 10 ticks; 6 second differences above 4 sqrt(6) 2 N = 19.6 N,
  // with the foot's summed reading above 2 x 19.6 N (4 pads), make a burst when the window is
  // rougher than it moves (sum d2^2 > sum d1^2). +-16 N jitter: |d2| = 64 N (58 N on the foot,
  // whose other pads alternate by 1 N).
  Feet feet(suralp(), 5e-3), chatter(suralp(), 5e-3);
  for (int k = 0; k < 100; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = chatter.measured[j] = moving(j, k, 0.0);
    const double jitter = k % 2 == 0 ? 16.0 : -16.0;
    feet.measured[1] = 300.0 + jitter;              // white-like: a noise burst
    feet.measured[5] = 300.0 + 80.0 * k + jitter;   // |d1| = 48 or 112 N: a load moving fast
    chatter.measured[2] = 300.0 + jitter;            // two pads of one foot trading load:
    chatter.measured[3] = 300.0 - jitter;            // each rough, their foot's sum smooth
    feet.step();
    chatter.step();
    // The burst is judged once 6 large differences are in: ticks 1..6 (at tick 1 the difference
    // is the one-tick change, 32 N, and the foot's sum has no history yet).
    ASSERT_EQ(feet.type(1), k >= 6 ? FaultType::noise : FaultType::none) << "tick " << k;
    ASSERT_EQ(feet.type(5), FaultType::none) << "tick " << k;
    ASSERT_EQ(chatter.type(2), FaultType::none) << "tick " << k;
    ASSERT_EQ(chatter.type(3), FaultType::none) << "tick " << k;
  }
}

// A noise burst (+-12 N alternating: every second difference 48 N, above 4 sqrt(6) 2 N) on a
// loaded pad from tick 200 to 499, with a spike of 150 N every 100 ticks in it (tick 250, 350,
// 450: 10 Hz, so the spike hold would be ln(100) / 10 Hz = 0.46 s). The spikes are the noise's:
// the noise test alone clears the flag, once its window is quiet (38 ticks) and clear_s (50 ticks)
// has passed, not 0.46 s after the last spike.
TEST(ContactForceFdi, ANoiseBurstIsClearedByTheNoiseTestNotHeldByItsSpikes) {
  Feet feet(suralp(), 1e-3);
  int cleared_at = -1;
  for (int k = 0; k < 1200; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    if (k >= 200 && k < 500) {
      feet.measured[2] = 300.0 + (k % 2 == 0 ? 12.0 : -12.0) + (k % 100 == 50 ? 150.0 : 0.0);
    }
    feet.step();
    if (k == 400) {
      EXPECT_EQ(feet.type(2), FaultType::noise);
    }
    if (k >= 500 && cleared_at < 0 && feet.type(2) == FaultType::none) cleared_at = k;
    if (cleared_at >= 0) {
      ASSERT_EQ(feet.type(2), FaultType::none) << "tick " << k;
    }
  }
  ASSERT_GE(cleared_at, 500);
  EXPECT_LE(cleared_at, 500 + 38 + 50 + 10);
}

TEST(ContactForceFdi, ALoadedNoiseBurstTriplesTheStepThatConfirmsANeighboursJump) {
  // Pad 2 reads a noise burst (+-12 N about its 300 N load) from tick 200, flagged noise by tick
  // 400; F_z is the true loads' sum, so the sum residual carries the burst's swings. A neighbour's
  // 50 N step at tick 600 is then not confirmed (it takes 3 x jump_confirm_N = 75 N: the swings
  // of a real burst move a 10 ms mean by tens of newtons); a 100 N step at tick 800 is, on its
  // window's last tick (809). Without the burst the 50 N step is an offset at once (tick 609).
  for (const bool burst : {true, false}) {
    SCOPED_TRACE(burst ? "with the burst" : "without it");
    Feet feet(suralp(), 1e-3);
    for (int k = 0; k < 900; ++k) {
      double fz = 0.0;
      for (std::size_t j = 0; j < kChannels; ++j) {
        feet.measured[j] = moving(j, k, 0.0);
        fz += feet.measured[j];
      }
      if (burst && k >= 200) feet.measured[2] += k % 2 == 0 ? 12.0 : -12.0;
      if (k >= 600) feet.measured[5] += 50.0;
      if (k >= 800) feet.measured[6] += 100.0;
      feet.step(fz);
      if (k == 400 && burst) {
        ASSERT_EQ(feet.type(2), FaultType::noise);
      }
      ASSERT_EQ(feet.type(5), !burst && k >= 609 ? FaultType::offset : FaultType::none) << "tick " << k;
      ASSERT_EQ(feet.type(6), k >= 809 ? FaultType::offset : FaultType::none) << "tick " << k;
    }
  }
}

TEST(ContactForceFdi, ANoiseBurstIsRecoveredFromItsLeaveOneOutForceWhereItsLowPassWouldLag) {
  // Pad 2 reads +-12 N of noise about its load from tick 200 (flagged noise by tick 400; F_z is the
  // true loads' sum, the other pads healthy). From tick 500 its load rises 3 N per tick by 300 N.
  // A 10 Hz low-pass of the reading lags that ramp by 3 N x 15.9 ticks = 48 N; the leave-one-out
  // force follows it, and the low-pass of reading - force keeps only the noise's remainder, under
  // 1 N here: recovered within 2 N of the load through the ramp.
  Feet feet(suralp(), 1e-3);
  double worst = 0.0;
  for (int k = 0; k < 700; ++k) {
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    const double load = moving(2, k, 0.0) + (k < 500 ? 0.0 : std::min(300.0, 3.0 * (k - 500)));
    feet.measured[2] = load;
    for (double x : feet.measured) fz += x;
    if (k >= 200) feet.measured[2] += k % 2 == 0 ? 12.0 : -12.0;
    feet.step(fz);
    if (k == 400) {
      ASSERT_EQ(feet.type(2), FaultType::noise);
    }
    if (k >= 500) {
      ASSERT_EQ(feet.type(2), FaultType::noise) << "tick " << k;
      worst = std::max(worst, std::abs(feet.outs[ContactForceFdi::kRecovered][2] - load));
    }
  }
  EXPECT_LT(worst, 2.0);
}

TEST(ContactForceFdi, AJumpMustBeASurpriseNotAFastRamp) {
  // 200 Hz, F_z steady: a pad whose load speeds up smoothly (10 N per tick per tick) to 30 N per
  // tick moves the sum residual as much as a step would, but its linear prediction foresees each
  // tick: no jump. A 30 N step on a steady pad is both a change and a surprise: an offset of the
  // step's size (29 N: the pad's own alternation takes 1 N) once the 0.01 s window confirms it.
  Feet ramp(suralp(), 5e-3), step(suralp(), 5e-3);
  double fz = 0.0;
  for (std::size_t j = 0; j < kChannels; ++j) fz += moving(j, 0, 0.0);
  double speed = 0.0, load = 0.0;
  for (int k = 0; k < 40; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) ramp.measured[j] = step.measured[j] = moving(j, k, 0.0);
    if (k >= 20) {
      speed = std::min(30.0, speed + 10.0);
      load += speed;
      ramp.measured[2] += load;
      step.measured[2] += 30.0;
    }
    ramp.step(fz);
    step.step(fz);
    ASSERT_EQ(ramp.type(2), FaultType::none) << "tick " << k;
    ASSERT_EQ(step.type(2), k >= 21 ? FaultType::offset : FaultType::none) << "tick " << k;
  }
  EXPECT_NEAR(step.outs[ContactForceFdi::kFaultEstimate][2], 29.0, 1e-9);
}

// Pad 3 is dead at its air level (+-1 N) while it carries 150 N, so the sum residual sits at
// -150 N, beyond its 80 N bound, with no pad named yet. On tick 500, 100 N of pad 3's load moves to
// pad 2 (read right: +100 N in one tick). The residual steps by +100 N, as pad 2's own step: with
// `sum_held` false the step is no evidence (without the rule, pad 2 was raised a +100 N offset on
// tick 509, when its jump window completes). `fz_error_N`: F_z's error, which moves the residual too.
std::vector<int> transfer_flags(double fz_error_N) {
  Feet feet(suralp(), 1e-3);
  std::vector<int> first(kChannels, -1);
  for (int k = 0; k < 800; ++k) {
    const double noise = k % 2 == 0 ? 1.0 : -1.0;
    double fz = fz_error_N;
    for (std::size_t j = 0; j < kChannels; ++j) {
      double load = j == 3 ? 150.0 : 200.0 + 10.0 * static_cast<double>(j);
      if (k >= 500 && j == 3) load -= 100.0;
      if (k >= 500 && j == 2) load += 100.0;
      fz += load;
      feet.measured[j] = (j == 3 ? 0.0 : load) + noise;
    }
    feet.step(fz);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (first[j] < 0 && feet.outs[ContactForceFdi::kFault][j] != 0.0) first[j] = k;
    }
  }
  return first;
}

TEST(ContactForceFdi, AStepIsNoEvidenceWhileTheSumIsAlreadyOffWithNoPadNamed) {
  const auto first = transfer_flags(0.0);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 3) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
  // The same step with the residual within its bound (F_z reading 150 N more: pad 3's missing
  // load hidden from the sum) is a step of pad 2's sensor, as before.
  EXPECT_EQ(transfer_flags(-150.0)[2], 509);
}

TEST(ContactForceFdi, APadTakingItsLoadBackIsALandingNotAJumpOrASpike) {
  // 200 Hz, both feet flat, F_z steady through the ring (the trunk IMU does not see a pad's
  // contact). Pad 2 sits on the ground with no load (the others carry F_z, its leave-one-out
  // force is 0) and reads its zero level; at tick 20 it takes 45 N in one tick and chatters (45,
  // -5, 70 N) before it settles at 80 N, which F_z then carries too: the sum residual steps like
  // a sensor's would, but a pad's own landing is not a jump and its ringing is not a spike. The
  // same 60 N step on a loaded pad is an offset, as it is on the landed pad once
  // touchdown_guard_s (0.15 s = 30 ticks) has passed.
  const std::array<double, 4> landing{45.0, -5.0, 70.0, 80.0};
  Feet landed(suralp(), 5e-3), loaded(suralp(), 5e-3);
  double fz = 0.0;
  for (std::size_t j = 0; j < kChannels; ++j) fz += j == 2 ? 0.0 : moving(j, 0, 0.0);
  for (int k = 0; k < 80; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) landed.measured[j] = loaded.measured[j] = moving(j, k, 0.0);
    const double alternation = k % 2 == 0 ? 0.0 : 1.0;
    landed.measured[2] = k < 20 ? alternation : k < 24 ? landing[static_cast<std::size_t>(k - 20)] : 80.0 + alternation;
    if (k >= 60) landed.measured[2] += 60.0;  // 0.2 s after its landing: a sensor step
    if (k >= 20) loaded.measured[2] += 60.0;
    landed.step(k < 24 ? fz : fz + 80.0);
    loaded.step(fz + moving(2, 0, 0.0));
    ASSERT_EQ(landed.type(2), k >= 61 ? FaultType::offset : FaultType::none) << "tick " << k;
    ASSERT_EQ(loaded.type(2), k >= 21 ? FaultType::offset : FaultType::none) << "tick " << k;
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 2) {
        ASSERT_EQ(landed.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
}

TEST(ContactForceFdi, ALandedPadIsJudgedAgainOnceItsRingHasDiedOut) {
  // The landing of the test above (200 Hz: 45, -5, 70 N, then 80 N from tick 23, in F_z from tick
  // 24), and a 60 N sensor step at tick 40: 0.1 s after the landing, inside touchdown_guard_s, but the ring ended
  // at tick 22 (its last change above jump_threshold_N) and jump_window_s (2 ticks) has passed
  // since. The step is an offset on the next tick, as on any loaded pad; the ring is not.
  const std::array<double, 4> landing{45.0, -5.0, 70.0, 80.0};
  Feet landed(suralp(), 5e-3);
  double fz = 0.0;
  for (std::size_t j = 0; j < kChannels; ++j) fz += j == 2 ? 0.0 : moving(j, 0, 0.0);
  for (int k = 0; k < 60; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) landed.measured[j] = moving(j, k, 0.0);
    const double alternation = k % 2 == 0 ? 0.0 : 1.0;
    landed.measured[2] = k < 20 ? alternation : k < 24 ? landing[static_cast<std::size_t>(k - 20)] : 80.0 + alternation;
    if (k >= 40) landed.measured[2] += 60.0;
    landed.step(k < 24 ? fz : fz + 80.0);
    ASSERT_EQ(landed.type(2), k >= 41 ? FaultType::offset : FaultType::none) << "tick " << k;
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 2) {
        ASSERT_EQ(landed.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
}

}  // namespace
}  // namespace ftsense::biped

namespace ftsense::biped {
namespace {

// The left foot swings for 200 ticks, then lands and pad 0's true load rises smoothly to 400 N
// (2 N per tick) while the foot's other pads read 100 N and the right foot's move. Pad 0 reads
// `reading(k, load)` +- 1 N; `each(k, feet)` sees every tick after its step.
template <class Reading, class Each>
void swing_then_landing(Feet& feet, Reading reading, Each each) {
  for (int k = 0; k < 600; ++k) {
    const bool landed = k >= 200;
    feet.left_foot_at(landed ? 0.0 : 0.1);
    const double load = landed ? std::min(400.0, 2.0 * (k - 200)) : 0.0;
    for (std::size_t j = 1; j < kChannels; ++j) feet.measured[j] = j < 4 ? (landed ? 100.0 + (k % 2) : k % 2) : moving(j, k, 0.0);
    double others = 0.0;
    for (std::size_t j = 1; j < kChannels; ++j) others += feet.measured[j];
    const double noise = k % 2 == 0 ? 1.0 : -1.0;
    feet.measured[0] = reading(k, load) + noise;
    feet.step(others + load);
    each(k, feet);
  }
}

// Pad 0 reads 150 N in the swing (raised as an offset by the airborne test). A frozen output keeps
// reading 150 N: re-typed frozen once the leave-one-out force has spanned 2 sum_threshold_N =
// 160 N; an offset reads load + 150 N and stays an offset.
FaultType after_landing(bool frozen, double& recovered) {
  Feet feet(suralp(), 1e-3);
  swing_then_landing(
      feet, [&](int, double load) { return frozen ? 150.0 : load + 150.0; },
      [](int k, const Feet& f) {
        if (k == 150) {
          EXPECT_EQ(f.type(0), FaultType::offset) << "the airborne test raises it";
        }
      });
  recovered = feet.outs[ContactForceFdi::kRecovered][0];
  return feet.type(0);
}

// The same swing and landing, but pad 0 reads its zero level until tick 100 and then freezes at
// 300 N +- 1 N in the air: a jump, raised as an offset 10 ticks later (the 0.01 s confirmation
// window), when its 10 Hz smoothed reading has covered only half the step. The span that tells a
// frozen output is the output's own, from when that smoothing has settled: without the wait, the
// rise alone (about 140 N) is more than follow_ratio of the 400 N the load spans.
FaultType frozen_by_a_jump_in_the_air(int& raised_at) {
  Feet feet(suralp(), 1e-3);
  raised_at = -1;
  swing_then_landing(
      feet, [](int k, double) { return k < 100 ? 0.0 : 300.0; },
      [&](int k, const Feet& f) {
        if (raised_at < 0 && f.type(0) != FaultType::none) raised_at = k;
      });
  return feet.type(0);
}

TEST(ContactForceFdi, AFrozenOutputsSpanStartsAfterTheStepThatRaisedIt) {
  int raised_at = -1;
  EXPECT_EQ(frozen_by_a_jump_in_the_air(raised_at), FaultType::frozen);
  EXPECT_EQ(raised_at, 109) << "a jump confirmed at the end of its 10-tick window";
}

// A frozen output re-typed by the follow test (pad 0 reads 150 N from the swing on) while its load
// swings up to 1000 N and back to 200 N; from tick 1100 its reading follows the load again, which
// rises 2 N per tick to `load_after` N. Returns the tick it is re-admitted at (-1: never), checks
// it was frozen at tick 1099 and stays re-admitted once it is.
int readmitted_after_freeze(double load_after, int ticks) {
  Feet feet(suralp(), 1e-3);
  int readmitted_at = -1;
  for (int k = 0; k < ticks; ++k) {
    const bool landed = k >= 200;
    feet.left_foot_at(landed ? 0.0 : 0.1);
    const double load = !landed  ? 0.0
                        : k < 600  ? 200.0 + 2.0 * (k - 200)
                        : k < 1000 ? 1000.0 - 2.0 * (k - 600)
                        : k < 1100 ? 200.0
                                   : std::min(load_after, 200.0 + 2.0 * (k - 1100));
    for (std::size_t j = 1; j < kChannels; ++j) feet.measured[j] = j < 4 ? (landed ? 100.0 + (k % 2) : k % 2) : moving(j, k, 0.0);
    double others = 0.0;
    for (std::size_t j = 1; j < kChannels; ++j) others += feet.measured[j];
    const double noise = k % 2 == 0 ? 1.0 : -1.0;
    feet.measured[0] = (k < 1100 ? 150.0 : load) + noise;
    feet.step(others + load);
    if (k == 1099) {
      EXPECT_EQ(feet.type(0), FaultType::frozen);
    }
    if (k >= 1100 && readmitted_at < 0 && feet.type(0) == FaultType::none) readmitted_at = k;
    if (readmitted_at >= 0) {
      EXPECT_EQ(feet.type(0), FaultType::none) << "tick " << k;
    }
  }
  return readmitted_at;
}

// Load to 500 N after the fault. Re-admission judges each load move of 2 sum_threshold_N (160 N)
// on its own: the first one after the fault ends re-admits it, although the reading never matches
// the 800 N span the load covered while it was frozen.
TEST(ContactForceFdi, AFrozenOutputIsReadmittedOnTheFirstLoadMoveItFollowsAgain) {
  const int readmitted_at = readmitted_after_freeze(500.0, 1400);
  ASSERT_GE(readmitted_at, 1100);
  // The load moves 160 N in 80 ticks; the 10 Hz smoothing of both lags alike.
  EXPECT_LE(readmitted_at, 1100 + 80 + 30);
}

// The same frozen output, but when its fault ends (tick 1100) the load moves only 100 N (200 to
// 300 N, 2 N per tick), less than the 2 sum_threshold_N (160 N) that the follow test's own
// decisions wait for. Its reading leaves the frozen 150 N for the load's 200 N and follows it:
// it has spanned sum_threshold_N (80 N) at 230 N (tick 1115), more than half the load's move. No
// stuck sensor's noise does that, so it is re-admitted then (plus the 10 Hz smoothing's lag),
// where it used to wait for the next 160 N move.
TEST(ContactForceFdi, AFrozenOutputWhoseReadingMovesBySumThresholdAgainIsReadmitted) {
  const int readmitted_at = readmitted_after_freeze(300.0, 1600);
  ASSERT_GE(readmitted_at, 1115);
  EXPECT_LE(readmitted_at, 1115 + 30);
}

// Both feet flat, F_z exact. Pad 0 steps by +60 N at tick 100 (a confirmed jump: an offset) and
// back at tick 400, while pad 5 of the other foot spikes every 20 ticks from tick 205 (flagged
// spikes, recovered by its own median, not substituted from the total force). The jump back is
// confirmed in its 10-tick window as the end of the offset: a spiking neighbour does not raise
// the confirmation to the 3 jump_confirm_N (75 N) that a substituted one needs.
TEST(ContactForceFdi, AnOffsetEndsWithItsJumpBackWhileANeighbourSpikes) {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 500; ++k) {
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = moving(j, k, 0.0);
      truth += feet.measured[j];
    }
    if (k >= 100 && k < 400) feet.measured[0] += 60.0;
    if (k >= 200 && k % 20 == 5) feet.measured[5] += 150.0;
    feet.step(truth);
    if (k == 150) {
      EXPECT_EQ(feet.type(0), FaultType::offset);
    }
    if (k == 399) {
      EXPECT_EQ(feet.type(0), FaultType::offset);
      EXPECT_EQ(feet.type(5), FaultType::spikes);
    }
    if (k >= 410) {
      ASSERT_EQ(feet.type(0), FaultType::none) << "tick " << k;
    }
  }
}

// Both feet flat, F_z exact. Pad 2 carries 200 N (+ its 1 N alternation) when, at tick 50, its
// reading doubles (gain x2) or gains 200 N (offset): the same jump, raised as an offset 10 ticks
// later. Then its load rises by 1 N per tick to 500 N. Taken as x - b, a gain leaves a sum
// residual that grows with the load; taken as x / k, k = 1 + jump / load before = 1 + 199 / 201,
// it leaves none: re-typed gain once the load has moved by 2 sum_threshold_N. An offset's residual
// stays at zero taken as x - b: it stays an offset.
// One tick with pad 2 carrying `load` and reading `reading`, the other pads healthy and moving,
// F_z exact.
void step_pad2(Feet& feet, int k, double load, double reading) {
  double fz = load;
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j == 2) continue;
    feet.measured[j] = moving(j, k, 0.0);
    fz += feet.measured[j];
  }
  feet.measured[2] = reading;
  feet.step(fz);
}

FaultType after_a_jump_under_a_rising_load(bool gain, double& recovered, double& load, int ticks = 600) {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < ticks; ++k) {
    load = (k < 100 ? 200.0 : std::min(500.0, 200.0 + (k - 100))) + (k % 2 == 0 ? 0.0 : 1.0);
    step_pad2(feet, k, load, k < 50 ? load : gain ? 2.0 * load : load + 200.0);
  }
  recovered = feet.outs[ContactForceFdi::kRecovered][2];
  return feet.type(2);
}

TEST(ContactForceFdi, AJumpUnderLoadIsAGainWhenTheResidualGrowsWithTheLoadAsAnOffset) {
  double recovered = 0.0, load = 0.0;
  EXPECT_EQ(after_a_jump_under_a_rising_load(true, recovered, load), FaultType::gain);
  EXPECT_NEAR(recovered, 2.0 * load / (1.0 + 199.0 / 201.0), 1e-9) << "x / k, k from the onset jump";
  EXPECT_EQ(after_a_jump_under_a_rising_load(false, recovered, load), FaultType::offset);
  EXPECT_NEAR(recovered, load + 1.0, 1e-9) << "x - b, b = 199 N: the jump";
}

TEST(ContactForceFdi, AnUndecidedOffsetOrGainIsRecoveredByTheModelNearerItsLeaveOneOutForce) {
  // Tick 180: the load has moved 80 N from L0, under the 2 sum_threshold_N the test waits for, so
  // the type is still offset. The gain's x / k (k = 1 + 199 / 201 from the onset jump) lies
  // 1.4 N from the (exact) leave-one-out force, x - b 81 N off it (more than jump_confirm_N, 25 N,
  // further): recovered as x / k. A true offset's x - b lies on it: kept.
  double recovered = 0.0, load = 0.0;
  EXPECT_EQ(after_a_jump_under_a_rising_load(true, recovered, load, 181), FaultType::offset);
  EXPECT_NEAR(recovered, 2.0 * load / (1.0 + 199.0 / 201.0), 1e-9);
  EXPECT_EQ(after_a_jump_under_a_rising_load(false, recovered, load, 181), FaultType::offset);
  EXPECT_NEAR(recovered, load + 1.0, 1e-9);
}

TEST(ContactForceFdi, ANegativeReadingOfALoadedPadIsNoForceAndItsLeaveOneOutForceStandsIn) {
  // Pad 2 (load about 220 N) reads its load negated for three ticks, fewer than the
  // negative-reading test needs to type it: unflagged, recovered as its (exact) leave-one-out force
  // on each; its reading itself on the ticks around them.
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 320; ++k) {
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = moving(j, k, 0.0);
      truth += feet.measured[j];
    }
    const double load = feet.measured[2];
    const bool negated = k >= 300 && k < 303;
    if (negated) feet.measured[2] = -load;
    feet.step(truth);
    ASSERT_EQ(feet.type(2), FaultType::none) << "tick " << k;
    EXPECT_NEAR(feet.outs[ContactForceFdi::kRecovered][2], load, 1e-9) << "tick " << k;
    EXPECT_NEAR(feet.outs[ContactForceFdi::kFaultEstimate][2], negated ? -2.0 * load : 0.0, 1e-9) << "tick " << k;
  }
}

TEST(ContactForceFdi, AnAirborneReadingBeyondItsNoiseIsNoForceBeforeTheAirTestRaisesIt) {
  // The left foot in the air (pads at 5 cm), the right one carrying the robot. From tick 100 pad 0
  // reads 50 N (beyond airborne_threshold_N, 4 sigma = 8 N), pad 1 about 3 N (within it). Before
  // the air test raises pad 0, its value is 0, what a pad in the air carries; pad 1 keeps its
  // reading.
  Feet feet(suralp(), 1e-3);
  feet.left_foot_at(0.05);
  int raised = -1;
  for (int k = 0; k < 400; ++k) {
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = j < 4 ? 0.0 : moving(j, k, 0.0);
      truth += feet.measured[j];
    }
    if (k >= 100) {
      feet.measured[0] = 50.0 + (k % 2 == 0 ? 0.0 : 1.0);
      feet.measured[1] = 3.0 + (k % 2 == 0 ? 0.5 : -0.5);  // a live sensor: never repeats itself
    }
    feet.step(truth);
    if (raised < 0 && feet.type(0) != FaultType::none) raised = k;
    if (k >= 100 && raised < 0) {
      ASSERT_EQ(feet.outs[ContactForceFdi::kRecovered][0], 0.0) << "tick " << k;
    }
    EXPECT_EQ(feet.type(1), FaultType::none) << "tick " << k;
    EXPECT_EQ(feet.outs[ContactForceFdi::kRecovered][1], feet.measured[1]) << "tick " << k;
  }
  EXPECT_GT(raised, 100) << "the air test needs its samples first";
}

// As above, but the load rises by 4 N per tick from the onset (tick 50) to 700 N, so it has moved
// 356 N from L0 = 200 N when the follow test's span starts (the flag raised on tick 59, its
// smoother settled five time constants of 10 Hz later, 0.0796 s: tick 139). Returns the first
// tick typed gain (-1: never).
int gain_typed_after_a_jump_under_a_fast_rising_load() {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 400; ++k) {
    const double load = (k < 50 ? 200.0 : std::min(700.0, 200.0 + 4.0 * (k - 50))) + (k % 2 == 0 ? 0.0 : 1.0);
    step_pad2(feet, k, load, k < 50 ? load : 2.0 * load);
    if (feet.type(2) == FaultType::gain) return k;
  }
  return -1;
}

TEST(ContactForceFdi, AGainIsTypedOnceTheLoadHasMovedFromWhereBothModelsMeetNotSinceTheSpanStarted) {
  // Judged on the tick the span starts (139; the type shows from the next): the load is 356 N from
  // L0 there. Judged on the span since the smoother settled, it waited until the smoothed force
  // had risen a further 160 N.
  EXPECT_EQ(gain_typed_after_a_jump_under_a_fast_rising_load(), 140);
}

TEST(ContactForceFdi, AnOffsetWhoseReadingDoesNotFollowTheLoadIsAFrozenOutputThatKeepsItsNoise) {
  double recovered = 0.0;
  EXPECT_EQ(after_landing(true, recovered), FaultType::frozen);
  EXPECT_NEAR(recovered, 400.0, 1e-9) << "substituted from the total force: F_z minus the other pads";
  EXPECT_EQ(after_landing(false, recovered), FaultType::offset);
  EXPECT_NEAR(recovered, 400.0, 2.0) << "the reading minus the airborne mean (150 N)";
}

}  // namespace
}  // namespace ftsense::biped

namespace ftsense::biped {
namespace {

// Pad 0 steps by +30 N at 100 N load (a confirmed jump: an offset), then reads 0 in the air, so
// the jump is taken for a gain k = 1 + 30 / 100. After landing, pad 0 reads either its true
// load (healthy: the correction only adds residual) or 1.3 times it (a gain fault). All pads of
// the foot carry constant loads, so the regression fits each alike and isolates none: only the
// model comparison can let the healthy pad go, once the correction has held for the 2 s window
// (the correction moves the reading by 23 N, under gain_min_load_N = 30 N: too little for the
// comparison within one stance).
FaultType gain_held_then(bool healthy, FaultType& middle) {
  Feet feet(suralp(), 1e-3);
  FaultType type = FaultType::none;
  for (int k = 0; k < 4000; ++k) {
    const bool lifted = k >= 300 && k < 500;
    feet.left_foot_at(lifted ? 0.1 : 0.0);
    const double load = lifted ? 0.0 : 100.0;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = j < 4 ? load + (k % 2) : moving(j, k, 0.0);
    double truth = 0.0;
    for (double x : feet.measured) truth += x;
    if (k >= 100 && k < 300) feet.measured[0] += 30.0;
    if (k >= 500 && !healthy) feet.measured[0] *= 1.3;
    feet.step(truth);
    if (k == 150) {
      EXPECT_EQ(feet.type(0), FaultType::offset) << "the confirmed jump";
    }
    if (k == 1000) middle = feet.type(0);
    type = feet.type(0);
  }
  return type;
}

// One tick of the walk below, before its total force's errors: the left foot 10 cm up over ticks
// [300, 500), its pads loaded 100 N before and 300 N after (+ 0 or 1 N); the right foot's pads
// moving(), or 10 cm up and reading 0 while `right_lifted`. l_foot/p1 reads +100 N over ticks
// [100, 300) and, unless `healthy`, 1.5 times its load from tick 500. Returns the pads' true sum.
double doubling_gain_tick(Feet& feet, int k, bool right_lifted, bool healthy) {
  const bool lifted = k >= 300 && k < 500;
  feet.left_foot_at(lifted ? 0.1 : 0.0);
  std::fill(feet.height.begin() + 4, feet.height.end(), right_lifted ? 0.1 : 0.0);
  const double load = lifted ? 0.0 : k < 300 ? 100.0 : 300.0;
  for (std::size_t j = 0; j < kChannels; ++j) {
    feet.measured[j] = j < 4 ? load + (k % 2) : right_lifted ? 0.0 : moving(j, k, 0.0);
  }
  double truth = 0.0;
  for (double x : feet.measured) truth += x;
  if (k >= 100 && k < 300) feet.measured[0] += 100.0;
  if (k >= 500 && !healthy) feet.measured[0] *= 1.5;
  return truth;
}

// As gain_held_then, with a +100 N jump at 100 N: in the air it is taken for a gain (k = 1.5,
// refined while loaded before the lift). The pad lands at tick 500 on a 300 N load and reads it
// (healthy: the gain ended in the air, and the correction x / k reads 200 N) or 1.5 times it
// (still faulty). The total force errs by the landing's impact, impact_N e^(-(k - 500) / 20)
// (20 ms) over the guard's 150 ticks. Returns the first tick from 500 on where pad 0 is not a
// gain fault (-1: none), and its recovered value then.
// With right_landing_error_N, the right foot also swings over ticks 850-999 and lands on tick 1000,
// the total force off by that much over its guard's 150 ticks.
int doubling_gain_cleared_at(bool healthy, double& recovered_then, double impact_N = 0.0,
                             double right_landing_error_N = 0.0) {
  Feet feet(suralp(), 1e-3);
  int cleared = -1;
  for (int k = 0; k < 1500 && cleared < 0; ++k) {
    const bool right_lifted = right_landing_error_N != 0.0 && k >= 850 && k < 1000;
    double truth = doubling_gain_tick(feet, k, right_lifted, healthy);
    if (k >= 500 && k < 650) truth += impact_N * std::exp(-(k - 500) / 20.0);
    if (k >= 1000 && k < 1150) truth += right_landing_error_N;
    feet.step(truth);
    if (k == 499) {
      EXPECT_EQ(feet.type(0), FaultType::gain) << "the jump, read 0 in the air, is a gain";
    }
    if (k >= 500 && feet.type(0) != FaultType::gain) {
      cleared = k;
      recovered_then = feet.outs[ContactForceFdi::kRecovered][0];
    }
  }
  return cleared;
}

TEST(ContactForceFdi, AGainThatEndedInTheAirIsDroppedWithinTheNextStance) {
  // Healthy after landing: the correction takes 100 N (beyond gain_min_load_N, 30 N) off a
  // residual that the reading leaves at 0.5 N. The touchdown guard's ticks (0.15 s, from the
  // touchdown seen on tick 501) are compared on their own and judged on the first tick after
  // it, before the jump test, resumed there, could blame a neighbour for the wrong correction's
  // moves. Until 2026-12-05 only the stance after the guard was compared (dropped at tick 700,
  // clear_s later), and before that the 2 s window decided, the channel reading 200 N against
  // 300 N until then.
  double recovered = 0.0;
  const int cleared = doubling_gain_cleared_at(true, recovered);
  std::printf("healthy after landing at tick 500: gain dropped at tick %d, recovered %.1f N\n", cleared, recovered);
  EXPECT_EQ(cleared, 501 + 150);  // the first tick after the guard
  EXPECT_NEAR(recovered, 300.0, 1.0);
  // Still faulty: the correction is what lowers the residual, and it stays.
  EXPECT_EQ(doubling_gain_cleared_at(false, recovered), -1);
  // With the landing's impact in the total force, +-300 N fading over 20 ms (twice the faulty
  // correction's 150 N): the faulty pad is kept through the guard and after. Judged within the
  // guard on its first clear_s (a try), the +300 N pulse, of the correction's sign, dropped it
  // on tick 550. The healthy pad is dropped on the first tick after the guard with the +300 N
  // pulse; the -300 N one leans against the reading over the guard (there the correction leaves
  // less), and the stance after the guard drops it, clear_s later, as before.
  const int healthy_plus = doubling_gain_cleared_at(true, recovered, 300.0);
  const int faulty_plus = doubling_gain_cleared_at(false, recovered, 300.0);
  const int healthy_minus = doubling_gain_cleared_at(true, recovered, -300.0);
  const int faulty_minus = doubling_gain_cleared_at(false, recovered, -300.0);
  std::printf("impact +300 N: healthy dropped at tick %d, faulty at tick %d; -300 N: at ticks %d and %d\n",
              healthy_plus, faulty_plus, healthy_minus, faulty_minus);
  EXPECT_EQ(healthy_plus, 501 + 150);
  EXPECT_EQ(faulty_plus, -1);
  EXPECT_EQ(healthy_minus, 700);
  EXPECT_EQ(faulty_minus, -1);
  // The other foot's landing is no evidence of this pad: the total force 150 N off over the right
  // foot's guard (the correction's sign and size, which over the pad's own guard would drop it: the
  // stated limit) keeps the faulty gain held (in a review's probe, judged over every foot's guard,
  // it was dropped on tick 1152).
  const int faulty_other_foot = doubling_gain_cleared_at(false, recovered, 0.0, 150.0);
  std::printf("the right foot landing with the total force 150 N off: faulty dropped at tick %d\n", faulty_other_foot);
  EXPECT_EQ(faulty_other_foot, -1);
}

// As doubling_gain_cleared_at: pad 0 is held as a gain from the air (k printed) and lands on
// tick 500 on 130 N, healthy, its correction 130 / k wrong by the residual it leaves (within the
// 80 N sum bound). On tick step_at (651: the first after the guard, when the gain is dropped) pad
// 1's load steps from 100 N to 100 + step_N, read right. Returns the ticks x channels other than
// pad 0 flagged by tick 1000, and pad 0's k before the landing and the tick it was dropped.
int neighbour_flags_as_a_gain_is_dropped(double step_N, double& k_held, int& dropped, int step_at = 651) {
  Feet feet(suralp(), 1e-3);
  int others = 0;
  dropped = -1;
  for (int k = 0; k < 1000; ++k) {
    const bool lifted = k >= 300 && k < 500;
    feet.left_foot_at(lifted ? 0.1 : 0.0);
    const double load = lifted ? 0.0 : 100.0;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = j < 4 ? load + (k % 2) : moving(j, k, 0.0);
    if (k >= 500) feet.measured[0] = 130.0 + (k % 2);
    if (k >= step_at) feet.measured[1] += step_N;
    double truth = 0.0;
    for (double x : feet.measured) truth += x;
    if (k >= 100 && k < 300) feet.measured[0] += 100.0;
    feet.step(truth);
    if (k == 299) k_held = feet.measured[0] / feet.outs[ContactForceFdi::kRecovered][0];
    if (k == 499) {
      EXPECT_EQ(feet.type(0), FaultType::gain) << "the jump, read 0 in the air, is a gain";
    }
    if (k >= 500 && dropped < 0 && feet.type(0) != FaultType::gain) dropped = k;
    for (std::size_t j = 1; j < kChannels; ++j) others += feet.type(j) != FaultType::none ? 1 : 0;
  }
  return others;
}

TEST(ContactForceFdi, AJumpGroupStraddlingAGainsDropIsNotConfirmedByIt) {
  // Dropping the gain steps the jump test's residual by 130 (1 - 1 / k) on the next tick (it takes
  // a gain's reading as x / k). Pad 1's step of that size on the drop's tick, read right, leaves
  // the residual alone, but its group's two windows straddle the drop: without the rule that
  // drops such a group (and forms none while its window before holds a drop), the residual's
  // step from the drop confirmed pad 1 as an offset, on 50 ticks (run once with the rule left out).
  double k_held = 0.0;
  int dropped = -1;
  neighbour_flags_as_a_gain_is_dropped(0.0, k_held, dropped);
  const double drop_step = 130.0 * (1.0 - 1.0 / k_held);
  const int others = neighbour_flags_as_a_gain_is_dropped(drop_step, k_held, dropped);
  std::printf("gain k %.3f dropped at tick %d; pad 1 stepping by %.1f N then: others flagged on %d ticks\n", k_held,
              dropped, drop_step, others);
  EXPECT_EQ(dropped, 501 + 150);
  EXPECT_EQ(others, 0);
  // The same step 4 ticks after the drop: its window before holds the drop (without the rule,
  // pad 1 was an offset on 50 ticks; run once).
  const int others_after = neighbour_flags_as_a_gain_is_dropped(drop_step, k_held, dropped, 655);
  std::printf("pad 1 stepping 4 ticks after the drop: others flagged on %d ticks\n", others_after);
  EXPECT_EQ(others_after, 0);
}

// As doubling_gain_cleared_at, the pad landing healthy on tick 500, but the total force unknown
// from tick 640 (inside the guard) to 999: the pad lifts over ticks 700-799 and lands again on
// 800 reading 1.5 times its 300 N load (the gain present again). Returns the first tick from 500
// on where pad 0 is not a gain fault (-1: none).
int gain_judged_after_a_gap() {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 1500; ++k) {
    const bool lifted = (k >= 300 && k < 500) || (k >= 700 && k < 800);
    feet.left_foot_at(lifted ? 0.1 : 0.0);
    const double load = lifted ? 0.0 : k < 300 ? 100.0 : 300.0;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = j < 4 ? load + (k % 2) : moving(j, k, 0.0);
    double truth = 0.0;
    for (double x : feet.measured) truth += x;
    if (k >= 100 && k < 300) feet.measured[0] += 100.0;
    if (k >= 800) feet.measured[0] *= 1.5;
    feet.step(truth, k < 640 || k >= 1000);
    if (k >= 500 && feet.type(0) != FaultType::gain) return k;
  }
  return -1;
}

TEST(ContactForceFdi, AGuardsGainComparisonIsNotJudgedAStanceLater) {
  // The guard's sums from the healthy landing (tick 500-639) favour the reading; the first usable
  // tick after them comes a stance later (1000), where the gain is back: they are dropped, not
  // judged there (a review's probe dropped the gain on tick 1001 with them).
  const int dropped = gain_judged_after_a_gap();
  std::printf("a guard's sums before 0.36 s without the total force: gain dropped at tick %d\n", dropped);
  EXPECT_EQ(dropped, -1);
}

// One tick k of a walk of 1 s strides, before its faults: the left foot stands for 700 ticks and
// swings (3 cm up) for 300, its pads' loads in stance given by `left_loads(s)` (s the stance's
// phase in [0, 1); 0 in the swing); the right foot's pads carry 150 N (+ right_sway_N
// sin(2 pi k / 370), with alternate signs pad by pad); every reading +-0.5 N alternately. Sets the
// heights and readings; returns the pads' true sum.
template <class LeftLoads>
double walk_loads(Feet& feet, int k, const LeftLoads& left_loads, bool heights_lost_mid_stance = false,
                  double right_sway_N = 0.0) {
  const int phase = k % 1000;
  const bool swinging = phase >= 700;
  // Both feet's poses lost (heights unknown, NaN) for 20 ticks in the middle of each stance.
  const bool lost = heights_lost_mid_stance && phase >= 300 && phase < 320;
  if (heights_lost_mid_stance) std::fill(feet.height.begin(), feet.height.end(), lost ? std::nan("") : 0.0);
  if (!lost) feet.left_foot_at(swinging ? 0.03 : 0.0);
  const std::array<double, 4> left = left_loads(phase / 700.0);
  const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
  double truth = 0.0;
  for (std::size_t j = 0; j < kChannels; ++j) {
    const double right_sway = (j % 2 == 0 ? 1.0 : -1.0) * right_sway_N * std::sin(2.0 * std::numbers::pi * k / 370.0);
    feet.measured[j] = (j < 4 ? (swinging ? 0.0 : left[j]) : 150.0 + right_sway) + wiggle;
    truth += feet.measured[j];
  }
  return truth;
}

// That walk's tick with l_foot/p4 reading k_true times its load from tick gain_from.
template <class LeftLoads>
void walk_tick(Feet& feet, int k, const LeftLoads& left_loads, int gain_from, double k_true,
               bool heights_lost_mid_stance = false, double right_sway_N = 0.0) {
  const double truth = walk_loads(feet, k, left_loads, heights_lost_mid_stance, right_sway_N);
  if (k >= gain_from) feet.measured[3] *= k_true;
  feet.step(truth);
}

// The left pads rolling from heel to toe and swaying from side to side by sway_N, each with a load
// of its own shape (s the stance's phase), at least 0 (a pad only pushes):
//   rear  (p3, p4): 300 (1 - s) + 50 +- sway_N sin(2 pi s),  front (p1, p2): 300 s + 50 +- sway_N sin(2 pi s),
// + on the left side (p1, p3), - on the right (p2, p4).
std::array<double, 4> swaying_sole(double s, double sway_N) {
  const double sway = sway_N * std::sin(2.0 * std::numbers::pi * s);
  return {std::max(0.0, 300.0 * s + 50.0 + sway), std::max(0.0, 300.0 * s + 50.0 - sway),
          std::max(0.0, 300.0 * (1.0 - s) + 50.0 + sway), std::max(0.0, 300.0 * (1.0 - s) + 50.0 - sway)};
}

// The walks' usual sole: a sway of +-60 N (every load at least 50 N).
std::array<double, 4> rolling_sole(double s) { return swaying_sole(s, 60.0); }

// That walk on the rolling sole (or `left_loads`). Returns the first tick l_foot/p4 is flagged (-1:
// never, by tick `ticks`), and its type and gain (reading / recovered value) on tick `check` (in a
// stance).
struct Flagged {
  int first = -1;
  FaultType type = FaultType::none;
  double k = 0.0;
};
using LeftSole = std::array<double, 4> (*)(double);
template <class LeftLoads = LeftSole>
Flagged walking_gain(int gain_from, double k_true, int check, bool heights_lost_mid_stance = false,
                     double right_sway_N = 0.0, const LeftLoads& left_loads = rolling_sole, int ticks = 12000) {
  Feet feet(suralp(), 1e-3);
  Flagged out;
  for (int k = 0; k < ticks; ++k) {
    walk_tick(feet, k, left_loads, gain_from, k_true, heights_lost_mid_stance, right_sway_N);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 3) {
        EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
    if (out.first < 0 && feet.type(3) != FaultType::none) out.first = k;
    if (k == check) {
      out.type = feet.type(3);
      out.k = feet.measured[3] / feet.outs[ContactForceFdi::kRecovered][3];
    }
  }
  return out;
}

TEST(ContactForceFdi, AGainThatBeginsInTheAirIsFittedOnTheTicksSinceTheResidualLeftItsBound) {
  // From tick 4800 (a swing; the foot lands at 5000) l_foot/p4 reads half its load. It lands
  // reading so (no jump), and the sum residual follows -x4 through every stance from then on. The
  // gain window (2 s) holds the stances before, in which p4 carried its load with the residual at
  // 0: with them, no pad's fit explains the residual, and p4 was flagged at tick 11907 (with the
  // window since the residual left its bound taken out). That window opens within the stance of
  // 5000-5700 and holds the fault alone. Here the right foot's pads read a still 150 N: any of
  // them might be stuck with the residual its load, so p4 is a gain once its point has closed that
  // stance (tick 5700) and stayed in the air clear_s (50 ticks), where a gain reads 0 and an
  // additive fault's residual stays.
  const Flagged in_air = walking_gain(4800, 0.5, 6300);
  std::printf("a x0.5 gain from tick 4800, in the air: flagged at tick %d; at tick 6300 %s, k %.3f\n", in_air.first,
              std::string(to_string(in_air.type)).c_str(), in_air.k);
  EXPECT_GE(in_air.first, 5700 + 50);
  EXPECT_LE(in_air.first, 5700 + 50 + 10);  // judged every 10 ticks
  EXPECT_EQ(in_air.type, FaultType::gain);
  EXPECT_NEAR(in_air.k, 0.5, 0.01);
  // The same walk with both feet's heights unknown (NaN) for 20 ticks in the middle of every
  // stance: those ticks are in no stance and close none, so the within-stance fit holds the same
  // stances. Taken as air, they split every stance in two and counted as air after it.
  const Flagged heights_lost = walking_gain(4800, 0.5, 6300, true);
  std::printf("the same with heights lost mid-stance: flagged at tick %d; at tick 6300 %s, k %.3f\n",
              heights_lost.first, std::string(to_string(heights_lost.type)).c_str(), heights_lost.k);
  EXPECT_EQ(heights_lost.first, in_air.first);
  EXPECT_EQ(heights_lost.type, FaultType::gain);
  EXPECT_NEAR(heights_lost.k, 0.5, 0.01);
  // With the right pads' loads moving (+-40 N) no reading on the ground stayed still, and p4's fit
  // (through 0 at zero load: it began in the air) stands out of every other channel's once its
  // stance has closed: a gain before its pad has been in the air clear_s. (Until 2026-12-06 only
  // after that: tick 5760.) Its twin p3 carries the same heel shape within the stance.
  const Flagged moving_right = walking_gain(4800, 0.5, 6300, false, 40.0);
  std::printf("the same with the right pads' loads moving: flagged at tick %d; at tick 6300 %s, k %.3f\n",
              moving_right.first, std::string(to_string(moving_right.type)).c_str(), moving_right.k);
  EXPECT_GE(moving_right.first, 5700);
  EXPECT_LT(moving_right.first, 5700 + 50);
  EXPECT_EQ(moving_right.type, FaultType::gain);
  EXPECT_NEAR(moving_right.k, 0.5, 0.01);
  // Begun in stance, it is found by its jump, as before.
  const Flagged in_stance = walking_gain(5300, 1.8, 7300);
  std::printf("a x1.8 gain from tick 5300, in stance: flagged at tick %d; at tick 7300 %s, k %.3f\n",
              in_stance.first, std::string(to_string(in_stance.type)).c_str(), in_stance.k);
  EXPECT_LE(in_stance.first, 5300 + 10);
  EXPECT_EQ(in_stance.type, FaultType::gain);
  EXPECT_NEAR(in_stance.k, 1.8, 0.02);
}

TEST(ContactForceFdi, AGainBegunInTheAirOfAnySizeIsNamedAndBlamesNoNeighbour) {
  // walking_gain's walk, the right pads' loads moving (+-40 N), l_foot/p4 reading k times its
  // load from tick 4800 (a swing; it lands at 5000). Every size is named a gain and no other
  // channel is flagged (walking_gain asserts that on every tick). Its k is held within the
  // refits' dead bands: the reading's own fit against its leave-one-out force leaves a held k
  // alone within gain_threshold / 2 of its ratio to the fitted one, so up to 1 / (1 - 0.1) - 1
  // of the truth (the gain window's band, on beta, is about the k's error itself: 0.1).
  // How soon is printed, not asserted: the window since the residual left its bound opens only
  // where the 1 Hz residual passes sum_threshold_N (80 N here: |k - 1| of a heel load of up to
  // 350 N over its stance), which x0.5 does at its first landing, named 0.9 s after the onset
  // (7.1 s with that window switched off: probed 2026-12-06); x0.6-0.8 and x1.3-1.4 are left to
  // the 2 s gain window, named 1.9-5.9 s after it (the known limit, docs/results.md "A gain begun
  // in the air, of any size").
  for (const double k_true : {0.5, 0.6, 0.7, 0.8, 1.3, 1.4}) {
    const Flagged f = walking_gain(4800, k_true, 13300, false, 40.0, rolling_sole, 14000);
    std::printf("x%.2f from tick 4800, in the air: flagged at tick %d (%.2f s after); at tick 13300 %s, k %.3f\n",
                k_true, f.first, (f.first - 4800) * 1e-3, std::string(to_string(f.type)).c_str(), f.k);
    EXPECT_GE(f.first, 5000) << "x" << k_true;  // not before its pad carries load
    EXPECT_LT(f.first, 11000) << "x" << k_true;  // the slowest, x0.6, on tick 10706
    EXPECT_EQ(f.type, FaultType::gain) << "x" << k_true;
    EXPECT_LE(std::abs(f.k / k_true - 1.0), 1.0 / (1.0 - 0.5 * suralp().gain_threshold) - 1.0) << "x" << k_true;
  }
}

TEST(ContactForceFdi, AStrongGainBegunInTheAirIsNamedWithinItsLandingsStance) {
  // A sole that sways from side to side (+-200 N, each pad's load at least 0: a pad only pushes)
  // loads p4 unlike its twin p3 within the stance, and the right pads' loads move (+-40 N). A
  // x1.6 gain begun in the air (tick 4800) is then named within the stance it lands in
  // (5000-5700): the 2 s gain window's fit on p4 explains the residual and stands out of every
  // other channel's before the stance ends (with the window since the residual left its bound
  // switched off, on the same tick: a probe of 2026-12-06). (On a sole swaying +-100 N, a x2
  // gain was named on tick 5654, but its healthy twin p3 was held frozen for a while from tick
  // 5184: still at its load's turning point while the residual moved; docs/results.md.)
  const auto swaying = [](double s) { return swaying_sole(s, 200.0); };
  const Flagged f = walking_gain(4800, 1.6, 6300, false, 40.0, swaying);
  std::printf("x1.6 from tick 4800 on a swaying sole: flagged at tick %d; at tick 6300 %s, k %.3f\n", f.first,
              std::string(to_string(f.type)).c_str(), f.k);
  EXPECT_GE(f.first, 5000);  // not before its pad carries load
  EXPECT_LT(f.first, 5700);  // within the landing's stance
  EXPECT_EQ(f.type, FaultType::gain);
  EXPECT_NEAR(f.k, 1.6, 0.02);
}

// walking_gain's walk with the right pads' loads moving (+-40 N), judged alone: l_foot/p4 reads
// k_true times its load from tick 4800 (in the air) and the total force reads its landing's
// error too, error_N (1 - s) over the stance that follows (5000-5700, s its phase), beyond the
// residual's bound (80 N) at first; or l_foot/`drifting` drifts by rate_N_s from tick
// drift_from. Returns the first channel flagged and when, and how long others were flagged.
struct FirstFlag {
  std::size_t channel = kChannels;
  int tick = -1;
  FaultType type = FaultType::none;
  int other_ticks = 0;  // ticks x channels flagged other than the faulty one
};
FirstFlag walking_with(double k_true, double error_N, std::size_t drifting = kChannels, double rate_N_s = 0.0,
                       int drift_from = 0) {
  Feet feet(suralp(), 1e-3);
  FirstFlag out;
  const std::size_t faulty = drifting < kChannels ? drifting : 3;
  for (int k = 0; k < 12000; ++k) {
    const double truth = walk_loads(feet, k, rolling_sole, false, 40.0);
    if (drifting < kChannels) {
      if (k >= drift_from) feet.measured[drifting] += rate_N_s * (k - drift_from) * 1e-3;
    } else if (k >= 4800) {
      feet.measured[3] *= k_true;
    }
    const double error = k >= 5000 && k < 5700 ? error_N * (1.0 - (k - 5000) / 700.0) : 0.0;
    feet.step(truth + error);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (feet.type(j) == FaultType::none) continue;
      if (out.tick < 0) {
        out = FirstFlag{.channel = j, .tick = k, .type = feet.type(j)};
      }
      if (j != faulty) ++out.other_ticks;
    }
  }
  return out;
}

TEST(ContactForceFdi, ATotalForceErrorShapedLikeTheLandingsLoadBlamesNoNeighbourOfAGainBegunInTheAir) {
  // An error of the total force that fades over the stance fits the heel pads' shape. A fit that
  // needs an intercept (no gain begun in the air) is no candidate, but it explains the residual as
  // well: it rivals the best gain fit. Counted as no rival (a version of 2026-12-06), l_foot/p3
  // was named a gain on tick 5310 and held to the end, and p4 never named.
  const FirstFlag f = walking_with(0.5, 150.0);
  std::printf("x0.5 from the air, the total force 150 N off at the landing: channel %zu flagged %s at tick %d; "
              "others flagged %d ticks\n",
              f.channel, std::string(to_string(f.type)).c_str(), f.tick, f.other_ticks);
  // p4 itself is flagged first, on tick 5573, as the version before these rules flags it (typed
  // frozen on that tick by both; the test asks who is blamed).
  EXPECT_EQ(f.channel, 3u);
  EXPECT_EQ(f.tick, 5573);
  EXPECT_EQ(f.other_ticks, 0);
}

TEST(ContactForceFdi, ADriftInStanceIsNoGainBegunInTheAir) {
  // l_foot/p1 drifts by -300 N/s from tick 5200, in stance: the residual is a ramp in time, which
  // the heel pads' falling loads fit over a short window with an intercept of hundreds of newtons.
  // A gain begun in the air has none: without that rule, l_foot/p4 was named a gain on tick 5715.
  const FirstFlag f = walking_with(1.0, 0.0, 0, -300.0, 5200);
  std::printf("l_foot/p1 drifting -300 N/s from tick 5200: channel %zu flagged %s at tick %d; others flagged %d "
              "ticks\n",
              f.channel, std::string(to_string(f.type)).c_str(), f.tick, f.other_ticks);
  EXPECT_EQ(f.channel, 0u);
  EXPECT_NE(f.type, FaultType::gain);
  EXPECT_EQ(f.other_ticks, 0);
}

// The walk of walking_gain, judged on a 6 N sum bound: l_foot/p4 carries 30 (1 - s) + 10 N in
// stance and reads `k_true` times it from tick gain_from (4800: a swing), under gain_min_load_N (30 N) RMS;
// l_foot/p2 carries 20 + 1.2 (30 (1 - s) + 10) N, p4's shape on a load, and p3
// 150 + 100 sin(2 pi s). Returns the ticks x channels flagged other than p4 over 12 s.
int light_gain_beside_a_loaded_neighbour_blames(double k_true, double sum_threshold_N = 6.0, int gain_from = 4800) {
  ContactForceFdi::Params p = suralp();
  p.sum_threshold_N = sum_threshold_N;
  Feet feet(p, 1e-3);
  int others = 0;
  const auto light_heel = [](double s) {
    const double heel = 30.0 * (1.0 - s) + 10.0;
    return std::array<double, 4>{300.0 * s + 50.0, 20.0 + 1.2 * heel,
                                 150.0 + 100.0 * std::sin(2.0 * std::numbers::pi * s), heel};
  };
  for (int k = 0; k < 12000; ++k) {
    walk_tick(feet, k, light_heel, gain_from, k_true);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 3 && feet.type(j) != FaultType::none) {
        if (others == 0) std::printf("  channel %zu flagged %s at tick %d\n", j, std::string(to_string(feet.type(j))).c_str(), k);
        ++others;
      }
    }
  }
  return others;
}

TEST(ContactForceFdi, ALightlyLoadedGainLeavesItsLoadedNeighbourUnblamed) {
  // The residual, -0.65 of p4's load, leaves its bound in the stance after the onset. In the
  // window since then p2's fit explains 92.5 % of it, but p4's, too little loaded to be blamed,
  // explains all of it: nobody is isolated. Without p4 competing, p2 was a gain from tick 5940
  // to the end (6060 ticks; run once with it left out).
  const int others = light_gain_beside_a_loaded_neighbour_blames(0.35);
  std::printf("a x0.35 gain on a lightly loaded pad: other channels flagged on %d ticks\n", others);
  EXPECT_EQ(others, 0);
  // From tick 0 on an 80 N bound: the residual never leaves it, and the 2 s gain window alone
  // judges, alike (without p4 competing there, p2 was a gain from tick 2302 to the end; run once).
  const int others_2s = light_gain_beside_a_loaded_neighbour_blames(0.35, 80.0, 0);
  std::printf("... judged by the 2 s window alone: other channels flagged on %d ticks\n", others_2s);
  EXPECT_EQ(others_2s, 0);
}

// As doubling_gain_cleared_at, for two pads of the left foot at once: from tick 100 to the lift
// at 300, l_foot/p1 reads +100 N and l_foot/p2 -30 N off their 100 N (taken in the air for gains
// of 2 and 0.7). They land at tick 500 on 300 N each and read it (healthy) or 2 and 0.7 times it.
// Returns the first tick from 500 on where neither is a gain fault (-1: none).
int two_gains_cleared_at(bool healthy) {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 4000; ++k) {
    const bool lifted = k >= 300 && k < 500;
    feet.left_foot_at(lifted ? 0.1 : 0.0);
    const double load = lifted ? 0.0 : k < 300 ? 100.0 : 300.0;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = j < 4 ? load + (k % 2) : moving(j, k, 0.0);
    double truth = 0.0;
    for (double x : feet.measured) truth += x;
    if (k >= 100 && k < 300) {
      feet.measured[0] += 100.0;
      feet.measured[1] -= 30.0;
    }
    if (k >= 500 && !healthy) {
      feet.measured[0] *= 2.0;
      feet.measured[1] *= 0.7;
    }
    feet.step(truth);
    if (k == 499) {
      EXPECT_EQ(feet.type(0), FaultType::gain) << "l_foot/p1: the jump, read 0 in the air, is a gain";
      EXPECT_EQ(feet.type(1), FaultType::gain) << "l_foot/p2: the jump, read 0 in the air, is a gain";
    }
    if (k >= 500 && feet.type(0) != FaultType::gain && feet.type(1) != FaultType::gain) return k;
  }
  return -1;
}

TEST(ContactForceFdi, TwoGainsThatEndedTogetherAreDroppedTogether) {
  // Healthy on 300 N, the corrections x / k take +150 N and -128.6 N off the readings, and leave
  // the residual at -21.4 N. Each gain judged alone leaves the other's correction in it (128.6 N
  // and 150 N: worse than -21.4 N), and the one-correction stance comparison does not judge two,
  // so neither was ever dropped. Taken as they are together, the readings leave the residual at
  // 0.5 N: both are dropped once the joint sums hold the gain window (2 s of usable ticks: from
  // when both were typed gains in the air, the touchdown guard left out), within 2 s of the
  // guard's end.
  const int cleared = two_gains_cleared_at(true);
  std::printf("two gains healthy after landing at tick 500: dropped at tick %d\n", cleared);
  EXPECT_GT(cleared, 500);
  EXPECT_LT(cleared, 500 + 150 + 2000);
  // Still faulty: their corrections are what lower the residual, and they stay.
  EXPECT_EQ(two_gains_cleared_at(false), -1);
}

// Tick k of a walk whose left foot swings (3 cm up) or stands: the left pads read 0 N in the air
// and 100 N down, the right ones 200 N while the left swings and 100 N otherwise (800 N in all),
// each +-0.5 N alternating tick by tick.
void left_swing_loads(Feet& feet, int k, bool swinging) {
  feet.left_foot_at(swinging ? 0.03 : 0.0);
  const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
  for (std::size_t j = 0; j < kChannels; ++j) {
    feet.measured[j] = (j < 4 ? (swinging ? 0.0 : 100.0) : (swinging ? 200.0 : 100.0)) + wiggle;
  }
}

// The left foot swings over ticks [100, land); l_foot/p1 reads an offset of `before` N from tick
// 150, raised in the air, which becomes `after` N at tick 400, still in the air. Returns the tick
// the channel is re-admitted (-1: never) and its fault estimate 50 ticks after the landing.
int offset_changed_in_flight(double before, double after, int land, double& estimate_after_landing) {
  Feet feet(suralp(), 1e-3);
  int cleared = -1;
  for (int k = 0; k < land + 100; ++k) {
    const bool swinging = k >= 100 && k < land;
    left_swing_loads(feet, k, swinging);
    if (k >= 150) feet.measured[0] += k < 400 ? before : after;
    feet.step(800.0);
    if (k >= 200 && k < 400) {
      EXPECT_EQ(feet.type(0), FaultType::offset) << "tick " << k;
    }
    if (k >= 400 && cleared < 0 && feet.type(0) == FaultType::none) cleared = k;
    if (cleared >= 0 && feet.type(0) != FaultType::none) {
      ADD_FAILURE() << "raised again at tick " << k << ", re-admitted at " << cleared;
      return -1;
    }
    if (k == land + 50) estimate_after_landing = feet.outs[ContactForceFdi::kFaultEstimate][0];
  }
  return cleared;
}

TEST(ContactForceFdi, AnOffsetThatEndsInTheAirIsReadmittedOnTheFirstBlockOfTheAirThatReadsZero) {
  // 15 N (beyond airborne_threshold_N, 8 N; its end under jump_threshold_N, 20 N, so no step
  // restarts the swing's mean, and no jump confirms the end). The air's readings count from tick
  // 119 (airborne_settle_s after the lift-off at tick 100) in blocks of 20 (kAirborneMeanWindow_s):
  // the block of ticks 399-418 holds one 15 N reading, mean 0.75 N < airborne_clear_N (4 N):
  // re-admitted at tick 418. Before, the swing's mean (15 N over 250 readings, 0 over 60) stayed
  // beyond 4 N to the landing, and the channel stayed flagged into the stance.
  double estimate = 0.0;
  const int cleared = offset_changed_in_flight(15.0, 0.0, 460, estimate);
  std::printf("15 N offset ended in the air at tick 400: re-admitted at tick %d\n", cleared);
  EXPECT_EQ(cleared, 418);
  EXPECT_NEAR(estimate, 0.0, 1e-9);
  // A 60 N offset's end is a confirmed jump back to within the noise of 0: re-admitted on its
  // jump window (jump_window_s, 10 ms) as before.
  EXPECT_EQ(offset_changed_in_flight(60.0, 0.0, 460, estimate), 409);
}

TEST(ContactForceFdi, AnOffsetThatChangesSizeInTheAirIsFittedOnTheReadingsAfterTheStep) {
  // 60 N -> 30 N at tick 400: a step within steps_back's band (|-30 + 60| = 30 N < 0.4 x 60 N +
  // jump_confirm_N = 49 N), which the jump test took for the fault's end (re-admitted at tick 409,
  // raised again by the air test at 438). In the air the readings after the step decide: they read
  // 30 N, so it stays an offset, fitted on them alone (not on one line through both levels).
  double estimate = 0.0;
  const int cleared = offset_changed_in_flight(60.0, 30.0, 500, estimate);
  EXPECT_EQ(cleared, -1);
  EXPECT_NEAR(estimate, 30.0, 0.5);
}

// The left foot swings over ticks [100, 350), 0.25 s (a quadruped's swing, shorter than the
// 0.3 s the air's line once needed), its pads reading 0 N +- 0.5 N; l_foot/p1 reads a fault of
// 10 N + slope (t - 0.15 s) from tick 150 (no step for the jump test: under 20 N). Returns the
// type it shows on the tick before the landing; `drift_from` the first tick it shows drift (-1:
// none), `estimate_after_landing` its fault estimate 50 ticks after the landing.
FaultType fault_in_a_short_swing(double slope_N_s, int& drift_from, double& estimate_after_landing) {
  Feet feet(suralp(), 1e-3);
  FaultType before_landing = FaultType::none;
  drift_from = -1;
  for (int k = 0; k < 400; ++k) {
    const bool swinging = k >= 100 && k < 350;
    left_swing_loads(feet, k, swinging);
    if (k >= 150) feet.measured[0] += 10.0 + slope_N_s * (k - 150) * 1e-3;
    feet.step(800.0);
    if (drift_from < 0 && feet.type(0) == FaultType::drift) drift_from = k;
    if (k == 349) before_landing = feet.type(0);
    if (k == 399) estimate_after_landing = feet.outs[ContactForceFdi::kFaultEstimate][0];
  }
  return before_landing;
}

TEST(ContactForceFdi, ADriftIsToldFromAnOffsetInAShortSwingWhereItsSlopeStandsOutOfTheNoise) {
  // The air test raises the fault once the swing's mean passes airborne_threshold_N (8 N), on
  // tick 222 at 40 N/s, and fits a line to the readings from there. A drift is a slope beyond
  // z = 5.71 of its standard errors (the two-sided normal quantile of alpha = T /
  // false_alarm_interval_s = 1e-3 / 86400, as the decision is taken again every tick), the
  // standard error sigma_x / sqrt(sum (t - mean t)^2), sigma_x = 2 N. After n readings,
  // sqrt(sum (t - mean t)^2) = T sqrt(n (n^2 - 1) / 12): at n = 100 (tick 321), 40 N/s x 0.2887 s
  // = 11.55 N > 5.71 x 2 N = 11.42 N (n = 99: 11.37 N). Before, a drift needed 0.3 s of air
  // readings, and this one stayed an offset.
  int drift_from = 0;
  double estimate = 0.0;
  EXPECT_EQ(fault_in_a_short_swing(40.0, drift_from, estimate), FaultType::drift);
  EXPECT_EQ(drift_from, 321);
  // Extrapolated through the landing: 10 + 40 x 0.249 N, 50 ticks after it.
  EXPECT_NEAR(estimate, 10.0 + 40.0 * 0.249, 1.0);
  // 2 N/s: raised on tick 267, 83 readings to the landing, 0.44 N: no slope to tell, an offset.
  EXPECT_EQ(fault_in_a_short_swing(2.0, drift_from, estimate), FaultType::offset);
  EXPECT_EQ(drift_from, -1);
  EXPECT_EQ(fault_in_a_short_swing(0.0, drift_from, estimate), FaultType::offset);
  EXPECT_EQ(drift_from, -1);
  EXPECT_NEAR(estimate, 10.0, 0.5);
}

TEST(ContactForceFdi, ADriftStaysADriftAtTheStartOfItsNextSwing) {
  // As fault_in_a_short_swing at 40 N/s, with a second swing over ticks [600, 850): the line
  // spans both swings, and the type stays drift through the stance and the second swing's first
  // readings (its swing mean settles only after three of the air test's windows). Before, those
  // readings typed it an offset at the fits' mean level until they had settled.
  Feet feet(suralp(), 1e-3);
  int drift_from = -1;
  for (int k = 0; k < 900; ++k) {
    const bool swinging = (k >= 100 && k < 350) || (k >= 600 && k < 850);
    left_swing_loads(feet, k, swinging);
    if (k >= 150) feet.measured[0] += 10.0 + 40.0 * (k - 150) * 1e-3;
    feet.step(800.0);
    if (drift_from < 0 && feet.type(0) == FaultType::drift) drift_from = k;
    if (drift_from >= 0) {
      ASSERT_EQ(feet.type(0), FaultType::drift) << "tick " << k << ", a drift since tick " << drift_from;
    }
  }
  EXPECT_EQ(drift_from, 321);
  // Its estimate at the end: 10 + 40 x 0.749 N (the line through both swings).
  EXPECT_NEAR(feet.outs[ContactForceFdi::kFaultEstimate][0], 10.0 + 40.0 * 0.749, 1.0);
}

// The left foot swings five times, over ticks [100 + 600 i, 350 + 600 i), i = 0..4, its pads
// reading 0 N +- 0.5 N in the air; l_foot/p1 reads `fault(k)` [N] on top of its load. Returns
// the first tick it is flagged (-1: never), the type it shows on that tick and on the tick before
// the fourth landing (2149), and its fault estimate there.
struct SwingsFault {
  int raised = -1;
  FaultType type_when_raised = FaultType::none;
  FaultType type_before_landing = FaultType::none;
  double estimate_before_landing_N = 0.0;
  // After tick k: l_foot/p1's first flag, and its type and estimate on the tick before the landing.
  void observe(const Feet& feet, int k, int before_landing) {
    if (raised < 0 && feet.type(0) != FaultType::none) {
      raised = k;
      type_when_raised = feet.type(0);
    }
    if (k == before_landing) {
      type_before_landing = feet.type(0);
      estimate_before_landing_N = feet.outs[ContactForceFdi::kFaultEstimate][0];
    }
  }
};
template <class Fault>
SwingsFault fault_over_swings(const Fault& fault) {
  Feet feet(suralp(), 1e-3);
  SwingsFault seen;
  for (int k = 0; k < 2200; ++k) {
    left_swing_loads(feet, k, k >= 100 && (k - 100) % 600 < 250);
    feet.measured[0] += fault(k);
    feet.step(800.0);
    seen.observe(feet, k, 2149);
  }
  return seen;
}

TEST(ContactForceFdi, ADriftFoundInTheAirAfterSwingsItGrewThroughIsADriftWhenRaised) {
  // 5 N/s from tick 400: the second and third swings read about 2.2 and 5.2 N in the air, under
  // airborne_threshold_N (8 N), and the fourth passes it as its mean grows. Its swing alone is too
  // short to show the slope (0.16 s of 5 N/s: 0.8 N, under the 5.71 standard errors of 2 N); the
  // levels of the swings before, with it, lie on one ramp that the step (an offset after the third
  // swing) misses by far (onset_shape.hpp). Before: an offset of the fourth swing's level.
  const SwingsFault drift = fault_over_swings([](int k) { return k >= 400 ? 5e-3 * (k - 400) : 0.0; });
  std::printf("5 N/s drift from tick 400: raised on tick %d as %s\n", drift.raised,
              std::string(to_string(drift.type_when_raised)).c_str());
  EXPECT_GT(drift.raised, 1900);
  EXPECT_EQ(drift.type_when_raised, FaultType::drift);
  EXPECT_EQ(drift.type_before_landing, FaultType::drift);
  EXPECT_NEAR(drift.estimate_before_landing_N, 5e-3 * (2149 - 400), 0.5);
  // 9 N from tick 1700, in the stance after the third swing: the swings before read 0, a step.
  const SwingsFault offset = fault_over_swings([](int k) { return k >= 1700 ? 9.0 : 0.0; });
  EXPECT_GT(offset.raised, 1900);
  EXPECT_EQ(offset.type_when_raised, FaultType::offset);
  EXPECT_EQ(offset.type_before_landing, FaultType::offset);
  EXPECT_NEAR(offset.estimate_before_landing_N, 9.0, 0.5);
  // 4 N from tick 400 and 10 N from tick 1700: the levels 0, 4, 4, 10 fit neither a ramp nor one
  // step within their noise; the fault is typed by what the air shows now, an offset.
  const SwingsFault two_steps = fault_over_swings([](int k) { return k >= 1700 ? 10.0 : k >= 400 ? 4.0 : 0.0; });
  EXPECT_GT(two_steps.raised, 1900);
  EXPECT_EQ(two_steps.type_when_raised, FaultType::offset);
  EXPECT_EQ(two_steps.type_before_landing, FaultType::offset);
  // 12 N from tick 1480, late in the third swing (its window: ticks 1319-1549), a step under
  // jump_threshold_N (20 N) that restarts nothing: that window's mean, 3.6 N, lies between 0 and
  // 12 N as a ramp's would, but its two levels (its line's, -0.8 N and 8.0 N, 0.13 s apart)
  // show the steep step it is, which no ramp through the fourth swing's 12 N fits: an offset.
  const SwingsFault late_step = fault_over_swings([](int k) { return k >= 1480 ? 12.0 : 0.0; });
  EXPECT_GT(late_step.raised, 1900);
  EXPECT_EQ(late_step.type_when_raised, FaultType::offset);
  EXPECT_EQ(late_step.type_before_landing, FaultType::offset);
  EXPECT_NEAR(late_step.estimate_before_landing_N, 12.0, 0.5);
  // 12 N from tick 1940, early in the fourth swing, the one that raises it: that window's own two
  // levels (one between, one full) fit a ramp that began within it exactly; the swings before
  // read 0, so nothing grew through them: an offset.
  const SwingsFault early_step = fault_over_swings([](int k) { return k >= 1940 ? 12.0 : 0.0; });
  EXPECT_GT(early_step.raised, 1900);
  EXPECT_EQ(early_step.type_when_raised, FaultType::offset);
  EXPECT_EQ(early_step.type_before_landing, FaultType::offset);
  EXPECT_NEAR(early_step.estimate_before_landing_N, 12.0, 0.5);
}

// The left foot stands for 2.5 s, swings over ticks [2500, 2750) and lands; its pads' loads
// sway between the feet by +-40 N over 0.7 s (a constant load would make any fault's reading
// line up with the residual, a gain to the regression). l_foot/p1 reads fault(k) on top of its
// load; the total force is the pads' true sum plus N(0, 2 N), std::mt19937(seed), plus
// total_error(k). ramp_history_s 1.6 unless given: the sum residual's history is 16 blocks of 0.1 s.
template <class Fault, class TotalError>
SwingsFault fault_through_a_long_stance(const Fault& fault, const TotalError& total_error, unsigned seed,
                                        double ramp_history_s = 1.6, double noise_std_N = 2.0) {
  ContactForceFdi::Params p = suralp();
  p.ramp_history_s = ramp_history_s;
  p.noise_std_N = noise_std_N;
  Feet feet(p, 1e-3);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 2.0);
  SwingsFault seen;
  for (int k = 0; k < 2800; ++k) {
    const bool swinging = k >= 2500 && k < 2750;
    left_swing_loads(feet, k, swinging);
    const double sway = 40.0 * std::sin(2.0 * std::numbers::pi * k / 700.0);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (!(swinging && j < 4)) feet.measured[j] += j < 4 ? sway : -sway;
    }
    feet.measured[0] += fault(k);
    double sum = 0.0;
    for (double x : feet.measured) sum += x;
    feet.step(sum - fault(k) + noise(rng) + total_error(k));
    seen.observe(feet, k, 2740);
  }
  return seen;
}

TEST(ContactForceFdi, ADriftThatGrewWhileItsPadWasLoadedIsADriftWhenTheAirFindsIt) {
  // A pad that swings once in seconds (a quadruped's foot) shows a slow drift in one swing only:
  // no swing before it tells a ramp from a step. But while the pad was loaded the sum residual
  // carried the drift: its 0.1 s block means (0.2 N of noise each, measured on their second
  // differences) rose along a ramp from tick 1500 that reaches, at the swing, the level the air
  // reads (10 N), so the fault is a drift when raised (before: an offset until the next swing).
  const unsigned seed = 11;
  std::printf("total force error N(0, 2 N), std::mt19937(%u)\n", seed);
  const auto none = [](int) { return 0.0; };
  const SwingsFault drift =
      fault_through_a_long_stance([](int k) { return k >= 1500 ? 10e-3 * (k - 1500) : 0.0; }, none, seed);
  std::printf("10 N/s drift from tick 1500: raised on tick %d as %s\n", drift.raised,
              std::string(to_string(drift.type_when_raised)).c_str());
  EXPECT_GT(drift.raised, 2500);
  EXPECT_EQ(drift.type_when_raised, FaultType::drift);
  EXPECT_EQ(drift.type_before_landing, FaultType::drift);
  EXPECT_NEAR(drift.estimate_before_landing_N, 10e-3 * (2740 - 1500), 0.5);
  // 10 N from tick 2000, a step under jump_threshold_N in the stance: the blocks step, an offset.
  const SwingsFault offset = fault_through_a_long_stance([](int k) { return k >= 2000 ? 10.0 : 0.0; }, none, seed);
  EXPECT_GT(offset.raised, 2500);
  EXPECT_EQ(offset.type_when_raised, FaultType::offset);
  EXPECT_EQ(offset.type_before_landing, FaultType::offset);
  EXPECT_NEAR(offset.estimate_before_landing_N, 10.0, 0.5);
  // The total force drifting down by 10 N/s from tick 1500 makes the same ramp in the sum
  // residual; the pad reads 25 N too from the swing on: the ramp (10 N there) is not the level
  // the air reads, so it is not the pad's fault. An offset.
  const SwingsFault reference_drift = fault_through_a_long_stance(
      [](int k) { return k >= 2500 ? 25.0 : 0.0; }, [](int k) { return k >= 1500 ? -10e-3 * (k - 1500) : 0.0; },
      seed);
  EXPECT_GT(reference_drift.raised, 2500);
  EXPECT_EQ(reference_drift.type_when_raised, FaultType::offset);
  EXPECT_EQ(reference_drift.type_before_landing, FaultType::offset);
  // A step a little above the air's threshold on a quieter sensor (noise_std_N 0.5: the air
  // raises beyond 2 N): 4 N from tick 2312, in the middle of the 0.125 s block 2250-2374, whose
  // mean is half of it; the last block before the swing (2375-2499) reads all of it. The blocks
  // alone fit a ramp (onset 2.18 s, 15.9 N/s), whose level at the air's mean time the air's 4 N
  // does not contradict within z = 5.71 of the noise. Joined to the blocks as one more level, the
  // air's 4 N is off that ramp and on the step: an offset (a drift with the blocks alone; a
  // review's finding).
  const SwingsFault mid_block_step =
      fault_through_a_long_stance([](int k) { return k >= 2312 ? 4.0 : 0.0; }, none, seed, 2.0, 0.5);
  EXPECT_GT(mid_block_step.raised, 2500);
  EXPECT_EQ(mid_block_step.type_when_raised, FaultType::offset);
  EXPECT_EQ(mid_block_step.type_before_landing, FaultType::offset);
  // The same step a block earlier (tick 2187, in the block 2125-2249), so that two full blocks read
  // it before the swing: 0, 2, 4, 4 and the air's 4 N, a step inside the block. An offset. (Here the
  // ramp fails with or without the rule that it beat a step inside a block by z^2: its misfit is
  // beyond its chi-square bound already. Where the blocks scatter more, the bound is loose and that
  // rule decides: SURALP's stress walk 2, docs/results.md.)
  const SwingsFault earlier_mid_block_step =
      fault_through_a_long_stance([](int k) { return k >= 2187 ? 4.0 : 0.0; }, none, seed, 2.0, 0.5);
  EXPECT_GT(earlier_mid_block_step.raised, 2500);
  EXPECT_EQ(earlier_mid_block_step.type_when_raised, FaultType::offset);
  EXPECT_EQ(earlier_mid_block_step.type_before_landing, FaultType::offset);
}

// l_foot/p1's drift of fault_in_a_short_swing (40 N/s from tick 150, typed drift on tick 321),
// on a foot that lands on tick 350 and then stays down to tick 4000 (a robot that stops and
// stands). From tick 1000 the fault follows `after` (its size [N] at tick k >= 1000; 44 N, the
// drift's level, at tick 1000). The total force carries an error of N(0, total_noise_N),
// std::mt19937(seed), a bias of total_bias_N, and from tick 1000 total_step_N more; no other
// channel may be flagged. (jump_threshold_N and clear_s: the detector's, 0 for its default.)
struct LongStance {
  int cleared = -1;  // the first tick the channel shows no fault after it showed drift (-1: none)
  FaultType type_at_end = FaultType::none;
  double estimate_at_end_N = 0.0;  // its fault estimate on the last tick
  double recovered_rms_N = 0.0;    // its recovered load's error over the last 1000 ticks
};
template <class After>
LongStance drift_in_a_long_stance(const After& after, unsigned seed, double total_bias_N = 0.0,
                                  double jump_threshold_N = 0.0, double total_noise_N = 2.0,
                                  double clear_s = 0.0, double total_step_N = 0.0, int gap_from = -1,
                                  int gap_to = -1) {
  ContactForceFdi::Params params = suralp();
  params.jump_threshold_N = jump_threshold_N;
  if (clear_s > 0.0) params.clear_s = clear_s;
  Feet feet(params, 1e-3);
  std::mt19937 rng(seed);
  std::normal_distribution<double> total_error(0.0, total_noise_N);
  LongStance out;
  bool drift = false;
  double squared_error = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const bool swinging = k >= 100 && k < 350;
    left_swing_loads(feet, k, swinging);
    const double load = feet.measured[0];
    feet.measured[0] += k < 150 ? 0.0 : k < 1000 ? 10.0 + 40.0 * (k - 150) * 1e-3 : after(k);
    const double total = 800.0 + total_bias_N + (k >= 1000 ? total_step_N : 0.0) + total_error(rng);
    feet.step(total, !(k >= gap_from && k < gap_to));  // in the gap, the total force is unknown
    drift = drift || feet.type(0) == FaultType::drift;
    if (drift && out.cleared < 0 && feet.type(0) == FaultType::none) out.cleared = k;
    for (std::size_t j = 1; j < kChannels; ++j) EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
    const double error = feet.outs[ContactForceFdi::kRecovered][0] - load;
    if (k >= 3000) squared_error += error * error;
  }
  out.type_at_end = feet.type(0);
  out.estimate_at_end_N = feet.outs[ContactForceFdi::kFaultEstimate][0];
  out.recovered_rms_N = std::sqrt(squared_error / 1000.0);
  return out;
}

// The drift's level at tick 1000, where `after` takes over.
constexpr double kDriftLevelAt1000 = 10.0 + 40.0 * 0.85;

TEST(ContactForceFdi, ADriftThatEndsWhileItsPadStaysLoadedIsReadmittedOnceTheReadingStaysFlat) {
  // The drift's correction goes on through the stance; once the fault has faded (over ticks
  // 1000-1200, 0.22 N a tick: too gently for the jump test), the reading as it is leaves a
  // quarter of its power (from about tick 1127), but that alone does not re-admit a drift (its
  // slope may have grown wrong while it goes on): the reading must also stay flat, no slope and
  // no bend beyond z = 5.71 of their standard errors, over a window long enough that z se of the
  // slope is within a quarter of the drift's fitted slope per tick (with 2 N of error,
  // se = 2 N sqrt(12 / n^3): some 250 ticks at 40 N/s, more at the slope refitted through the
  // stance). The window that holds the fade's tail is closed as sloped; the next one is flat: the
  // channel is re-admitted within 1 s of the fade's end (tick 2026 with this seed). Before, a
  // drift was only dropped in the air: on a foot that stays down, never, its correction growing
  // without bound.
  const unsigned seed = 5;
  std::printf("total force error N(0, 2 N), std::mt19937(%u)\n", seed);
  const auto fades = [](int k) { return k < 1200 ? kDriftLevelAt1000 * (1200 - k) / 200.0 : 0.0; };
  const LongStance faded = drift_in_a_long_stance(fades, seed);
  std::printf("a drift faded out over ticks 1000-1200: re-admitted at tick %d\n", faded.cleared);
  EXPECT_GE(faded.cleared, 1200 + 250);
  EXPECT_LE(faded.cleared, 2200);
  EXPECT_EQ(faded.type_at_end, FaultType::none);
  // With the total force 40 N off either way (within sum_threshold_N, 80 N here), the faded
  // reading leads the load by -40 or +40 N as the sum residual sees it, flat, beyond
  // gain_min_load_N: but the window before it fell, so it is no plateau, and the comparison
  // re-admits it (later: the correction must overshoot that lead too).
  for (const double bias : {-40.0, 40.0}) {
    const LongStance biased = drift_in_a_long_stance(fades, seed, bias);
    std::printf("the same with the total force %+.0f N off: re-admitted at tick %d\n", bias, biased.cleared);
    EXPECT_GE(biased.cleared, 1200) << "total force " << bias << " N off";
    EXPECT_EQ(biased.type_at_end, FaultType::none) << "total force " << bias << " N off";
  }
  // Faded, then growing again at 15 N/s: the correction leaves more than the reading as it is,
  // but the reading falls and rises within the first window (a line through it is flat, its bend
  // is not) and slopes in every window after: not re-admitted by the stance comparison.
  const auto regrows = [&](int k) { return k < 1200 ? fades(k) : 15.0 * (k - 1200) * 1e-3; };
  const LongStance regrown = drift_in_a_long_stance(regrows, seed);
  std::printf("faded, then growing again at 15 N/s: re-admitted at tick %d\n", regrown.cleared);
  EXPECT_EQ(regrown.cleared, -1);
  EXPECT_EQ(regrown.type_at_end, FaultType::drift);
}

TEST(ContactForceFdi, ADriftsEndIsJudgedOnTheTimeItsTicksWereTakenAtNotOnTheirCount) {
  const unsigned seed = 5;
  std::printf("total force error N(0, 2 N), std::mt19937(%u)\n", seed);
  const auto fades = [](int k) { return k < 1200 ? kDriftLevelAt1000 * (1200 - k) / 200.0 : 0.0; };
  // The drift of ADriftThatEndsWhileItsPadStaysLoadedIsReadmittedOnceTheReadingStaysFlat fades
  // out over ticks 1000-1200; here the total force is unknown over ticks 1300-2300 (no tick of
  // that second is usable). The trend window's abscissa is the ticks' time: the flat readings
  // before the gap and after it lie 1000 ticks apart, which a drift going on at a quarter of its
  // rate would have moved them by, so the window is decided on fewer ticks after the gap than it
  // needed without one. Counted by usable ticks, the two sides were glued into one line and the
  // channel was re-admitted at tick 3012 (run once): about the 2026 of the walk without a gap
  // plus the gap's 1000 ticks.
  const LongStance no_gap = drift_in_a_long_stance(fades, seed);
  const LongStance gap = drift_in_a_long_stance(fades, seed, 0.0, 0.0, 2.0, 0.0, 0.0, 1300, 2300);
  std::printf("a drift faded out over ticks 1000-1200: re-admitted at tick %d; with the total force unknown "
              "over ticks 1300-2300: at tick %d\n", no_gap.cleared, gap.cleared);
  EXPECT_EQ(no_gap.cleared, 2026);
  EXPECT_GE(gap.cleared, 2300);
  EXPECT_LE(gap.cleared, no_gap.cleared + 1000 - 200);
  EXPECT_EQ(gap.type_at_end, FaultType::none);
}

TEST(ContactForceFdi, ADriftThatEndsByAStepUnderTheJumpThresholdIsReadmittedOnceItsReadingSitsOnTheLoad) {
  // The drift's reading steps back by its 44 N at tick 1000, while its foot stays down. With the
  // jump test's threshold set to 50 N, no jump test sees that step. The reading (and its foot's
  // summed reading) stepped back by about its correction on a tick, beyond z sqrt(2) sigma_x
  // (16 N), and the sum residual (the reading as it is) by as much from its level before the
  // reading began to lead (a low-pass over clear_s, 50 ticks, of the usable ticks before),
  // nearer that than no step; half the correction is beyond z = 5.71 of the step's standard
  // error (2 N of scatter: 0.35 N); the reading sits on the load since (mean lead within
  // gain_min_load_N, 30 N here) with no slope or bend, and wins the stance comparison over
  // clear_s (ticks 1000-1049): the channel shows no
  // fault from tick 1050, the comparison's first chance. Without the step's cue (run once), only
  // once a window could show the drift going on at a quarter of its fitted rate: tick 1427.
  const unsigned seed = 5;
  std::printf("total force error N(0, 2 N), std::mt19937(%u)\n", seed);
  const LongStance stepped = drift_in_a_long_stance([](int) { return 0.0; }, seed, 0.0, 50.0);
  std::printf("a drift that steps back to 0 at tick 1000: re-admitted at tick %d\n", stepped.cleared);
  EXPECT_EQ(stepped.cleared, 1050);
  EXPECT_EQ(stepped.type_at_end, FaultType::none);
  // With clear_s 10 ms (the level before is a low-pass over 10 ticks) and the total force's
  // error 15 N RMS, the step's standard error is s sqrt(1 / 19 + 1 / n), s the scatter the window
  // measures: half the correction, 22 N, is beyond z of it only once the mean since has enough
  // ticks (some 75 at s = 15 N; tick 1060 with std::mt19937(5), where the window's s came out
  // smaller). Without that bar (run once): tick 1010, the comparison's first chance.
  const LongStance noisy = drift_in_a_long_stance([](int) { return 0.0; }, seed, 0.0, 50.0, 15.0, 0.01);
  std::printf("the same with clear_s 10 ms and the total force's error N(0, 15 N): re-admitted at tick %d\n",
              noisy.cleared);
  EXPECT_GE(noisy.cleared, 1040);
  EXPECT_LE(noisy.cleared, 1200);
  // The drift goes on at 40 N/s while the total force steps up by its 44 N at tick 1000: the sum
  // residual steps as an end would, and the reading as it is sits on the load for a while, but
  // the reading itself did not step. Not re-admitted (without the reading's own step, run once:
  // tick 1050).
  const auto goes_on = [](int k) { return kDriftLevelAt1000 + 40.0 * (k - 1000) * 1e-3; };
  const LongStance total_stepped = drift_in_a_long_stance(goes_on, seed, 0.0, 50.0, 2.0, 0.0, kDriftLevelAt1000);
  std::printf("a drift going on while the total force steps by its size: re-admitted at tick %d\n",
              total_stepped.cleared);
  EXPECT_EQ(total_stepped.cleared, -1);
  EXPECT_EQ(total_stepped.type_at_end, FaultType::drift);
  EXPECT_EQ(noisy.type_at_end, FaultType::none);
}

TEST(ContactForceFdi, ADriftThatStopsAtItsLevelWhileItsPadStaysLoadedIsHeldAsAnOffsetThere) {
  // From tick 1000 the drift stays at its level, 44 N (a plateau). Its reading as it is stays
  // flat, 44 N above the load, beyond gain_min_load_N (30 N in these tests): an offset of that
  // level from then on, estimated as the flat window's mean lead of the reading (the total force's
  // error averages out; 2 N RMS here). Before, the drift's slope was extrapolated through the
  // stance until the correction, some three times the level, left four times the reading's
  // power: re-admitted then, the reading 44 N too high to the end.
  const unsigned seed = 5;
  std::printf("total force error N(0, 2 N), std::mt19937(%u)\n", seed);
  const LongStance held = drift_in_a_long_stance([](int) { return kDriftLevelAt1000; }, seed);
  std::printf("a drift that stops at %.0f N: re-admitted at tick %d, %s at the end (estimate %.2f N), "
              "recovered %.2f N RMS over the last second\n",
              kDriftLevelAt1000, held.cleared, std::string(to_string(held.type_at_end)).c_str(),
              held.estimate_at_end_N, held.recovered_rms_N);
  EXPECT_EQ(held.cleared, -1);
  EXPECT_EQ(held.type_at_end, FaultType::offset);
  EXPECT_NEAR(held.estimate_at_end_N, kDriftLevelAt1000, 2.0);
  EXPECT_LT(held.recovered_rms_N, 2.0);
}

TEST(ContactForceFdi, AnOffsetOnAQuantisersLevelBoundaryIsNoDrift) {
  // 10 N steps under 0.7 N of noise (a coarse ADC the noise cannot dither): an offset of 15 N in
  // the air lies on the boundary of two levels, and its readings toggle between 10 and 20 N at
  // random, a standard deviation of 5 N where the drift test assumes sigma_x = sqrt(0.7^2 +
  // 10^2 / 12) = 2.97 N. Its line's slope must still not pass z = 5.71 of its standard errors
  // on any of these 20 swings of 0.5 s: the test is repeated every tick, but on fits whose ticks
  // are correlated, so z is conservative by more than that factor (measured, not derived).
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::printf("seed %u\n", seed);
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.7);
    const auto quantised = [](double x) { return 10.0 * std::round(x / 10.0); };
    Feet feet(suralp(10.0), 1e-3);
    feet.fdi = ContactForceFdi([] {
      ContactForceFdi::Params p = suralp(10.0);
      p.noise_std_N = 0.7;
      return p;
    }(), StageContext(1e-3, "fdi"));
    feet.fdi.reset();
    for (int k = 0; k < 650; ++k) {
      const bool swinging = k >= 100 && k < 600;
      feet.left_foot_at(swinging ? 0.03 : 0.0);
      for (std::size_t j = 0; j < kChannels; ++j) {
        feet.measured[j] = quantised((j < 4 ? (swinging ? 0.0 : 100.0) : (swinging ? 200.0 : 100.0)) + noise(rng));
      }
      if (swinging && k >= 150) feet.measured[0] = quantised(15.0 + noise(rng));
      feet.step(800.0);
      ASSERT_NE(feet.type(0), FaultType::drift) << "seed " << seed << ", tick " << k;
      if (k == 599) {
        EXPECT_EQ(feet.type(0), FaultType::offset) << "seed " << seed << ": raised by the air test";
      }
    }
  }
}

// Both feet down for the whole trace, every pad carrying 100 N; l_foot/p1 (and, with `twin` N,
// r_foot/p1 by that much) steps +60 N at tick 200 (an offset, raised by the jump test) and, unless
// `ends` is false, l_foot/p1's offset fades out over ticks [1200, 1300) at 0.6 N per tick (no
// step for the jump test). Returns the tick l_foot/p1 is re-admitted (-1: never).
int offset_faded_in_stance(bool ends, double twin, double height = 0.0) {
  Feet feet(suralp(), 1e-3);
  std::fill(feet.height.begin(), feet.height.end(), height);
  int cleared = -1;
  bool raised = false;
  for (int k = 0; k < 2000; ++k) {
    const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = 100.0 + (j % 2 == 0 ? wiggle : -wiggle);
    const double fade = ends ? std::clamp((k - 1200) / 100.0, 0.0, 1.0) : 0.0;
    if (k >= 200) feet.measured[0] += 60.0 * (1.0 - fade);
    if (twin > 0.0 && k >= 200) feet.measured[4] += twin;
    feet.step(800.0);
    raised = raised || feet.type(0) == FaultType::offset;
    if (raised && cleared < 0 && feet.type(0) == FaultType::none) cleared = k;
    if (twin > 0.0 && raised) {
      EXPECT_EQ(feet.type(4), FaultType::offset) << "r_foot/p1, tick " << k;  // its offset stays
    }
    for (std::size_t j = 1; j < kChannels; ++j) {
      if (j != 4 || twin == 0.0) {
        EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
  EXPECT_TRUE(raised);
  return cleared;
}

TEST(ContactForceFdi, AnOffsetThatFadesOutLateInALongStanceIsReadmittedOnTheTicksSinceItsEnd) {
  // The offset b left. The jump test measured the onset as 61 N (the pads' +-0.5 N alternation
  // adds 1 N to a one-tick step), so the correction leaves (b - 61)^2, and the gain its onset
  // implies (raised by a jump under load, not yet seen in the air: k = 1 + 61 / 100 = 1.61)
  // leaves (b - 0.379 x)^2, x = 100 + b the reading. The reading as it is (b^2) leaves a quarter
  // of both once b < 14.5 N: from tick 1276 (b = 14.4 N; 207 against 2172 and 857). The CUSUM of
  // the reading's lead is positive from there; after clear_s (50 ticks, the 50th is tick 1325)
  // the reading wins, decided once that tick's residual is known (after its outputs): shown from
  // tick 1326. Over the stance so far (a thousand ticks in which the correction was right) it
  // would not win for another thousand; before, an offset was only dropped in the air.
  const int cleared = offset_faded_in_stance(true, 0.0);
  std::printf("offset faded out over ticks 1200-1300: re-admitted at tick %d\n", cleared);
  EXPECT_EQ(cleared, 1326);
  // The same with every pad's height unknown (NaN: a foot pose not finite): taken as on the
  // ground, as the recovery and the correction count take it. Taken as in the air by this
  // comparison alone, the stale correction was never judged (-1).
  EXPECT_EQ(offset_faded_in_stance(true, 0.0, std::nan("")), 1326);
  // An offset that stays: its correction keeps winning.
  EXPECT_EQ(offset_faded_in_stance(false, 0.0), -1);
  // Two offsets, one fades out: either correction explains the residual's move, and the one still
  // faulty can win first (a +48 N beside the +60 N that fades: its reading as it is leaves
  // (b - 12)^2, under a quarter of (b - 60)^2 once b < 28 N, before the other's does). With two
  // corrections in the residual, neither is re-admitted by this comparison.
  EXPECT_EQ(offset_faded_in_stance(true, 60.0), -1);
  EXPECT_EQ(offset_faded_in_stance(true, 48.0), -1);
}

// offset_faded_in_stance's two +60 N offsets (l_foot/p1 and r_foot/p1, from tick 200), but the
// right foot hands its load to the left over ticks [900, 1000) and lifts 3 cm at tick 1000, where
// it stays: r_foot/p1 reads its offset alone, measured by the air test. l_foot/p1's offset fades
// out over ticks [1400, 1500) as before. Returns the tick l_foot/p1 is re-admitted (-1: never);
// r_foot/p1 must stay an offset, every other channel unflagged.
int offset_faded_beside_one_in_the_air() {
  Feet feet(suralp(), 1e-3);
  int cleared = -1;
  bool raised = false;
  for (int k = 0; k < 2200; ++k) {
    const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
    const double handed = std::clamp((k - 900) / 100.0, 0.0, 1.0);  // of the right foot's load
    std::fill(feet.height.begin() + 4, feet.height.end(), k >= 1000 ? 0.03 : 0.0);
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = j < 4 ? 100.0 * (1.0 + handed) : 100.0 * (1.0 - handed);
      feet.measured[j] = load + (j % 2 == 0 ? wiggle : -wiggle);
    }
    const double fade = std::clamp((k - 1400) / 100.0, 0.0, 1.0);
    if (k >= 200) feet.measured[0] += 60.0 * (1.0 - fade);
    if (k >= 200) feet.measured[4] += 60.0;
    feet.step(800.0);
    raised = raised || feet.type(0) == FaultType::offset;
    if (raised && cleared < 0 && feet.type(0) == FaultType::none) cleared = k;
    if (k >= 215) {
      EXPECT_EQ(feet.type(4), FaultType::offset) << "r_foot/p1, tick " << k;
    }
    for (std::size_t j = 1; j < kChannels; ++j) {
      if (j != 4) {
        EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
  EXPECT_TRUE(raised);
  return cleared;
}

TEST(ContactForceFdi, AnOffsetBesideACorrectionInTheAirIsReadmittedOnTheTicksSinceItsEnd) {
  // A pad in the air is recovered as 0 whatever its correction, so the sum residual carries one
  // correction, l_foot/p1's: its end is judged as if it were alone, as in the test before. The
  // reading as it is (b^2) leaves a quarter of the correction's (b - 61)^2 once b < 20.3 N (from
  // about tick 1467), and the reading wins clear_s (50 ticks) later: tick 1516. Counting
  // r_foot/p1's correction as in the residual, the comparison never judged it: held to the end
  // of the trace (-1). On the walk that showed it (tools/unseen_walks.py --fault-seed 29
  // --seed-offset 5000, SURALP walk 7) a pad blamed for another's offset was held 3.26 s.
  const int cleared = offset_faded_beside_one_in_the_air();
  std::printf("offset faded out over ticks 1400-1500 beside one in the air: re-admitted at tick %d\n", cleared);
  EXPECT_EQ(cleared, 1516);
}

// l_foot/p1 reads a true +48 N offset from tick 200 that stays; r_foot/p1 a +60 N one that fades
// out over ticks [1200, 1300) with both feet down; the right foot hands its load to the left over
// [lift - 100, lift) and lifts 3 cm (or to `lifted_height` m) at `lift`. Returns the tick l_foot/p1
// is re-admitted (-1: never by tick 2400).
int true_offset_beside_an_ended_one_that_lifts(int lift, double lifted_height = 0.03) {
  Feet feet(suralp(), 1e-3);
  int cleared = -1;
  bool raised = false;
  for (int k = 0; k < 2400; ++k) {
    const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
    const double handed = std::clamp((k - (lift - 100)) / 100.0, 0.0, 1.0);
    std::fill(feet.height.begin() + 4, feet.height.end(), k >= lift ? lifted_height : 0.0);
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = j < 4 ? 100.0 * (1.0 + handed) : 100.0 * (1.0 - handed);
      feet.measured[j] = load + (j % 2 == 0 ? wiggle : -wiggle);
    }
    const double fade = std::clamp((k - 1200) / 100.0, 0.0, 1.0);
    if (k >= 200) feet.measured[0] += 48.0;
    if (k >= 200) feet.measured[4] += 60.0 * (1.0 - fade);
    feet.step(800.0);
    raised = raised || feet.type(0) == FaultType::offset;
    if (raised && cleared < 0 && feet.type(0) == FaultType::none) cleared = k;
  }
  EXPECT_TRUE(raised);
  return cleared;
}

TEST(ContactForceFdi, ATrueOffsetIsNotJudgedOnTicksThatHeldAnotherCorrection) {
  // While both corrections are in the residual and r_foot/p1's has ended, the residual is about
  // -61 N: l_foot/p1's reading as it is (-13 N) leads its correction's, but those ticks hold two
  // corrections and are not judged. Summed all the same, they were judged the tick the right
  // foot lifted (its correction then out of the residual): l_foot/p1 dropped at lift + 1, for
  // a lift at 1320, 1500 or 1700 (a review's probe). Summed only over ticks with one
  // correction in the residual, l_foot/p1 stays, its correction right in every one of them.
  for (const int lift : {1320, 1500, 1700}) {
    const int cleared = true_offset_beside_an_ended_one_that_lifts(lift);
    std::printf("the other foot lifts at tick %d: the true offset re-admitted at tick %d\n", lift, cleared);
    EXPECT_EQ(cleared, -1) << "lift at tick " << lift;
  }
}

TEST(ContactForceFdi, APadAtTheAirborneHeightOrOfUnknownHeightKeepsItsCorrectionInTheResidual) {
  // Pins the count of corrections in the sum residual (corrections_in_residual): a pad is in the
  // air only when its height is known and above airborne_height_m. The previous test's scenario,
  // the right foot "lifted" to exactly airborne_height_m (not above it: on the ground), or to an
  // unknown height (NaN: taken as on the ground). Either way r_foot/p1's ended +60 N correction
  // stays in the sum residual (near -60 N from its fade on), so the residual holds two
  // corrections and l_foot/p1's true +48 N offset is never judged: held to the end (-1).
  // Counted as in the air (`>=` for `>` at the boundary, or NaN taken as airborne), the sums
  // restart at the lift with one correction: l_foot/p1's reading as it is leaves (-60 + 48)^2 =
  // 144, under a quarter of its correction's 60^2, and it wins after clear_s (50 ticks, lift to
  // lift + 49), shown on lift + 50: the true offset dropped on ticks 1370, 1550, 1750 (measured
  // with each mutant).
  const double boundary = suralp().airborne_height_m;
  for (const double lifted_height : {boundary, std::nan("")}) {
    for (const int lift : {1320, 1500, 1700}) {
      const int cleared = true_offset_beside_an_ended_one_that_lifts(lift, lifted_height);
      std::printf("the other foot at %g m from tick %d: the true offset re-admitted at tick %d\n", lifted_height, lift,
                  cleared);
      EXPECT_EQ(cleared, -1) << "lift at tick " << lift << " to " << lifted_height << " m";
    }
  }
}

// As doubling_gain_cleared_at(false, ...): l_foot/p1 is held as a gain from the air (k = 1.98:
// 450 / 227.25) and lands on tick 500 on 300 N, still faulty (reading 450 N: its correction
// leaves -72.75 N in the residual, the reading as it is +150 N). r_foot/p1 reads a +150 N offset
// from tick 200 (raised by the jump test), which ends inside the left foot's landing guard (ticks
// 500-649): it fades out over ticks [503, 523) at 7.5 N a tick (under jump_threshold_N). The
// right foot lifts 10 cm, its pads to 0, at `right_lift`. Returns the first tick from 500 on where
// l_foot/p1 is not a gain fault (-1: none by tick 1500); no pad but the two is flagged.
int gain_beside_an_offset_ended_in_its_guard(int right_lift) {
  Feet feet(suralp(), 1e-3);
  int cleared = -1;
  for (int k = 0; k < 1500; ++k) {
    const bool right_lifted = k >= right_lift;
    const double truth = doubling_gain_tick(feet, k, right_lifted, false);
    const double fade = std::clamp((k - 503) / 20.0, 0.0, 1.0);
    if (k >= 200 && !right_lifted) feet.measured[4] += 150.0 * (1.0 - fade);
    feet.step(truth);
    if (k == 499) {
      EXPECT_EQ(feet.type(0), FaultType::gain) << "the jump, read 0 in the air, is a gain";
    }
    if (k >= 500 && cleared < 0 && feet.type(0) != FaultType::gain) cleared = k;
    for (std::size_t j = 1; j < kChannels; ++j) {
      if (j != 4) {
        EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
  return cleared;
}

TEST(ContactForceFdi, AGuardsTicksThatHeldAnotherCorrectionAreNoEvidenceOfAGainsEnd) {
  // Pins compare_held_gain_in_guard's "one correction in the residual": a guard tick holding two
  // restarts the guard's sums. From tick 523 to the right foot's lift (645) the residual is
  // -72.75 - 150 = -222.75 N (both corrections in it, r_foot/p1's wrong), which l_foot/p1's
  // reading as it is (its correction 450 - 227.25 = 222.75 N added back) explains exactly: those
  // ticks say nothing of which correction is wrong. Its guard sums hold only the ticks from the
  // lift to 649 (5 at most, under clear_s's 50): no verdict on tick 650, the first after the
  // guard; the stance after it holds one correction, which leaves 72.75 N against the reading's
  // 150 N: the gain, still there, is held to the end (-1). Summing the guard's ticks whatever
  // the count (the condition dropped, or `corrections > 2`), the reading leaves 0.05 of the
  // correction's power over the 150 ticks, and with one correction on tick 650 the gain was
  // dropped there, shown on tick 651 (measured with each mutant for lifts on ticks 645 and 650;
  // in probes also 610, 620 and 649).
  for (const int right_lift : {645, 650}) {
    const int cleared = gain_beside_an_offset_ended_in_its_guard(right_lift);
    std::printf("the other foot lifts on tick %d: the faulty gain dropped at tick %d\n", right_lift, cleared);
    EXPECT_EQ(cleared, -1) << "right foot lifted on tick " << right_lift;
  }
}

TEST(ContactForceFdi, AnOffsetRaisedUnderLoadThatIsAGainIsNotDroppedAsItsPadUnloads) {
  // A x1.5 gain on a pad carrying 150 N: its onset jumps +75 N, raised as an offset (L0 = 150 N).
  // Then the pad hands its load to its neighbour over ticks 600-700, the foot down throughout
  // (150 N of load move: under the 2 sum_threshold_N the offset-or-gain test waits for). The
  // offset's correction (75 N) grows wrong as the load falls (0.5 L - 75), and the reading as it is
  // (0.5 L) leaves a quarter of its power once L < 50 N: taken alone, that comparison dropped
  // the fault at tick 716. The gain the onset implies (k = 1.5) explains the reading exactly, so
  // the reading as it is does not win: the channel stays flagged.
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 1200; ++k) {
    const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = 100.0 + (j % 2 == 0 ? wiggle : -wiggle);
    const double handed = 150.0 * std::clamp((k - 600) / 100.0, 0.0, 1.0);
    const double load0 = 150.0 - handed;
    feet.measured[1] += 50.0 + handed;  // pad 1 carries 150 N, then 300 N
    feet.measured[0] += load0 - 100.0;
    double fz = 0.0;
    for (double x : feet.measured) fz += x;
    if (k >= 200) feet.measured[0] += 0.5 * load0;  // reads 1.5 times its load
    feet.step(fz);
    if (k >= 215) {
      ASSERT_NE(feet.type(0), FaultType::none) << "tick " << k;
    }
    for (std::size_t j = 1; j < kChannels; ++j) ASSERT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
  }
}

// At 200 Hz, l_foot/p1 (channel 0) carries 100 N and reads `scale` times its load plus `offset`
// from tick 100 (0.5 s): a jump of (scale - 1) 100 N + offset, raised as an offset that may be a
// gain (L0 = 100 N). Over ticks [150, 250) its load rises by `move` and falls back, taken from
// l_foot/p2 (under the 2 sum_threshold_N, 160 N, the offset-or-gain test waits for; if
// `move_held`, it rises over [150, 200) and stays). If `lifts`,
// the left foot then rolls off its other pads over ticks [250, 300) (2 N a tick each, to the right
// foot's pads), and channel 0 sheds its 100 N in three ticks from tick 300 (a lift-off logged at
// 200 Hz); the foot is 3 cm up from tick 303. Else the foot stays down and the offset (if any)
// ends at tick 300. The total force reads `bias` beyond the pads' loads. Returns the channel's
// type at tick 320 and the first tick it is typed gain (-1: never).
std::pair<FaultType, int> fault_on_a_pad_at_200_hz(double scale, double offset, bool lifts, double move = 50.0,
                                                   double bias = 0.0, bool move_held = false) {
  Feet feet(suralp(), 5e-3);
  int typed_gain = -1;
  for (int k = 0; k <= 320; ++k) {
    const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
    const double rolled = lifts ? std::clamp((k - 250) / 50.0, 0.0, 1.0) : 0.0;  // of pads 1-3's loads
    const double shed = lifts ? std::clamp((k - 299) / 3.0, 0.0, 1.0) : 0.0;     // of pad 0's load
    const double moved = move * std::clamp(move_held ? (k - 150) / 50.0 : 1.0 - std::abs(k - 200) / 50.0, 0.0, 1.0);
    std::fill(feet.height.begin(), feet.height.begin() + 4, lifts && k >= 303 ? 0.03 : 0.0);
    const double load0 = (1.0 - shed) * (100.0 + moved);
    const double right = 100.0 + (300.0 * rolled + 100.0 * shed) / 4.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = j == 0 ? load0 : j < 4 ? 100.0 * (1.0 - rolled) - (j == 1 ? moved : 0.0) : right;
      feet.measured[j] = load + (j % 2 == 0 ? wiggle : -wiggle);
    }
    if (k >= 100) feet.measured[0] += (scale - 1.0) * load0 + (!lifts && k >= 300 ? 0.0 : offset);
    feet.step(800.0 + bias);
    if (typed_gain < 0 && feet.type(0) == FaultType::gain) typed_gain = k;
  }
  return {feet.type(0), typed_gain};
}

// At 500 Hz, l_foot/p1 (channel 0) carries `onset_load` N and reads `scale` times its load from
// tick 100: a jump of (scale - 1) onset_load, raised as an offset that may be a gain. Over ticks
// [150, 200) its load moves by `move` (handed to or taken from l_foot/p2, which carries 200 N) and
// stays. The left foot then rolls off its other pads over ticks [250, 300) onto the right foot's,
// and channel 0 sheds its load in `shed_ticks` ticks from tick 300 (a lift-off); the foot is 3 cm
// up once it has. F_z is the pads' true sum. Returns the channel's type at tick 320 and the first
// tick it was typed gain (-1: never).
std::pair<FaultType, int> gain_pad_shedding_at_500_hz(double onset_load, double move, int shed_ticks, double scale) {
  Feet feet(suralp(), 2e-3);
  int typed_gain = -1;
  for (int k = 0; k <= 320; ++k) {
    const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
    const double rolled = std::clamp((k - 250) / 50.0, 0.0, 1.0);  // of pads 1-3's loads
    const double shed = std::clamp((k - 299) / static_cast<double>(shed_ticks), 0.0, 1.0);  // of pad 0's load
    const double moved = move * std::clamp((k - 150) / 50.0, 0.0, 1.0);
    feet.left_foot_at(k >= 300 + shed_ticks ? 0.03 : 0.0);
    const double load0 = (1.0 - shed) * (onset_load + moved);
    double left = 0.0;
    for (std::size_t j = 0; j < 4; ++j) {
      const double load = j == 0 ? load0 : (1.0 - rolled) * (j == 1 ? 200.0 - moved : 100.0);
      left += load;
      feet.measured[j] = load + (j % 2 == 0 ? wiggle : -wiggle);
    }
    const double right = (onset_load + 600.0 - left) / 4.0;  // the rest of a constant total
    for (std::size_t j = 4; j < kChannels; ++j) feet.measured[j] = right + (j % 2 == 0 ? wiggle : -wiggle);
    double fz = 0.0;
    for (double x : feet.measured) fz += x;
    if (k >= 100) feet.measured[0] += (scale - 1.0) * load0;
    feet.step(fz);
    if (typed_gain < 0 && feet.type(0) == FaultType::gain) typed_gain = k;
  }
  return {feet.type(0), typed_gain};
}

TEST(ContactForceFdi, AGainTakenWithinItsStepBacksWindowIsNotTakenForAnEndedOffset) {
  // A x1.5 gain on a pad carrying 380 N (raised as a +190 N offset), whose load falls to 260 N and
  // is then shed in 6 ticks at 500 Hz. The offset-or-gain test waits for the load to move 160 N
  // from its onset: the shedding takes it there on tick 303, inside the window of the shedding's
  // step, and the gain was taken there, then cleared by that group's decision on tick 304 as a
  // step back by the offset's size (a grid of onset loads 150-400 N, moves 0 to -120 N, sheds in 3-14
  // ticks, x1.5 and x2 at 1 and 2 ms found this one shape: onset loads 360-400 N). The step is the
  // gain's load leaving, judged with the gain it was taken for: it stays a gain.
  const auto [type, typed_gain] = gain_pad_shedding_at_500_hz(380.0, -120.0, 6, 1.5);
  EXPECT_EQ(typed_gain, 304);
  EXPECT_EQ(type, FaultType::gain);
}

TEST(ContactForceFdi, AGainWhosePadLiftsWithinAJumpWindowIsNotTakenForAnEndedOffset) {
  // A x2 gain: its reading falls by twice the load its pad sheds, 67 N on tick 300 (within the
  // step-back band of its +100 N offset), and once the pad is unloaded the sum residual has
  // stepped by the offset (the reading 0, corrected to -100 N), as an offset's end moves it: the
  // offset was cleared when that group was decided, and the gain went on unflagged. The load's
  // move over ticks [150, 250) left the offset's correction wrong by half of it and the gain's
  // right, so the gain led the offset-or-gain comparison at the jump, and the leave-one-out force
  // fell across the step as the gain implies for the reading's fall: the gain is taken on it.
  const auto [gain_type, gain_tick] = fault_on_a_pad_at_200_hz(2.0, 0.0, true);
  std::printf("a x2 gain whose pad lifts at tick 300 (200 Hz): typed gain at tick %d\n", gain_tick);
  EXPECT_EQ(gain_type, FaultType::gain);
  EXPECT_EQ(gain_tick, 301);
  // A true +50 N offset through the same load move, that ends at tick 300 with its foot down: its
  // correction was right throughout, the gain never led, and its step back ends it as before.
  const auto [offset_type, offset_gain_tick] = fault_on_a_pad_at_200_hz(1.0, 50.0, false);
  EXPECT_EQ(offset_type, FaultType::none);
  EXPECT_EQ(offset_gain_tick, -1);
  // The same offset with its load 20 N lower from tick 200 on (not back) and the total force
  // reading 5 N high (a review's probe): near L0 the two models meet, and the bias let the gain
  // lead at the jump; but the leave-one-out force did not step with the reading, as it does when
  // a pad sheds its load: the end stands. (Taken on the gain's lead alone, it was typed a gain on
  // tick 301, as were 12 more of 48 such traces: offsets of 50 and 100 N, moves of +-20 and
  // +-40 N, biases of +-5 to +-20 N; none is now.)
  const auto [biased_type, biased_gain_tick] = fault_on_a_pad_at_200_hz(1.0, 50.0, false, -20.0, 5.0, true);
  EXPECT_EQ(biased_type, FaultType::none);
  EXPECT_EQ(biased_gain_tick, -1);
}

TEST(ContactForceFdi, AnOffsetTakenAsAGainIsNotJudgedOnTheTickItWasRetyped) {
  // A x2 gain on a pad carrying 400 N: its onset jumps +400 N, raised as an offset (b = 400 N,
  // L0 = 400 N). From tick 300 the pad hands its load to its neighbour within 20 ticks, down to
  // 10 N, its foot down throughout. The offset-or-gain test takes it as a gain (k = 2) once the
  // 10 Hz low-pass of its leave-one-out force has moved 160 N from L0: on tick 320, the load's
  // first at 10 N. On that tick the recovered value and the residual were computed as x - b: a
  // correction of 400 N and a residual of L - L0 = -390 N, which the gain's stance comparison
  // took as its first tick. That one tick outweighed the 49 after it (the gain's correction
  // x - x / k = 10 N, the reading as it is 10 N off): the reading "won" and the gain, still
  // there, was dropped on tick 369. The tick is no evidence for either model.
  Feet feet(suralp(), 1e-3);
  int typed_gain = -1;
  for (int k = 0; k < 1000; ++k) {
    const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = 100.0 + (j % 2 == 0 ? wiggle : -wiggle);
    const double load2 = 10.0 + 390.0 * (1.0 - std::clamp((k - 300) / 20.0, 0.0, 1.0));
    feet.measured[2] += load2 - 100.0;
    feet.measured[3] += 400.0 - load2;  // pad 3 takes what pad 2 hands on
    double fz = 0.0;
    for (double x : feet.measured) fz += x;
    if (k >= 100) feet.measured[2] += load2;  // reads twice its load
    feet.step(fz);
    if (typed_gain < 0 && feet.type(2) == FaultType::gain) typed_gain = k;
    if (k >= 110) {
      ASSERT_NE(feet.type(2), FaultType::none) << "tick " << k << " (typed gain on " << typed_gain << ")";
    }
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 2) {
        ASSERT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
  EXPECT_EQ(typed_gain, 320) << "typed once the load had moved, not at its onset";
  EXPECT_EQ(feet.type(2), FaultType::gain);
  EXPECT_NEAR(feet.outs[ContactForceFdi::kRecovered][2], 10.0, 1.0) << "x / k";
}

TEST(ContactForceFdi, AGainCorrectionThatDoesNotLowerTheResidualIsDroppedWithoutIsolation) {
  FaultType middle = FaultType::none;
  EXPECT_EQ(gain_held_then(true, middle), FaultType::none) << "re-admitted by model comparison";
  EXPECT_EQ(middle, FaultType::gain);
  EXPECT_EQ(gain_held_then(false, middle), FaultType::gain) << "a real gain fault stays";
  EXPECT_EQ(middle, FaultType::gain);
}

}  // namespace
}  // namespace ftsense::biped

namespace ftsense::biped {
namespace {

// Pad 0 carries 100 + 50 sin(2 pi k / 200) N. From tick 300 to 600 it reads either minus its load
// (a sign flip) or its load - 180 N (a negative offset): both read below zero under load, and
// only the line of the reading on the leave-one-out force (slope -1 against +1) tells them apart,
// once that force has moved beyond its error bound.
TEST(ContactForceFdi, ALoadedPadReadingMinusItsLoadIsASignFlipNotANegativeOffset) {
  constexpr double kTwoPi = 6.283185307179586;
  Feet flip(suralp(), 1e-3), offset(suralp(), 1e-3);
  for (int k = 0; k < 800; ++k) {
    const double load = 100.0 + 50.0 * std::sin(kTwoPi * k / 200.0);
    for (std::size_t j = 1; j < kChannels; ++j) flip.measured[j] = offset.measured[j] = moving(j, k, 0.0);
    flip.measured[0] = offset.measured[0] = load;
    double truth = 0.0;
    for (double x : flip.measured) truth += x;
    const bool faulty = k >= 300 && k < 600;
    if (faulty) {
      flip.measured[0] = -load;
      offset.measured[0] = load - 180.0;
    }
    flip.step(truth);
    offset.step(truth);
    // The flip is judged once the leave-one-out force has spanned sum_threshold_N = 80 N since the
    // first negative reading (from 50 N at tick 350 to 130 N near tick 421).
    if (k == 421) {
      EXPECT_EQ(flip.type(0), FaultType::offset) << "the confirmed jump, not yet judged a flip";
    }
    if (k == 450) {
      EXPECT_EQ(flip.type(0), FaultType::gain);
      EXPECT_NEAR(flip.outs[ContactForceFdi::kRecovered][0], load, 1e-6) << "read / k with k = -1";
      EXPECT_EQ(offset.type(0), FaultType::offset);
      EXPECT_NEAR(offset.outs[ContactForceFdi::kFaultEstimate][0], -180.0, 2.0);
    }
    if (k >= 300 && k < 600) {
      ASSERT_NE(offset.type(0), FaultType::gain) << "tick " << k;
    }
    for (std::size_t j = 1; j < kChannels; ++j) {
      ASSERT_EQ(flip.type(j), FaultType::none) << "channel " << j << ", tick " << k;
    }
  }
  EXPECT_EQ(flip.type(0), FaultType::none) << "right side up again under load: re-admitted";
}

// A quadruped: four point feet of one sensor each, as many feet as measured carries channels.
// The left front foot swings reading +20 N (an offset that starts as it lifts), the other three
// carry the 130 N of a 13 kg robot; the thresholds follow from the 0.5 N noise and the weight.
// The 20 N step is 40 sigma, far above the derived 5 N jump threshold, and the sum residual steps
// by as much: the jump is confirmed once jump_window_s (10 ticks) has seen it, on tick lift + 9.
// The airborne mean then measures the offset; once down, the foot is recovered by subtracting it.
// No other foot is blamed.
// Spikes every `gap` ticks on a loaded pad from tick 300, `count` of them; returns the ticks after
// the last spike's detection at which the flag is first down (-1: never within 2000 ticks), and
// checks it was spikes until then.
int spike_flag_clears_after(int gap, int count, const ContactForceFdi::Params& p) {
  Feet feet(p, 1e-3);
  const int first = 300, last = first + gap * (count - 1);
  for (int k = 0; k < last + 2000; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    if (k >= first && k <= last && (k - first) % gap == 0) feet.measured[2] += 150.0;
    feet.step();
    if (k > last + 1) {  // the last spike is seen on the tick after it
      if (feet.type(2) == FaultType::none) return k - (last + 1);
      EXPECT_EQ(feet.type(2), FaultType::spikes) << "tick " << k;
    }
  }
  return -1;
}

TEST(ContactForceFdi, TheSpikeFlagIsHeldForTheGapARunningSpikeProcessRarelyLeaves) {
  // Every 20 ticks at 1 kHz: lambda^ = (n - 1) / D = 50 Hz over the seen time, so the hold is
  // h = ln(1 / 0.01) / 50 = 92.1 ms: the flag is down on the 93rd tick after the last spike.
  const auto p = suralp();
  EXPECT_EQ(spike_flag_clears_after(20, 10, p), 93);
  // Every 100 ticks (10 Hz): h = 460.5 ms.
  EXPECT_EQ(spike_flag_clears_after(100, 5, p), 461);
  // Slower than ln(100) / spike_hold_s = 5.76 Hz (every 200 ticks): spike_hold_s (0.8 s) caps it.
  EXPECT_EQ(spike_flag_clears_after(200, 4, p), 800);
  // A single spike: no rate, spike_hold_s.
  EXPECT_EQ(spike_flag_clears_after(20, 1, p), 800);
  // A rarer gap asked for holds longer: p_gap = 1e-4 doubles ln(1 / p_gap).
  auto strict = p;
  strict.spike_gap_probability = 1e-4;
  EXPECT_EQ(spike_flag_clears_after(20, 10, strict), 185);
}

TEST(ContactForceFdi, AQuadrupedsPointFeetAreJudgedAsManyAsMeasuredCarries) {
  ContactForceFdi::Params p;
  p.points_per_foot = 1;
  p.noise_std_N = 0.5;
  p.weight_N = 130.0;
  ContactForceFdi fdi(p, StageContext(1e-3, "fdi", {{"measured", 4}}));
  std::vector<std::string> inputs;
  for (const auto& port : fdi.ports().inputs()) inputs.push_back(port.name);
  EXPECT_EQ(inputs, (std::vector<std::string>{"measured", "total_force", "point_height"}));
  ASSERT_EQ(fdi.ports().inputs()[ContactForceFdi::kMeasured].dim, 4u);
  std::vector<std::vector<double>> outs;
  for (const auto& port : fdi.ports().outputs()) outs.emplace_back(port.dim, 0.0);
  fdi.reset();
  std::vector<double> measured(4), total{0.0, 0.0, 130.0};
  std::vector<double> height(4, 0.0);
  const int lift = 100, land = 300;
  int raised_at = -1;
  for (int k = 0; k < 400; ++k) {
    const bool swinging = k >= lift && k < land;
    height[0] = swinging ? 0.03 : 0.0;
    const double wiggle = k % 2 == 0 ? 0.3 : -0.3;  // a noisy sensor never repeats itself
    // The load leaves the foot over the 50 ticks before it lifts and returns over the 50 after
    // it lands (a weight shift, not a step).
    const double share = std::clamp(std::max(lift - k, k - land + 1) / 50.0, 0.0, 1.0);
    const double loads[4] = {32.5 * share, 43.333 - 10.833 * share, 43.334 - 10.834 * share, 43.333 - 10.833 * share};
    for (std::size_t j = 0; j < 4; ++j) measured[j] = loads[j] + wiggle * (j % 2 == 0 ? 1.0 : -1.0);
    if (k >= lift) measured[0] += 20.0;  // the offset starts as the foot lifts
    const std::span<const double> ins[] = {measured, total, height};
    std::vector<std::span<double>> out_spans(outs.begin(), outs.end());
    fdi.step(StepIO{k * 1e-3, ins, out_spans});
    const auto type = [&](std::size_t j) {
      return fault_type_from_code(outs[ContactForceFdi::kFaultType][j]).value_or(FaultType::unclassified);
    };
    if (raised_at < 0 && type(0) != FaultType::none) raised_at = k;
    for (std::size_t j = 1; j < 4; ++j) ASSERT_EQ(type(j), FaultType::none) << "foot " << j << ", tick " << k;
  }
  EXPECT_EQ(raised_at, lift + 9);
  EXPECT_EQ(fault_type_from_code(outs[ContactForceFdi::kFaultType][0]), FaultType::offset);
  EXPECT_NEAR(outs[ContactForceFdi::kFaultEstimate][0], 20.0, 0.1);
  EXPECT_NEAR(outs[ContactForceFdi::kRecovered][0], 32.5 + 0.3 * (399 % 2 == 0 ? 1.0 : -1.0), 0.1);
}

// SURALP's sole: four pads on a 0.24 m x 0.15 m rectangle (configs/suralp_robust.json).
const std::vector<std::array<double, 2>> kSuralpSole = {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}, {-0.12, -0.075}};

// Two pads frozen at once, one on each foot, both loaded: the total force leaves their sum only.
// Given the sole's layout (points), the loads of each foot lie on a plane, which tells each its
// own share: recovered within 1e-4 N on this noiseless trace (the solver's ridge of 1e-9); without
// it, they share equally. Both freeze below the largest load they have shown (not a ceiling).
// Returns the largest |recovered - true| of the two over the last 200 ticks, and checks both were
// flagged frozen.
double frozen_pair_error(bool with_points) {
  auto p = suralp();
  if (with_points) p.points = kSuralpSole;
  Feet feet(p, 1e-3);
  constexpr double kPi = std::numbers::pi;
  std::vector<double> truth(kChannels);
  const int freeze = 600, ticks = 1000;
  double worst = 0.0;
  for (int k = 0; k < ticks; ++k) {
    const double t = k * 1e-3;
    // Each foot's pads carry a + b x + c y, a rolling load (under 2 N per tick).
    const double left[3] = {300.0 + 50.0 * std::cos(2 * kPi * 0.5 * t), 600.0 + 300.0 * std::sin(2 * kPi * 0.7 * t),
                            200.0 * std::cos(2 * kPi * 0.3 * t)};
    const double right[3] = {450.0 + 40.0 * std::cos(2 * kPi * 0.4 * t), -500.0 + 200.0 * std::sin(2 * kPi * 0.6 * t),
                             -150.0 + 100.0 * std::sin(2 * kPi * 0.9 * t)};
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double* plane = j < 4 ? left : right;
      truth[j] = plane[0] + plane[1] * (j % 4 < 2 ? 0.12 : -0.12) +
                 plane[2] * (j % 2 == 0 ? 0.075 : -0.075);
    }
    double sum = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      sum += truth[j];
      // l_foot/p4 and r_foot/p3 stick at their last reading.
      if (k < freeze || (j != 3 && j != 6)) feet.measured[j] = truth[j];
    }
    feet.step(sum);
    if (k >= ticks - 200) {
      EXPECT_EQ(feet.type(3), FaultType::frozen) << "tick " << k;
      EXPECT_EQ(feet.type(6), FaultType::frozen) << "tick " << k;
      for (const std::size_t j : {std::size_t{3}, std::size_t{6}}) {
        worst = std::max(worst, std::abs(feet.outs[ContactForceFdi::kRecovered][j] - truth[j]));
      }
    }
  }
  return worst;
}

TEST(ContactForceFdi, TwoFrozenPadsOnTwoFeetAreRecoveredFromTheirSolesPlanes) {
  const double with_points = frozen_pair_error(true);
  const double equal_shares = frozen_pair_error(false);
  std::printf("largest error of the two recovered pads: %.3g N with the sole's layout, %.1f N with equal shares\n",
              with_points, equal_shares);
  EXPECT_LT(with_points, 1e-4);
  EXPECT_GT(equal_shares, 50.0);
}

TEST(ContactForceFdi, AFrozenPadOnAFootWhoseOtherPadsReadNothingCarriesNothingOfAnotherFootsLoad) {
  // Pads 3 (left) and 6 (right) stick at their readings from tick 300 (exact repeats: frozen and
  // substituted). From tick 600 the left foot is about to lift: on the ground still, its loads 0,
  // its healthy pads reading +-1 N. The right foot carries all of F_z; pad 6 carries what the
  // right foot's other pads leave of it, and pad 3 nothing. No sole layout: no plane relation,
  // the sum alone (equal shares gave each half of pad 6's 240 N).
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 800; ++k) {
    const double noise = k % 2 == 0 ? 1.0 : -1.0;
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = j < 4 ? (k < 600 ? 150.0 + 10.0 * static_cast<double>(j) : 0.0)
                                 : (k < 600 ? 200.0 : 240.0) + 10.0 * static_cast<double>(j - 4);
      fz += load;
      if (k < 300 || (j != 3 && j != 6)) feet.measured[j] = load + noise;
    }
    feet.step(fz);
    if (k >= 700) {
      ASSERT_EQ(feet.type(3), FaultType::frozen) << "tick " << k;
      ASSERT_EQ(feet.type(6), FaultType::frozen) << "tick " << k;
      // F_z less the readable pads as read: 260 N, less the noise of six pads (+-6 N).
      EXPECT_NEAR(feet.outs[ContactForceFdi::kRecovered][6], 260.0 - 6.0 * noise, 1e-9) << "tick " << k;
      EXPECT_EQ(feet.outs[ContactForceFdi::kRecovered][3], 0.0) << "tick " << k;
    }
  }
}

TEST(ContactForceFdi, ALiftingFootsSubstitutedPadTakesOnNoLoadThatTheTotalForceLeaves) {
  // Pad 6 sticks from tick 300 (exact repeats: frozen, substituted); from tick 600 the right foot
  // is about to lift (on the ground, its loads 0, its readable pads at +-1 N), and from tick 700
  // F_z reads 100 N above the loads' sum. Pad 6 is the one substituted pad, so it takes what F_z
  // leaves, but a lifting sole takes on no load: it carries no more than on the tick before, 0
  // from the first tick the pads' noise leaves it nothing. The 100 N stay in the sum residual,
  // reported unisolated (without the rule pad 6 carried them: 100 N +- 7 N).
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 1500; ++k) {
    const double noise = k % 2 == 0 ? 1.0 : -1.0;
    double fz = k >= 700 ? 100.0 : 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = j < 4 ? (k < 600 ? 150.0 : 240.0) + 10.0 * static_cast<double>(j)
                                 : (k < 600 ? 200.0 + 10.0 * static_cast<double>(j - 4) : 0.0);
      fz += load;
      if (k < 300 || j != 6) feet.measured[j] = load + noise;
    }
    feet.step(fz);
    if (k >= 610) {
      ASSERT_EQ(feet.type(6), FaultType::frozen) << "tick " << k;
      EXPECT_EQ(feet.outs[ContactForceFdi::kRecovered][6], 0.0) << "tick " << k;
    }
    if (k == 1499) {
      EXPECT_EQ(feet.outs[ContactForceFdi::kUnisolated][0], 1.0);
    }
  }
}

TEST(ContactForceFdi, AFrozenPadALandingSoleStandsOnAloneKeepsItsShareOfTheLoad) {
  // As above, but the left foot lifts (0.05 m) from tick 600 and lands on tick 900 on its heel
  // pad 3 alone (200 N for 60 ticks; pads 0-2 on the ground, unloaded), then on all four. Inside
  // the landing's guard the sole is not taken as lifting: pads 3 and 6 share what the total
  // force leaves (200 N and 385 N, less the noise of six pads), as without the rule, not 0 and all.
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 1000; ++k) {
    if (k == 600) feet.left_foot_at(0.05);
    if (k == 900) feet.left_foot_at(0.0);
    const double noise = k % 2 == 0 ? 1.0 : -1.0;
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      double load = j < 4 ? 150.0 + 10.0 * static_cast<double>(j) : 200.0 + 10.0 * static_cast<double>(j - 4);
      if (j < 4 && k >= 600) load = k < 900 ? 0.0 : k < 960 ? (j == 3 ? 200.0 : 0.0) : 150.0;
      if (j >= 4 && k >= 600 && k < 960) load += 150.0 + 10.0 * 1.5;  // the left foot's load, on the right
      fz += load;
      if (k < 300 || (j != 3 && j != 6)) feet.measured[j] = load + noise;
    }
    feet.step(fz);
    if (k > 900 && k < 960) {
      ASSERT_EQ(feet.type(3), FaultType::frozen) << "tick " << k;
      ASSERT_EQ(feet.type(6), FaultType::frozen) << "tick " << k;
      const double share = (200.0 + 220.0 + 165.0 - 6.0 * noise) / 2.0;
      EXPECT_NEAR(feet.outs[ContactForceFdi::kRecovered][3], share, 1e-9) << "tick " << k;
      EXPECT_NEAR(feet.outs[ContactForceFdi::kRecovered][6], share, 1e-9) << "tick " << k;
    }
  }
}

TEST(ContactForceFdi, PointsMustDescribeEveryChannelOfAFoot) {
  auto p = suralp();
  p.points = {{0.12, 0.075}, {0.12, -0.075}, {-0.12, 0.075}};
  try {
    const ContactForceFdi fdi(p, StageContext(1e-3, "fdi"));
    FAIL() << "three points for four channels per foot";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems()[0].path, "/params/points");
  }
}

// The left foot swings and lands; 40 ms after its touchdown, inside the guard where the sum
// residual carries the impact, r_foot/p1 (loaded) steps by +80 N. Returns the tick it is flagged
// (-1: not by the trace's end, 0.94 s, still inside the 150 ms guard), and checks that no other
// channel is flagged. At 1 kHz unless `period_s` says otherwise; with `one_tick`, the reading is
// back on the tick after (a spike, not a step: flagged as such, or not at all inside the guard).
int offset_flagged_inside_a_touchdown_guard(bool with_points, double period_s = 1e-3, bool one_tick = false) {
  auto p = suralp();
  if (with_points) p.points = kSuralpSole;
  Feet feet(p, period_s);
  constexpr double kPi = std::numbers::pi;
  constexpr double kWeight = 1100.0;
  const int lift = static_cast<int>(std::lround(0.6 / period_s)), land = static_cast<int>(std::lround(0.8 / period_s)),
            onset = static_cast<int>(std::lround(0.84 / period_s)), ticks = static_cast<int>(std::lround(0.94 / period_s));
  const double ramp_ticks = 0.05 / period_s;
  int flagged = -1;
  double onset_change = 0.0;  // pad 4's reading's change on the onset tick, but for the step
  for (int k = 0; k < ticks; ++k) {
    const double t = k * period_s;
    // The left foot's share of the weight: half on both feet, none in the air, back over 50 ms.
    const double left_share = k < lift ? 0.5 : k < land ? 0.0 : std::min(0.5, 0.5 * (k - land + 1) / ramp_ticks);
    feet.left_foot_at(k >= lift && k < land ? 0.03 : 0.0);
    const double pitch = 400.0 * std::sin(2 * kPi * 0.8 * t), roll = 150.0 * std::cos(2 * kPi * 0.5 * t);
    double sum = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double share = j < 4 ? left_share : 1.0 - left_share;
      const double x = j % 4 < 2 ? 0.12 : -0.12, y = j % 2 == 0 ? 0.075 : -0.075;
      // Each foot's pads on a plane scaled by its share (under 2 N per tick but at the landing).
      const double load = share * (kWeight / 4.0 + pitch * x + roll * y);
      const double wiggle = load > 0.0 ? (k % 2 == 0 ? 0.3 : -0.3) : 0.0;  // no pad repeats itself
      sum += load;
      if (j == 4 && k == onset - 1) onset_change = -(load + wiggle);
      if (j == 4 && k == onset) onset_change += load + wiggle;
      feet.measured[j] = load + wiggle + (j == 4 && k >= onset && (!one_tick || k == onset) ? 80.0 : 0.0);
    }
    feet.step(sum);
    if (flagged < 0 && feet.type(4) != FaultType::none) flagged = k;
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 4) {
        EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
  if (flagged >= 0 && !one_tick) {
    EXPECT_EQ(feet.type(4), FaultType::offset);
    // The jump as read: 80 N plus that tick's load change and the wiggle's flip (at 1 kHz under
    // 2.6 N in all).
    EXPECT_NEAR(feet.outs[ContactForceFdi::kFaultEstimate][4], 80.0 + onset_change, 1e-9);
  }
  return flagged;
}

TEST(ContactForceFdi, AStepInsideATouchdownGuardIsConfirmedByItsSolesPlane) {
  const int with_points = offset_flagged_inside_a_touchdown_guard(true);
  const int sum_only = offset_flagged_inside_a_touchdown_guard(false);
  std::printf("offset 40 ms after a touchdown, flagged at tick %d with the soles' layout, %d without (onset 840)\n",
              with_points, sum_only);
  // The window after the step is complete 10 ticks after it (jump_window_s).
  EXPECT_EQ(with_points, 840 + 9);
  EXPECT_EQ(sum_only, -1);
  // At 200 Hz the window is 2 ticks: the step is flagged on tick 168 + 1.
  EXPECT_EQ(offset_flagged_inside_a_touchdown_guard(true, 5e-3), 168 + 1);
}

// The trace of offset_flagged_inside_a_touchdown_guard (soles' layout given, 1 kHz), but each
// reading carries the sensors' white noise (2 N, as told; seed 7, a fixed std::mt19937), and on
// the onset tick, 40 ms after the left foot's touchdown, the right foot's pads (4-7) step by
// `load_steps` (their loads: the readings and the total force alike) and their readings further
// by `sensor_steps` (sensor faults). Returns the channels flagged by the trace's end (0.94 s).
std::vector<std::size_t> flagged_after_right_pads_step(std::array<double, 4> load_steps,
                                                       std::array<double, 4> sensor_steps) {
  auto p = suralp();
  p.points = kSuralpSole;
  Feet feet(p, 1e-3);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, p.noise_std_N);
  constexpr double kPi = std::numbers::pi;
  constexpr double kWeight = 1100.0;
  for (int k = 0; k < 940; ++k) {
    const double t = k * 1e-3;
    const double left_share = k < 600 ? 0.5 : k < 800 ? 0.0 : std::min(0.5, 0.5 * (k - 800 + 1) / 50.0);
    feet.left_foot_at(k >= 600 && k < 800 ? 0.03 : 0.0);
    const double pitch = 400.0 * std::sin(2 * kPi * 0.8 * t), roll = 150.0 * std::cos(2 * kPi * 0.5 * t);
    double sum = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double share = j < 4 ? left_share : 1.0 - left_share;
      const double x = j % 4 < 2 ? 0.12 : -0.12, y = j % 2 == 0 ? 0.075 : -0.075;
      double load = share * (kWeight / 4.0 + pitch * x + roll * y);
      if (j >= 4 && k >= 840) load += load_steps[j - 4];
      sum += load;
      feet.measured[j] = load + noise(rng) + (j >= 4 && k >= 840 ? sensor_steps[j - 4] : 0.0);
    }
    feet.step(sum);
  }
  std::vector<std::size_t> flagged;
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (feet.type(j) != FaultType::none) flagged.push_back(j);
  }
  return flagged;
}

TEST(ContactForceFdi, PadsThatFallAsOneInsideAGuardAreNotNamedByAPlaneOneOfThemExplains) {
  // Three pads' loads fall by 40 N on one tick, the plane x0 - x1 - x2 + x3 departing by +40 N:
  // what pad 5's or pad 6's fall alone implies, as well as all three's. One relation cannot tell
  // which stepped (a lifting sole whose pad nears its zero load departs so): none is named.
  // Before this rule the three were raised as offsets together.
  EXPECT_EQ(flagged_after_right_pads_step({-40.0, -40.0, -40.0, 0.0}, {}), std::vector<std::size_t>{});
  // Two sensors stepping +40 N together on a diagonal (x0 and x3: +80 N on the plane, twice what
  // either alone implies) are still named together, and one alone as before.
  EXPECT_EQ(flagged_after_right_pads_step({}, {40.0, 0.0, 0.0, 40.0}), (std::vector<std::size_t>{4, 7}));
  // Two unequal ones (+60 N and +25 N: the +60 N alone leaves 25 N of the plane's step, beyond
  // its noise) are named too. (A member that "explained" the step within the group test's 50 %
  // allowance, as a first version let it, named neither on this trace without its noise, in a
  // review's probe: there the noise bar is near 0 and the allowance decided.)
  EXPECT_EQ(flagged_after_right_pads_step({}, {60.0, 0.0, 0.0, 25.0}), (std::vector<std::size_t>{4, 7}));
  EXPECT_EQ(flagged_after_right_pads_step({}, {0.0, 0.0, 40.0, 0.0}), std::vector<std::size_t>{6});
}

// r_foot/p1 (channel 4) clips at 500 N. The trace (1 kHz, the soles' layout, 2 N of noise, seed
// 7, 2200 N of weight) first makes that ceiling known: the left foot swings (0.3-0.5 s; its load
// handed over in the 50 ms before it lifts and taken back in the 50 ms after it lands) and the
// right pads carry 550 N each, so channel 4 sits on 500 N for 0.2 s and is flagged; it is
// re-admitted once its load falls below. Before and in the left foot's second swing (0.95-1.2 s)
// a moment keeps channel 4 under its ceiling (the right foot's loads a + m s_j,
// s = (+1, 0, 0, -1): a diagonal moment, on the sole's plane; channel 4 at 470 N in the swing).
// The left foot lands at 1.2 s; inside that landing's guard channel 4's load rises to 493 N by
// tick 1221, then by 5.75 N a tick to 540 N on tick 1229, held to tick 1239: it reads 500 N from
// about tick 1223, some 17 ticks, short of the 20 the repeat test needs (40 N unread at the end).
// On tick 1240 the sole's load moves on (channels 4 and 5 lose 46 and 40 N, channel 7 takes 6 N:
// on the plane; the total force with them; the landing's ramp goes on, 5.5 N a tick off every
// right pad). Channel 4 leaves its ceiling by about 11.5 N as read, under the jump threshold
// (20 N), channel 5 steps by 45.5 N, and the plane as read steps by about half the 40 N channel 4
// hid: what channel 5's step alone implies (before the rule, channel 5 was raised as an offset).
// Returns the channels other than 4 flagged on any tick; whether channel 4 was flagged frozen or
// saturated at the end of the first swing, and healthy again at 1.0 s.
struct ClipAtLandingResult {
  std::vector<std::size_t> neighbours_flagged;
  bool ceiling_learnt = false;
  bool readmitted = false;
};
ClipAtLandingResult clip_ends_as_its_foot_unloads() {
  auto p = suralp();
  p.points = kSuralpSole;
  Feet feet(p, 1e-3);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, p.noise_std_N);
  constexpr double kCeiling = 500.0, kShare = 275.0;
  const std::array<double, 4> moment_sign = {1.0, 0.0, 0.0, -1.0};
  ClipAtLandingResult result;
  std::vector<char> flagged(kChannels, 0);
  double m_held = 0.0;
  for (int k = 0; k < 1440; ++k) {
    const bool swing = (k >= 300 && k < 500) || (k >= 1000 && k < 1200);
    feet.left_foot_at(swing ? 0.03 : 0.0);
    // The right foot's mean pad load: all the weight in a swing, half after a 50 ms landing ramp.
    double a_right = kShare;
    if (swing) a_right = 2.0 * kShare;
    if ((k >= 250 && k < 300) || (k >= 950 && k < 1000)) a_right = kShare + kShare * ((k % 50) + 1) / 50.0;
    if (k >= 500 && k < 550) a_right = 2.0 * kShare - kShare * (k - 500 + 1) / 50.0;
    if (k >= 1200 && k < 1250) a_right = 2.0 * kShare - kShare * (k - 1200 + 1) / 50.0;
    const double a_left = 2.0 * kShare - a_right;
    // Channel 4's load in the second stride (the moment is what it takes): 80 N under the foot's
    // mean as the left foot lifts, 470 N in the swing, then as in the comment above.
    double pad4 = a_right;
    if (k >= 950 && k < 1000) pad4 = a_right - 80.0 * (k - 950 + 1) / 50.0;  // the moment comes in
    if (k >= 1000 && k < 1200) pad4 = 470.0;
    if (k >= 1200 && k < 1222) pad4 = 470.0 + 24.0 * (k - 1200) / 22.0;
    if (k >= 1222 && k < 1230) pad4 = 494.0 + 5.75 * (k - 1221);
    if (k >= 1230 && k < 1240) pad4 = kCeiling + 40.0;
    double m = pad4 - a_right;
    if (k == 1239) m_held = m;
    if (k >= 1240) m = m_held;
    // The sole's load moving on: pads 4 and 5 lose 46 and 40 N, pad 7 takes 6 N (on the plane:
    // the diagonals' sums change alike), and the total force with them.
    const std::array<double, 4> step_N = {-46.0, -40.0, 0.0, 6.0};
    double sum = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = j < 4 ? (swing ? 0.0 : a_left) : a_right + m * moment_sign[j - 4] + (k >= 1240 ? step_N[j - 4] : 0.0);
      sum += load;
      const double reading = load + noise(rng);
      feet.measured[j] = j == 4 ? std::min(reading, kCeiling) : reading;
    }
    feet.step(sum);
    if (k == 499) result.ceiling_learnt = feet.type(4) == FaultType::saturation || feet.type(4) == FaultType::frozen;
    if (k == 999) result.readmitted = feet.type(4) == FaultType::none;
    for (std::size_t j = 0; j < kChannels; ++j) flagged[j] = flagged[j] || (j != 4 && feet.type(j) != FaultType::none);
  }
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (flagged[j] != 0) result.neighbours_flagged.push_back(j);
  }
  return result;
}

TEST(ContactForceFdi, AClipThatEndsAsItsFootUnloadsNamesNoNeighbour) {
  const ClipAtLandingResult r = clip_ends_as_its_foot_unloads();
  EXPECT_TRUE(r.ceiling_learnt);
  EXPECT_TRUE(r.readmitted);
  EXPECT_EQ(r.neighbours_flagged, std::vector<std::size_t>{});
}

TEST(ContactForceFdi, AOneTickSpikeInsideATouchdownGuardIsNoStepOfItsSolesPlane) {
  // The same +80 N, back on the next tick, at 200 Hz: the plane relation's 2-tick mean moves by
  // half of it, within 50 % of what the jump implies; but the reading is back, so it leaves its
  // foot's group, and inside the guard (where spikes are not looked for) it is not flagged.
  EXPECT_EQ(offset_flagged_inside_a_touchdown_guard(true, 5e-3, true), -1);
}

// The trace above, with the right foot rolled onto its toes (its heel pads carry nothing, so its
// plane cannot judge: the foot is not in full contact), and the left foot landing `landings`
// times, 0.4 s apart from 0.5 s (each swing 0.1 s): r_foot/p1 steps by +80 N 40 ms after the last
// landing, and the trace ends 0.2 s after it, past the guard. With `fz_error_N` e, the total
// force is off by -e, then +e, switching at each landing (its error moving across a guard). With
// `neighbour_N`, r_foot/p2 takes that much more load on the onset tick, as does the total force
// (a healthy step beside the faulty one). With `fault_N` 0, r_foot/p1's step is load (+50 N, the
// total force with it) and, with `left_fault_N`, l_foot/p1 (its foot in full contact) reads that
// much more from 30 ms after the last landing. Returns the tick r_foot/p1 is flagged (-1: not by
// the end); no other channel may be flagged but l_foot/p1 by its own offset.
struct GuardCase {
  double period_s = 1e-3;
  int landings = 6;
  double fz_error_N = 0.0;
  double neighbour_N = 0.0;
  double fault_N = 80.0;
  double left_fault_N = 0.0;
  bool toe_off_unseen = false;  // r_foot/p2 rolls off on the onset tick (no fault, no p1 step),
                                // and the total force keeps its load (an error of the reference)
  bool noisy_left_pad = false;  // l_foot/p2 reads a noise burst (+-40 N a tick) from 0.2 s
                                // before the last landing
  bool toe_off_seen = false;    // r_foot/p2 rolls off on the onset tick, the total force with it
  double onset_after_landing_s = 0.04;
  std::size_t watched = 4;  // the channel whose first flag's tick is returned
  double relanding_after_s = 0.0;  // > 0: the left foot's kinematics lift it 5 ms before this
                                   // long after the last landing and land it again (its loads as
                                   // they were: a glitch the pads do not feel), and the trace
                                   // runs 0.4 s past the last landing
};
int offset_in_a_guard_off_full_contact_flagged_at(const GuardCase& g) {
  auto p = suralp();
  p.points = kSuralpSole;
  const double period_s = g.period_s;
  Feet feet(p, period_s);
  constexpr double kPi = std::numbers::pi;
  constexpr double kWeight = 1100.0;
  const auto tick = [&](double s) { return static_cast<int>(std::lround(s / period_s)); };
  const int last_land = tick(0.5 + 0.4 * (g.landings - 1));
  const int onset = last_land + tick(g.onset_after_landing_s);
  const int ticks = last_land + tick(g.relanding_after_s > 0.0 ? 0.4 : 0.25);
  const int relanding = g.relanding_after_s > 0.0 ? last_land + tick(g.relanding_after_s) : -1;
  const double ramp_ticks = 0.05 / period_s;
  int flagged = -1;
  double onset_change = 0.0;  // pad 4's reading's change on the onset tick, but for the step
  for (int k = 0; k < ticks; ++k) {
    const double t = k * period_s;
    // The left foot's share: half, none in its swings, back over 50 ms after each landing.
    double left_share = 0.5;
    int landed = 0;
    bool swinging = false;
    for (int i = 0; i < g.landings; ++i) {
      const int land = tick(0.5 + 0.4 * i), lift = land - tick(0.1);
      swinging = swinging || (k >= lift && k < land);
      if (k >= land) {
        ++landed;
        left_share = std::min(0.5, 0.5 * (k - land + 1) / ramp_ticks);
      }
    }
    if (swinging) left_share = 0.0;
    feet.left_foot_at(swinging || (k >= relanding - tick(0.005) && k < relanding) ? 0.03 : 0.0);
    const double pitch = 400.0 * std::sin(2 * kPi * 0.8 * t), roll = 150.0 * std::cos(2 * kPi * 0.5 * t);
    double sum = 0.0, unseen_N = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double share = j < 4 ? left_share : 1.0 - left_share;
      const double x = j % 4 < 2 ? 0.12 : -0.12, y = j % 2 == 0 ? 0.075 : -0.075;
      const bool heel_off = j >= 4 && x < 0.0;  // the right foot on its toes
      double load = heel_off ? 0.0 : share * (kWeight / 4.0 + pitch * x + roll * y);
      if (j == 5 && k >= onset) load += g.neighbour_N;
      if (j == 4 && k >= onset && g.fault_N == 0.0 && !g.toe_off_unseen) load += 50.0;
      if (j == 5 && k >= onset && g.toe_off_seen) load = 0.0;
      if (j == 5 && k >= onset && g.toe_off_unseen) {
        unseen_N = load;
        load = 0.0;
      }
      const double wiggle = k % 2 == 0 ? 0.3 : -0.3;  // every pad's noise, unloaded too
      sum += load;
      if (j == 4 && k == onset - 1) onset_change = -(load + wiggle);
      if (j == 4 && k == onset) onset_change += load + wiggle;
      feet.measured[j] = load + wiggle + (j == 4 && k >= onset ? g.fault_N : 0.0) +
                         (j == 0 && k >= last_land + tick(0.03) ? g.left_fault_N : 0.0) +
                         (j == 1 && g.noisy_left_pad && k >= last_land - tick(0.2) ? (k % 2 == 0 ? 40.0 : -40.0) : 0.0);
    }
    feet.step(sum + unseen_N + (landed % 2 == 0 ? -g.fz_error_N : g.fz_error_N));
    if (flagged < 0 && feet.type(g.watched) != FaultType::none) flagged = k;
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != g.watched && !(j == 0 && g.left_fault_N != 0.0) && !(j == 1 && g.noisy_left_pad)) {
        EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
  if (g.left_fault_N != 0.0) {
    EXPECT_EQ(feet.type(0), FaultType::offset);
  }
  if (g.noisy_left_pad) {
    EXPECT_EQ(feet.type(1), FaultType::noise);
  }
  if (flagged >= 0 && g.watched == 4) {
    EXPECT_EQ(feet.type(4), FaultType::offset);
    EXPECT_NEAR(feet.outs[ContactForceFdi::kFaultEstimate][4], 80.0 + onset_change, 1e-9);
  }
  return flagged;
}

// The first tick whose time, accumulated as Feet::step does, lies touchdown_guard_s (0.15 s) or
// more after that of tick `land`: the first tick past that landing's guard.
int first_tick_past_guard(double period_s, int land) {
  double t = 0.0, landed_at = 0.0;
  for (int k = 0;; ++k, t += period_s) {
    if (k == land) landed_at = t;
    if (k > land && !(t - landed_at < 0.15)) return k;
  }
}

TEST(ContactForceFdi, AStepInsideATouchdownGuardThatItsSolesPlaneCannotJudgeIsConfirmedByTheSumOnceTheGuardIsOver) {
  // The last landing is on tick 2500; its guard ends 150 ms later (tick 2650, or 2651 as the
  // harness's time accumulates); the residual, +80 N from its mean before the guard, has settled
  // a jump window (10 ticks) later: flagged on its 10th tick. Five healthy landings before it measured the residual's step across a guard: 0 here, so
  // the bar is the jump test's confirmation step. Before, the plane dropped the step and the
  // offset went unseen to the foot's lift.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({}), first_tick_past_guard(1e-3, 2500) + 9);
  // At 200 Hz: the last landing on tick 500, the guard ends 30 ticks later, the window is 2 ticks.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.period_s = 5e-3}), first_tick_past_guard(5e-3, 500) + 1);
}

TEST(ContactForceFdi, AStepInsideAGuardIsJudgedOnlyOnceFiveLandingsHaveShownWhatALandingDoesToTheResidual) {
  // Four landings before it: the residual's own step across a guard is not known yet.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.landings = 5}), -1);
  // The total force off by -10 N, then +10 N, switching at each landing: the residual steps by
  // 20 N across every guard, so a guard's step must exceed z (for one decision per landing,
  // a guard apart, at one false alarm per 86400 s: 4.78) times 20 N: the 80 N step does not.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.fz_error_N = 10.0}), -1);
  // 2 N of such error (steps of 4 N, a bar of 20 N, under the 25 N confirmation step): found.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.fz_error_N = 2.0}), first_tick_past_guard(1e-3, 2500) + 9);
}

TEST(ContactForceFdi, TwoPadsOfAFootSteppingOnOneTickInsideAGuardCannotBeToldApartByTheSum) {
  // r_foot/p2 takes 40 N more load on the onset tick (the total force with it): the residual
  // steps by p1's +80 N, which the group's net step (+120 N) matches within half as well. One
  // residual step, two pads that stepped: neither is blamed (judged alone, p1 would be).
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.neighbour_N = 40.0}), -1);
}

TEST(ContactForceFdi, APadRollingOffInsideAGuardIsItsContactGoingNotAnOnsetTheSumJudges) {
  // r_foot/p2 steps from its load to 0 on the onset tick while the total force keeps that load:
  // the residual steps by the pad's step. A step to the zero level is a contact going (a sole
  // rolling off the pad), which the reference may miss: not judged as an onset (judged, the
  // pad would be raised with an offset of minus its load).
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.fault_N = 0.0, .toe_off_unseen = true, .watched = 5}), -1);
}

TEST(ContactForceFdi, AStepLateInAGuardIsJudgedAfterItAndDoesNotRaiseTheBarItIsJudgedAgainst) {
  // The step 145 ms after the landing, 5 ms before the guard ends: its plane group is decided a
  // jump window after it (tick 2654), after the guard, and it is judged a jump window later
  // (2664). The guard's own step, +80 N, was measured before that judgment (a jump window after
  // the guard): it counts clipped at the bar (25 N), not as 80 N, which would have set the bar
  // to 4.78 x 32.7 N = 156 N and hidden the fault.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.onset_after_landing_s = 0.145}), 2645 + 9 + 10);
}

TEST(ContactForceFdi, AStepBesideAPadRollingOffOnTheSameTickCannotBePinnedByTheSum) {
  // r_foot/p2 rolls off (to 0, the total force with it) on the tick r_foot/p1 steps by +80 N:
  // the residual steps by p1's 80 N, but the foot's plane group holds two pads, and a step to 0
  // is no candidate of its own (a contact going): the residual's step cannot be pinned on p1.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.toe_off_seen = true}), -1);
}

TEST(ContactForceFdi, AStepInsideAGuardIsNotJudgedByTheSumWhileANoiseBurstIsInIt) {
  // l_foot/p2 reads a noise burst (flagged as such) through the last landing: its swings are in
  // the residual, whose step across a guard was learnt with no channel flagged. The +80 N step
  // is not judged by the sum then (it is with the burst left out: the first test).
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.noisy_left_pad = true}), -1);
}

TEST(ContactForceFdi, AStepInsideAGuardIsNotJudgedOnAResidualThatAFlagRaisedSinceHasMoved) {
  // r_foot/p1's step is load (+50 N, the total force with it), and l_foot/p1, on the landed foot
  // in full contact, reads +50 N more from 30 ms after the landing: its plane raises that offset
  // inside the guard, and the residual, which takes an offset as read, steps by +50 N across the
  // guard. That step is l_foot/p1's, not r_foot/p1's: a flag raised since the guard began voids
  // the judgment.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.fault_N = 0.0, .left_fault_N = 50.0}), -1);
}

TEST(ContactForceFdi, AStepInsideAGuardStillUnjudgedWhenTheNextGuardBeginsIsDropped) {
  // The left foot lands again 155 ms after the last landing, 4 ms after that guard's last tick and 5 ms
  // before the +80 N step would have been judged (tick 2660): the step is dropped unjudged, not
  // judged after the second guard against a landing's bar learnt on one guard at a time (that
  // would flag it at tick 2655 + 150 + 10).
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.relanding_after_s = 0.155}), -1);
  // Landing again 165 ms after (the step judged 5 ms before): flagged as without the glitch.
  EXPECT_EQ(offset_in_a_guard_off_full_contact_flagged_at({.relanding_after_s = 0.165}),
            first_tick_past_guard(1e-3, 2500) + 9);
}

}  // namespace
}  // namespace ftsense::biped

namespace ftsense::biped {
namespace {

// The quadruped of the test above: its left front foot swings from tick 100 to 250 reading +20 N
// from its lift (an offset, measured in the air), then its right front foot swings from tick 300
// and lands on tick 550. At tick 600, inside that landing's touchdown guard (150 ticks), the left
// front reading steps back by 20 N: either the offset ends (the total force stays: the sum
// residual steps by -20 N), or, when `load_shift`, the foot hands 20 N of load to its landed
// neighbour in that tick (the reading was right to step: the residual stays). Returns the tick
// the offset is dropped (-1: kept to tick 900).
// With `both`, the left hind foot swings too (ticks 120 to 240) reading +20 N from its lift, an
// offset that stays; at tick 600 it hands 20 N of its load to the landed right front foot, so its
// reading steps back by its offset's size while its fault goes on: `other_dropped_at` says when it
// was dropped (-1: never).
int quadruped_offset_dropped_at(bool load_shift, bool both = false, int* other_dropped_at = nullptr) {
  ContactForceFdi::Params p;
  p.points_per_foot = 1;
  p.noise_std_N = 0.5;
  p.weight_N = 130.0;
  ContactForceFdi fdi(p, StageContext(1e-3, "fdi", {{"measured", 4}}));
  std::vector<std::vector<double>> outs;
  for (const auto& port : fdi.ports().outputs()) outs.emplace_back(port.dim, 0.0);
  fdi.reset();
  std::vector<double> measured(4), total{0.0, 0.0, 130.0};
  std::vector<double> height(4, 0.0);
  const int lift[4] = {100, 300, both ? 120 : 100000, 100000}, land[4] = {250, 550, both ? 240 : 100000, 100000};
  const int end = 600;
  int dropped_at = -1;
  if (other_dropped_at != nullptr) *other_dropped_at = -1;
  for (int k = 0; k < 900; ++k) {
    const double wiggle = k % 2 == 0 ? 0.3 : -0.3;
    // A swinging foot's load leaves over the 50 ticks before it lifts and returns over the 50
    // after it lands; the 130 N are shared in proportion by the feet that carry.
    double share[4], carried = 0.0;
    for (std::size_t j = 0; j < 4; ++j) {
      height[j] = k >= lift[j] && k < land[j] ? 0.03 : 0.0;
      share[j] = std::clamp(std::max(lift[j] - k, k - land[j] + 1) / 50.0, 0.0, 1.0);
      carried += share[j];
    }
    double loads[4];
    for (std::size_t j = 0; j < 4; ++j) loads[j] = 130.0 * share[j] / carried;
    if (load_shift && k >= end) {
      loads[0] -= 20.0;
      loads[1] += 20.0;
    }
    if (both && k >= end) {
      loads[2] -= 20.0;
      loads[1] += 20.0;
    }
    for (std::size_t j = 0; j < 4; ++j) measured[j] = loads[j] + wiggle * (j % 2 == 0 ? 1.0 : -1.0);
    if (k >= lift[0] && (load_shift || k < end)) measured[0] += 20.0;
    if (both && k >= lift[2]) measured[2] += 20.0;
    const std::span<const double> ins[] = {measured, total, height};
    std::vector<std::span<double>> out_spans(outs.begin(), outs.end());
    fdi.step(StepIO{k * 1e-3, ins, out_spans});
    const auto type = [&](std::size_t j) {
      return fault_type_from_code(outs[ContactForceFdi::kFaultType][j]).value_or(FaultType::unclassified);
    };
    if (k == end - 1) {
      EXPECT_EQ(type(0), FaultType::offset) << "load_shift " << load_shift;
      EXPECT_NEAR(outs[ContactForceFdi::kFaultEstimate][0], 20.0, 0.1);
      if (both) {
        EXPECT_EQ(type(2), FaultType::offset);
      }
    }
    if (k >= end && dropped_at < 0 && type(0) == FaultType::none) dropped_at = k;
    if (both && k >= end && *other_dropped_at < 0 && type(2) == FaultType::none) *other_dropped_at = k;
  }
  return dropped_at;
}

TEST(ContactForceFdi, AnOffsetThatEndsInsideAnotherFootsTouchdownGuardIsDroppedOnceTheGuardIsOver) {
  // The step back is seen at once but judged by the sum residual after the guard (tick 700) and
  // a jump window (10 ticks) to settle: dropped on tick 709. Before, it was kept until the foot
  // lifted (here: never).
  EXPECT_EQ(quadruped_offset_dropped_at(false), 550 + 150 + 9);
  // The same step with the load handed to the neighbour leaves the residual alone: kept.
  EXPECT_EQ(quadruped_offset_dropped_at(true), -1);
  // An end and, on the same tick, a flagged foot handing over load by its offset's size: the
  // residual steps by one offset, which matches each alone. Judged one by one, the foot whose
  // fault goes on would be dropped; with two pending, neither is (left to the air test).
  int other = 0;
  EXPECT_EQ(quadruped_offset_dropped_at(false, true, &other), -1);
  EXPECT_EQ(other, -1);
}

}  // namespace
}  // namespace ftsense::biped

namespace ftsense::biped {
namespace {

// Pad 0 reads +60 N from tick 100 (raised as an offset). At tick 400 two pads of the other foot
// take 30 N more each, as does the total force (a load the trunk sees: their group is not
// confirmed, and it is pending for a jump window). At tick 405, inside that window, pad 0 steps
// back by 60 N: the offset ends. Returns the tick it is dropped (-1: kept to tick 700).
int offset_end_during_a_pending_group_dropped_at() {
  Feet feet(suralp(), 1e-3);
  int dropped_at = -1;
  for (int k = 0; k < 700; ++k) {
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = moving(j, k, 0.0) + (k >= 400 && (j == 4 || j == 5) ? 30.0 : 0.0);
      truth += feet.measured[j];
    }
    if (k >= 100 && k < 405) feet.measured[0] += 60.0;
    feet.step(truth);
    if (k == 404) {
      EXPECT_EQ(feet.type(0), FaultType::offset);
    }
    for (std::size_t j = 1; j < kChannels; ++j) EXPECT_EQ(feet.type(j), FaultType::none) << "pad " << j << ", tick " << k;
    if (k >= 405 && dropped_at < 0 && feet.type(0) == FaultType::none) dropped_at = k;
  }
  return dropped_at;
}

TEST(ContactForceFdi, AnOffsetThatEndsWhileAnotherGroupIsPendingIsJudgedOnItsOwnWindow) {
  // Judged as a group of its own a jump window after its step: 405 + 9. Before, a step during a
  // pending group was no candidate, and the offset was held.
  EXPECT_EQ(offset_end_during_a_pending_group_dropped_at(), 405 + 9);
}

// Two steps within one jump window (1 kHz, 10 ticks): pads 4 and 5 (or `first_pads`) step up by
// 30 N each at tick 400, pad 0 steps down by 100 N at tick 403; `first_is_fault` / `late_is_fault`
// say whether the total force leaves each step out (a sensor's fault) or carries it (the load
// moved). Returns the tick each pad was first flagged (-1: never).
std::vector<int> steps_within_one_window_flagged_at(bool first_is_fault, bool late_is_fault,
                                                    std::array<std::size_t, 2> first_pads = {4, 5}) {
  Feet feet(suralp(), 1e-3);
  std::vector<int> first(kChannels, -1);
  for (int k = 0; k < 600; ++k) {
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = moving(j, k, 0.0);
      truth += feet.measured[j];
    }
    if (k >= 400) {
      for (std::size_t j : first_pads) feet.measured[j] += 30.0;
      if (!first_is_fault) truth += 60.0;
    }
    if (k >= 403) {
      feet.measured[0] -= 100.0;
      if (!late_is_fault) truth -= 100.0;
    }
    feet.step(truth);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (first[j] < 0 && feet.type(j) != FaultType::none) first[j] = k;
    }
  }
  return first;
}

TEST(ContactForceFdi, AFaultStartingWhileAnotherGroupIsPendingIsFoundWhenBothAreDecided) {
  // The late group (pad 0) is decided with the first a jump window after its own jump, 403 + 9,
  // by the hypothesis nearest the residual's step from before tick 400: the late sum (-100 N),
  // the first's (+60 N), or both (-40 N). Before, a healthy pad's step while a group was pending
  // joined no group, and pad 0's fault under a steady load went unseen.
  const std::vector<int> healthy_then_fault = steps_within_one_window_flagged_at(false, true);
  EXPECT_EQ(healthy_then_fault, (std::vector<int>{412, -1, -1, -1, -1, -1, -1, -1}));
  const std::vector<int> fault_then_healthy = steps_within_one_window_flagged_at(true, false);
  EXPECT_EQ(fault_then_healthy, (std::vector<int>{-1, -1, -1, -1, 412, 412, -1, -1}));
  const std::vector<int> both_faults = steps_within_one_window_flagged_at(true, true);
  EXPECT_EQ(both_faults, (std::vector<int>{412, -1, -1, -1, 412, 412, -1, -1}));
  // A pad of the first group that steps again (its load kept moving, then its sensor failed).
  const std::vector<int> member_then_fault = steps_within_one_window_flagged_at(false, true, {0, 5});
  EXPECT_EQ(member_then_fault, (std::vector<int>{412, -1, -1, -1, -1, -1, -1, -1}));
}

TEST(ContactForceFdi, TwoGroupsEachUnderTheConfirmationStepAreNotConfirmedTogether) {
  // Pad 4 steps +23 N at tick 400 and pad 0 +23 N at tick 403, neither in the total force: each
  // jumps beyond jump_threshold_N (20 N; with the 1 N alternation, by 22 and 24 N) but under
  // jump_confirm_N (25 N), so neither is confirmed, even though the residual steps by their sum. (A heel chattering beside a
  // clipped pad moved a pad by 38 N, its neighbour by 29 N, and the residual drifted with the
  // clipped load: the two were confirmed together as an offset of the chattering heel.)
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 600; ++k) {
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = moving(j, k, 0.0);
      truth += feet.measured[j];
    }
    if (k >= 400) feet.measured[4] += 23.0;
    if (k >= 403) feet.measured[0] += 23.0;
    feet.step(truth);
    for (std::size_t j = 0; j < kChannels; ++j) {
      ASSERT_EQ(feet.type(j), FaultType::none) << "pad " << j << ", tick " << k;
    }
  }
}

TEST(ContactForceFdi, ASpikesReturnIsNoLateGroupAndAFaultJustAfterItIsFound) {
  // Pad 2 spikes by 100 N for tick 400 (a group, emptied on tick 401 when it is back); pad 0
  // steps by -100 N at tick 403 (a fault). The spike's return is no step of its own: no late
  // group holds the jump test, and pad 0 forms a group of its own, confirmed on 403 + 9.
  Feet feet(suralp(), 1e-3);
  int pad0_flagged = -1;
  for (int k = 0; k < 600; ++k) {
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = moving(j, k, 0.0);
      truth += feet.measured[j];
    }
    if (k == 400) feet.measured[2] += 100.0;
    if (k >= 403) feet.measured[0] -= 100.0;
    feet.step(truth);
    if (pad0_flagged < 0 && feet.type(0) != FaultType::none) pad0_flagged = k;
  }
  EXPECT_EQ(pad0_flagged, 403 + 9);
}

TEST(ContactForceFdi, AFlaggedMemberOfAPendingGroupThatStepsBackIsReadmittedWithTheLateGroup) {
  // Pad 0 reads +60 N from tick 100 (flagged an offset on tick 109). At tick 400 its load and pad
  // 4's rise by 30 N each (a pending group, healthy: the total force carries them); at tick 403 its
  // offset ends. The step back joins the late group, decided on tick 403 + 9 by the residual's
  // -60 N step: re-admitted. Before, a member's own step joined neither the end test nor a group,
  // and the offset was held.
  Feet feet(suralp(), 1e-3);
  int readmitted = -1;
  for (int k = 0; k < 600; ++k) {
    double truth = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = moving(j, k, 0.0) + (k >= 400 && (j == 0 || j == 4) ? 30.0 : 0.0);
      truth += feet.measured[j];
    }
    if (k >= 100 && k < 403) feet.measured[0] += 60.0;
    feet.step(truth);
    if (k == 399) {
      EXPECT_EQ(feet.type(0), FaultType::offset);
    }
    for (std::size_t j = 1; j < kChannels; ++j) EXPECT_EQ(feet.type(j), FaultType::none) << "pad " << j << ", tick " << k;
    if (k >= 400 && readmitted < 0 && feet.type(0) == FaultType::none) readmitted = k;
  }
  EXPECT_EQ(readmitted, 403 + 9);
}

// The still-reading test: eight loaded pads at 1 kHz, each healthy load 200 + 10 j + 40 sin(2 pi t +
// j) N (its 10 Hz low-pass spans more than a quarter of 80 N within the window), read with a +-1 N
// alternation (a live sensor's noise, never a step). `still` pads carry a steady 150 N instead;
// from tick 500 the first of them is stuck at that reading while its load falls at 400 N/s
// (`load_falls`), and the total force is their true sum plus `reference_error` N/s from then on.
struct StillReadingTrace {
  std::vector<std::size_t> still;
  bool load_falls = true;
  double reference_error_N_s = 0.0;
  double still_load_N = 150.0;  // the first still pad's load before it falls, and its stuck reading (the others: 150 N)
  double floor_N = -1e9;        // the falling load stops there
};
constexpr int kStillFrom = 500;

double true_load(const StillReadingTrace& trace, std::size_t j, int k) {
  const double t = k * 1e-3;
  const bool is_still = std::find(trace.still.begin(), trace.still.end(), j) != trace.still.end();
  if (!is_still) return 200.0 + 10.0 * static_cast<double>(j) + 40.0 * std::sin(2.0 * std::numbers::pi * t + static_cast<double>(j));
  if (trace.load_falls && j == trace.still.front() && k >= kStillFrom) {
    return std::max(trace.floor_N, trace.still_load_N - 400.0 * (k - kStillFrom) * 1e-3);
  }
  return j == trace.still.front() ? trace.still_load_N : 150.0;
}

// Runs the trace for `ticks`; returns the tick each channel was first flagged (-1: never).
std::vector<int> first_flags(const StillReadingTrace& trace, int ticks, std::vector<double>* cannot_judge_at_end = nullptr) {
  Feet feet(suralp(), 1e-3);
  std::vector<int> first(kChannels, -1);
  for (int k = 0; k < ticks; ++k) {
    double fz = std::max(0, k - kStillFrom) * 1e-3 * trace.reference_error_N_s;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const bool is_still = std::find(trace.still.begin(), trace.still.end(), j) != trace.still.end();
      const double load = true_load(trace, j, k);
      fz += load;
      const bool stuck = is_still && j == trace.still.front();
      feet.measured[j] = (stuck ? trace.still_load_N : is_still ? 150.0 : load) + (k % 2 == 0 ? 1.0 : -1.0);
    }
    feet.step(fz);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (first[j] < 0 && feet.outs[ContactForceFdi::kFault][j] != 0.0) first[j] = k;
    }
  }
  if (cannot_judge_at_end != nullptr) *cannot_judge_at_end = feet.outs[ContactForceFdi::kCannotJudge];
  return first;
}

// The oracle of the header: the residual sum(N) - F_z low-passed at 10 Hz (a = 1 - e^(-2 pi 10 T))
// from tick 0, where the window starts; the first tick its range reaches sum_threshold_N (80 N)
// once the window is as long as the smoother's settling (five time constants, 0.0796 s). The flag
// shows from the next tick: that tick's residual is known once its outputs are.
int residual_moves_beyond_its_bound_at(const StillReadingTrace& trace, int ticks) {
  const double a = -std::expm1(-2.0 * std::numbers::pi * 10.0 * 1e-3);
  double smoothed = 0.0, lo = 0.0, hi = 0.0;
  for (int k = 0; k < ticks; ++k) {
    const double residual =
        (trace.still_load_N - true_load(trace, trace.still.front(), k)) -
        std::max(0, k - kStillFrom) * 1e-3 * trace.reference_error_N_s;
    smoothed = k == 0 ? residual : smoothed + a * (residual - smoothed);
    lo = k == 0 ? smoothed : std::min(lo, smoothed);
    hi = k == 0 ? smoothed : std::max(hi, smoothed);
    if (hi - lo >= 80.0 && k * 1e-3 >= 5.0 / (2.0 * std::numbers::pi * 10.0)) return k + 1;
  }
  return -1;
}

TEST(ContactForceFdi, AStillReadingWhoseLoadMovesIsFrozenOnceTheResidualHasMovedBeyondItsBound) {
  // Pad 2 stuck at 150 N (still noisy, so the repeat test never counts) while its load falls: the
  // residual rises 400 N/s; the only still reading among the loaded pads is blamed frozen on the
  // tick the low-passed residual has moved by 80 N, and substituted from the total force.
  const StillReadingTrace trace{{2}, true, 0.0};
  const int expected = residual_moves_beyond_its_bound_at(trace, 900);
  ASSERT_GT(expected, kStillFrom);
  const auto first = first_flags(trace, 900);
  EXPECT_EQ(first[2], expected);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 2) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
}

TEST(ContactForceFdi, TwoStillReadingsAreNotToldApartAndNeitherIsBlamed) {
  // Pad 6 carries a steady load too: either still reading explains the residual, so neither is
  // blamed; the sum residual says it cannot judge the others.
  std::vector<double> cannot_judge;
  const auto first = first_flags({{2, 6}, true, 0.0}, 900, &cannot_judge);
  for (std::size_t j = 0; j < kChannels; ++j) EXPECT_EQ(first[j], -1) << "channel " << j;
  EXPECT_EQ(cannot_judge[0], 1.0);
}

TEST(ContactForceFdi, APadStuckWhereItsLoadCameToZeroIsStillACandidate) {
  // Pad 2 carries 85 N, pad 6 a steady 150 N; from tick 500 pad 2's load falls at 400 N/s to 0 N
  // (tick 712, a foot about to lift) while its output stays at 85 N. When the residual has moved
  // by 80 N, pad 2's leave-one-out force x - r is under 5 N, below the airborne threshold (8 N):
  // were it stuck, it would carry almost nothing, which a pad may. It is a candidate beside the
  // still pad 6, so neither is blamed (taking only pads whose leave-one-out force is above the
  // airborne threshold, pad 6 was blamed alone).
  const StillReadingTrace trace{{2, 6}, true, 0.0, 85.0, 0.0};
  ASSERT_GT(residual_moves_beyond_its_bound_at(trace, 1200), 700);
  const auto first = first_flags(trace, 1200);
  for (std::size_t j = 0; j < kChannels; ++j) EXPECT_EQ(first[j], -1) << "channel " << j;
}

TEST(ContactForceFdi, AReferenceThatDriftsBlamesNoReadingThatFollowsItsLoad) {
  // Every load moves and is read right, but from tick 500 the total force drifts by -400 N/s: the
  // residual moves as it did above, and no reading that moves is blamed.
  const auto first = first_flags({{2}, false, -400.0}, 900);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 2) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
  // Pad 2 (steady 150 N, read right) is still: the residual's move is the reference's, and
  // blaming it is the test's known limit (one still reading is taken as stuck): it is flagged on
  // the same tick as a stuck one would be.
  EXPECT_EQ(first[2], residual_moves_beyond_its_bound_at({{2}, false, -400.0}, 900));
}

// The still-reading test's short windows. Pad 2's load rises from 100 to 300 N over ticks 300-500
// (1000 N/s, read right); from tick 500 its output sticks at 300 N while its load falls at
// 1000 N/s to 0. The other pads ramp at 400 N/s (0, 3, 5, 7 up from 100 N; 1, 4, 6 down from 500 N), so
// in any window a settling long each moves by 32 N, more than a quarter of the residual's move
// when a window is judged. Every reading alternates +-1 N; F_z is the loads' true sum.
double ramping_load(std::size_t j, int k) {
  const double t = k * 1e-3;
  if (j == 2) return k < 300 ? 100.0 : k < 500 ? 100.0 + (k - 300) : std::max(0.0, 300.0 - 1000.0 * (t - 0.5));
  const bool up = j == 0 || j == 3 || j == 5 || j == 7;
  return up ? 100.0 + 400.0 * t : 500.0 - 400.0 * t;
}
double ramping_reading(std::size_t j, int k) {
  return (j == 2 && k >= 500 ? 300.0 : ramping_load(j, k)) + (k % 2 == 0 ? 1.0 : -1.0);
}

// The header's windows, run on that trace: the readings and the residual sum(x) - F_z low-passed
// at 10 Hz; the long window opened on the first tick and again on the tick after each judgment;
// a short one on the first tick and then every half settling less half a tick (39.29 ms: every
// 40 ticks), each replacing the oldest of four. A window is judged on a later tick once it is a
// settling long (79.6 ms) and its residual spans sum_threshold_N (80 N): the candidates are the
// readings spanning under a quarter of that (in a short window: spanning, since r was last within
// a quarter of 80 N of the extreme it moved away from, under that and under twice the stuck band
// b, b = 8 sigma sqrt(a / (2 - a)) = 2.84 N for sigma = 2 N) with x - r above
// -airborne_threshold_N (-8 N); the long window first; a short window names its one candidate
// only if it spans at most b over the whole window. A candidate is on the ground (`airborne(j, k)`
// false) on every tick of its window, and one whose foot touched down (every pad of the foot on the
// ground after a tick with one in the air) within 0.15 s (touchdown_guard_s) is counted but not
// named. Returns the tick that one shows flagged (the tick after its window names it), and the
// channel; -1 if none by `ticks`.
template <class Load, class Reading, class Airborne>
std::pair<int, std::size_t> still_windows_oracle(Load load, Reading reading_of, int ticks, bool short_windows,
                                                 Airborne airborne) {
  const double a = -std::expm1(-2.0 * std::numbers::pi * 10.0 * 1e-3);
  const double settle = 5.0 / (2.0 * std::numbers::pi * 10.0);
  const double band = 8.0 * 2.0 * std::sqrt(a / (2.0 - a));
  struct Window {
    bool active = false;
    int start = 0;
    double lo_r = 0.0, hi_r = 0.0;
    std::array<double, kChannels> lo{}, hi{};
    // Each reading's range since r was last within 20 N of lo_r, and of hi_r.
    std::array<double, kChannels> since_lo_min{}, since_lo_max{}, since_hi_min{}, since_hi_max{};
    std::array<bool, kChannels> grounded{};
  };
  std::array<Window, 5> windows{};  // 0-3 short, 4 long
  std::array<double, kChannels> x{};
  std::array<int, 2> touchdown{-1000000, -1000000};
  double r = 0.0, next_short_s = -1e300;
  int next_slot = 0;
  for (int k = 0; k < ticks; ++k) {
    for (std::size_t f = 0; f < 2; ++f) {
      bool up_now = false, up_before = false;
      for (std::size_t j = 4 * f; j < 4 * f + 4; ++j) {
        up_now = up_now || airborne(j, k);
        up_before = up_before || (k > 0 && airborne(j, k - 1));
      }
      if (up_before && !up_now) touchdown[f] = k;
    }
    double residual = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double reading = reading_of(j, k);
      x[j] = k == 0 ? reading : x[j] + a * (reading - x[j]);
      residual += reading - load(j, k);
    }
    r = k == 0 ? residual : r + a * (residual - r);
    std::array<bool, 5> opened{};
    const auto open = [&](int w) {
      windows[w] = Window{true, k, r, r, x, x, x, x, x, x, {}};
      for (std::size_t j = 0; j < kChannels; ++j) windows[w].grounded[j] = !airborne(j, k);
      opened[w] = true;
    };
    if (!windows[4].active) open(4);
    if (short_windows && k * 1e-3 >= next_short_s) {
      open(next_slot);
      next_slot = (next_slot + 1) % 4;
      next_short_s = k * 1e-3 + 0.5 * settle - 0.5e-3;
    }
    for (int w = 0; w < 5; ++w) {
      if (!windows[w].active || opened[w]) continue;
      windows[w].lo_r = std::min(windows[w].lo_r, r);
      windows[w].hi_r = std::max(windows[w].hi_r, r);
      for (std::size_t j = 0; j < kChannels; ++j) {
        Window& v = windows[w];
        const bool near_lo = r <= v.lo_r + 20.0, near_hi = r >= v.hi_r - 20.0;
        v.since_lo_min[j] = near_lo ? x[j] : std::min(v.since_lo_min[j], x[j]);
        v.since_lo_max[j] = near_lo ? x[j] : std::max(v.since_lo_max[j], x[j]);
        v.since_hi_min[j] = near_hi ? x[j] : std::min(v.since_hi_min[j], x[j]);
        v.since_hi_max[j] = near_hi ? x[j] : std::max(v.since_hi_max[j], x[j]);
      }
      for (std::size_t j = 0; j < kChannels; ++j) {
        windows[w].lo[j] = std::min(windows[w].lo[j], x[j]);
        windows[w].hi[j] = std::max(windows[w].hi[j], x[j]);
        windows[w].grounded[j] = windows[w].grounded[j] && !airborne(j, k);
      }
    }
    for (int w : {4, 0, 1, 2, 3}) {
      Window& window = windows[w];
      const double span = window.hi_r - window.lo_r;
      if (!window.active || opened[w] || span < 80.0 || (k - window.start) * 1e-3 < settle) continue;
      window.active = false;
      const double bar = w == 4 ? 0.25 * span : std::max(0.25 * span, 2.0 * band);
      int candidates = 0;
      std::size_t culprit = 0;
      for (std::size_t j = 0; j < kChannels; ++j) {
        const bool fell = r - window.lo_r < window.hi_r - r;
        const double moved = w == 4 ? window.hi[j] - window.lo[j]
                             : fell ? window.since_hi_max[j] - window.since_hi_min[j]
                                    : window.since_lo_max[j] - window.since_lo_min[j];
        if (window.grounded[j] && moved < bar && x[j] - r > -8.0) {
          ++candidates;
          culprit = j;
        }
      }
      const bool landing = (k - touchdown[culprit / 4]) * 1e-3 < 0.15;
      if (candidates == 1 && !landing && (w == 4 || window.hi[culprit] - window.lo[culprit] <= band)) {
        return {k + 1, culprit};
      }
    }
  }
  return {-1, kChannels};
}
template <class Load, class Reading>
std::pair<int, std::size_t> still_windows_oracle(Load load, Reading reading_of, int ticks, bool short_windows) {
  return still_windows_oracle(load, reading_of, ticks, short_windows, [](std::size_t, int) { return false; });
}

// The detector on such a trace (F_z the loads' true sum): the tick each channel was first
// flagged (-1: never), and pad 2's type at the end.
template <class Load, class Reading>
std::vector<int> first_flags_of(Load load, Reading reading, int ticks, FaultType* pad2_type = nullptr) {
  Feet feet(suralp(), 1e-3);
  std::vector<int> first(kChannels, -1);
  for (int k = 0; k < ticks; ++k) {
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      fz += load(j, k);
      feet.measured[j] = reading(j, k);
    }
    feet.step(fz);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (first[j] < 0 && feet.outs[ContactForceFdi::kFault][j] != 0.0) first[j] = k;
    }
  }
  if (pad2_type != nullptr) *pad2_type = feet.type(2);
  return first;
}

TEST(ContactForceFdi, AReadingStuckAtTheLoadItJustRoseToIsFoundByAShortStillWindow) {
  // The long window holds pad 2's rise before it stuck, so it names no one when the residual has
  // moved; a short window opened once pad 2's low-pass has caught up with its stuck reading names
  // it on tick 642 (the long window alone: on tick 679, a settling after its reopening).
  const auto [expected, culprit] = still_windows_oracle(ramping_load, ramping_reading, 900, true);
  ASSERT_EQ(culprit, 2u);
  EXPECT_GT(expected, 500);
  EXPECT_LE(expected, 650);
  EXPECT_GT(still_windows_oracle(ramping_load, ramping_reading, 900, false).first, expected + 30);
  FaultType type_at_end = FaultType::none;
  const std::vector<int> first = first_flags_of(ramping_load, ramping_reading, 900, &type_at_end);
  EXPECT_EQ(first[2], expected);
  EXPECT_EQ(type_at_end, FaultType::frozen);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 2) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
}

// A reading that reaches a ceiling inside a short window: pad 5's load rises at 1000 N/s from
// tick 300 (100 N) and its output stops at 200 N (tick 400) while the load goes on to 400 N; pad 2,
// healthy, moves from 150 to 180 N over ticks 100-200 (so the long window, open since tick 0, rules
// it out) and then stays; the others ramp as above. The residual falls only once pad 5 is stuck,
// so pad 5's rise is no move of its own while the residual moved: both still readings explain
// it, and neither is named (taking pad 5's rise as its move, as a window's span does, a short
// window flagged pad 2 from tick 496). Pad 5 is left to the other tests.
double ceiling_load(std::size_t j, int k) {
  if (j == 2) return 150.0 + 0.3 * std::clamp(k - 100, 0, 100);
  if (j == 5) return k < 300 ? 100.0 : std::min(400.0, 100.0 + (k - 300));
  return ramping_load(j, k);
}
double ceiling_reading(std::size_t j, int k) {
  return (j == 5 ? std::min(200.0, ceiling_load(j, k)) : ceiling_load(j, k)) + (k % 2 == 0 ? 1.0 : -1.0);
}

TEST(ContactForceFdi, AStillNeighbourOfAReadingThatJustStuckIsNotNamedByAShortWindow) {
  EXPECT_EQ(still_windows_oracle(ceiling_load, ceiling_reading, 700, true).first, -1);
  const std::vector<int> first = first_flags_of(ceiling_load, ceiling_reading, 700);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 5) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
}

// The unread-load test: the right foot's pads carry 200 + 10 j N (pad 5 read `gain5` times its
// load, a gain not yet found), the left foot is lifted (0.05 m) and lands on tick 500 on pads 0-2
// (150 N each, read right) and pad 3, whose true load is `pad3_load` N. Pad 3's reading stays at
// its air level (+-1 N, a dead sensor's noise). Every reading alternates +-1 N. F_z is the true
// sum plus `impact` N for `impact_ticks` ticks from the landing (the trunk IMU's error at an
// impact). `heel_first`: pad 2 lands unloaded too (a sole on its heel). Returns the tick each
// channel was first flagged (-1: never).
struct LandingTrace {
  double pad3_load = 150.0;
  double impact = 0.0;
  int impact_ticks = 0;
  bool heel_first = false;
  double gain5 = 1.0;
  int pad7_unloads_at = -1;  // from then pad 7 reads and carries 0, its load on pad 4 (a lifting sole)
};

// The left foot, lifted 0.05 m, lands on tick 500. `pad(k, j, noise)` returns pad j's true load and
// its reading on tick k (noise: +-1 N alternating); F_z is the true sum plus `fz_error(k)`. Returns
// the tick each channel was first flagged (-1: never).
template <class Pad, class FzError>
std::vector<int> left_landing_first_flags(int ticks, Pad pad, FzError fz_error) {
  Feet feet(suralp(), 1e-3);
  feet.left_foot_at(0.05);
  std::vector<int> first(kChannels, -1);
  for (int k = 0; k < ticks; ++k) {
    if (k == 500) feet.left_foot_at(0.0);
    const double noise = k % 2 == 0 ? 1.0 : -1.0;
    double fz = fz_error(k);
    for (std::size_t j = 0; j < kChannels; ++j) {
      const auto [load, reading] = pad(k, j, noise);
      fz += load;
      feet.measured[j] = reading;
    }
    feet.step(fz);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (first[j] < 0 && feet.outs[ContactForceFdi::kFault][j] != 0.0) first[j] = k;
    }
  }
  return first;
}

std::vector<int> landing_flags(const LandingTrace& trace, int ticks) {
  return left_landing_first_flags(
      ticks,
      [&](int k, std::size_t j, double noise) {
        double load = j >= 4 ? 200.0 + 10.0 * static_cast<double>(j) : 0.0;
        if (j < 4 && k >= 500) load = j == 3 ? trace.pad3_load : (j == 2 && trace.heel_first) ? 0.0 : 150.0;
        if (trace.pad7_unloads_at >= 0 && k >= trace.pad7_unloads_at && (j == 4 || j == 7)) load = j == 7 ? 0.0 : 470.0;
        return std::pair{load, (j == 3 ? 0.0 : j == 5 ? trace.gain5 * load : load) + noise};
      },
      [&](int k) { return k >= 500 && k < 500 + trace.impact_ticks ? trace.impact : 0.0; });
}

// The oracle of the header: the residual sum(x) - F_z low-passed at 10 Hz from tick 0 stays
// below -sum_threshold_N (80 N) from some tick after the landing; the candidate is counted from
// then, or from the landing's guard's end (0.15 s: tick 650), whichever is later, and held for
// the smoother's settling (80 ticks: 0.080 s is the first multiple of 1 ms past 0.0796 s). The
// flag shows from the next tick.
int unread_load_flagged_at(double pad3_load) {
  const double a = -std::expm1(-2.0 * std::numbers::pi * 10.0 * 1e-3);
  double smoothed = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const double residual = 8.0 * (k % 2 == 0 ? 1.0 : -1.0) - (k >= 500 ? pad3_load : 0.0);
    smoothed = k == 0 ? residual : smoothed + a * (residual - smoothed);
    if (smoothed < -80.0) return std::max(k, 650) + 80 + 1;
  }
  return -1;
}

TEST(ContactForceFdi, APadThatReadsItsAirLevelOnALandedFootIsFrozenOnceTheShortfallHasHeld) {
  // Pad 3 carries 150 N from the landing and reads nothing: the pads read 150 N short of F_z, its
  // neighbours carry load, and it is the only pad on the ground at its air level. Its reading has
  // no window that spans a move named in time (the still-reading test names no pad of a foot
  // inside its landing's guard).
  const int expected = unread_load_flagged_at(150.0);
  ASSERT_EQ(expected, 731);
  const auto first = landing_flags({}, 900);
  EXPECT_EQ(first[3], expected);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 3) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
  // The right sole lifts meanwhile: from tick 640 its pad 7 reads and carries 0 on the ground, a
  // neighbour loaded. It read its load after the residual left its bound (within 20 ticks of the
  // landing), while the shortfall grew: it is no rival of pad 3.
  LandingTrace lifting;
  lifting.pad7_unloads_at = 640;
  const auto with_lifting = landing_flags(lifting, 900);
  EXPECT_EQ(with_lifting[3], expected);
  EXPECT_EQ(with_lifting[7], -1);
  // From tick 450, before the left foot lands: pad 7 has read nothing since the residual was last
  // within its bound, as a pad that died within its stance would have. But no load was handed to
  // it (no step of its foot's pads was left unnamed for it): it is no candidate (counted as one, it
  // was named on tick 592), and pad 3, which has read nothing since its own foot landed, is named
  // once that foot's guard is over, as without pad 7.
  LandingTrace lifted_before;
  lifted_before.pad7_unloads_at = 450;
  const auto with_lifted_before = landing_flags(lifted_before, 900);
  EXPECT_EQ(with_lifted_before[3], expected);
  EXPECT_EQ(with_lifted_before[7], -1);
}

TEST(ContactForceFdi, AnUnloadedPadIsNoUnreadLoadWhereTheShortfallIsAnImpactsOrTwoPadsReadNothing) {
  // Pad 3 truly unloaded (the sole rolls off it): F_z exceeds the pads' sum by 150 N for 90 ticks
  // or 300 N for 140 after the landing, an impact within the 0.15 s guard, whose low-passed
  // residual stays below -80 N for more than the settling (80 ticks) but ends inside the guard.
  for (const auto& [impact, ticks] : {std::pair{150.0, 90}, std::pair{300.0, 140}}) {
    SCOPED_TRACE("impact " + std::to_string(impact) + " N for " + std::to_string(ticks) + " ticks");
    const auto first = landing_flags({0.0, impact, ticks}, 1200);
    for (std::size_t j = 0; j < kChannels; ++j) EXPECT_EQ(first[j], -1) << "channel " << j;
  }
  // Pad 3 reads nothing of its 150 N, but pad 2 lands unloaded as well: either may be the one.
  const auto heel = landing_flags({150.0, 0.0, 0, true}, 1200);
  for (std::size_t j : {0U, 1U, 2U, 3U}) EXPECT_EQ(heel[j], -1) << "channel " << j;
}

TEST(ContactForceFdi, AShortfallFromBeforeTheLandingIsNoUnreadLoadOfTheLandedFootsPad) {
  // Pad 5 reads half its 250 N from the start (a gain not yet found): the pads read 125 N short
  // of F_z before the left foot lands, and after it pad 3, truly unloaded, is the one pad at its
  // air level. The shortfall is not the landing's: pad 3 is not blamed.
  const auto first = landing_flags({0.0, 0.0, 0, false, 0.5}, 1500);
  EXPECT_EQ(first[3], -1);
}

// A heel rolling onto a dead pad after its foot's guard: the left foot lands on tick 500 on pads
// 0-2 (150 N each, read right) while pad 3 carries nothing; on tick `roll` 60 N of each of pads 0
// and 1 moves onto pad 3 in one tick, and on tick 1100 another 45 N of each. Pad 3 reads its
// load if `pad3_reads`, else its air level. Every reading alternates +-1 N, F_z is the true sum.
// `pad3_carries_until` > 500: pad 3 first carries 30 N from the landing to that tick, read right
// (its sensor alive then), and carries nothing until the roll.
std::vector<int> heel_roll_flags(bool pad3_reads, int roll, int ticks, int pad3_carries_until = -1) {
  return left_landing_first_flags(
      ticks,
      [&](int k, std::size_t j, double noise) {
        double load = j >= 4 ? 200.0 + 10.0 * static_cast<double>(j) : 0.0;
        if (j < 4 && k >= 500) load = j == 3 ? 0.0 : 150.0;
        const bool early_load = j == 3 && k >= 500 && k < pad3_carries_until;
        if (early_load) load = 30.0;
        if (k >= roll && j < 2) load -= 60.0;
        if (k >= roll && j == 3) load += 120.0;
        if (k >= 1100 && j < 2) load -= 45.0;
        if (k >= 1100 && j == 3) load += 90.0;
        return std::pair{load, (j == 3 && !pad3_reads && !early_load ? 0.0 : load) + noise};
      },
      [](int) { return 0.0; });
}

TEST(ContactForceFdi, AnOffsetNotYetToldFromAGainRestartsTheStillWindows) {
  // Pad 5 (250 N) reads twice its load from tick 500: its jump of +250 N is confirmed an offset
  // b = 250 N, which fits the onset as well as a gain k = 1 + b / 250 N = 2. From tick 520 its load
  // falls 1 N per tick to 50 N, so x - b misses it by 250 N - L and the residual falls with it.
  // Pad 6 (260 N) is the one still reading; the others ramp at 400 N/s. Until the offset-or-gain
  // test decides (the load 160 N from where it stood), pad 5's correction may scale with its load:
  // the windows restart and pad 6 is not named (taking the offset as additive, pad 6 was flagged
  // frozen on tick 670). Pad 5 ends a gain.
  Feet feet(suralp(), 1e-3);
  std::vector<int> first(kChannels, -1);
  for (int k = 0; k < 900; ++k) {
    const double noise = k % 2 == 0 ? 1.0 : -1.0;
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const bool up = j == 0 || j == 2 || j == 7;
      double load = up ? 100.0 + 0.4 * k : 600.0 - 0.4 * k;  // 400 N/s: never still
      if (j == 6) load = 260.0;
      if (j == 5) load = 250.0 - std::clamp(k - 520, 0, 200);
      fz += load;
      feet.measured[j] = (j == 5 && k >= 500 ? 2.0 * load : load) + noise;
    }
    feet.step(fz);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (first[j] < 0 && feet.outs[ContactForceFdi::kFault][j] != 0.0) first[j] = k;
    }
  }
  EXPECT_EQ(feet.type(5), FaultType::gain);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 5) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
}

// The still-reading test across the other foot's landing. The right foot carries the robot: pad j
// (4-7) 250 + 10 (j - 4) N, pads 4, 5 and 7 with a 30 N sine of 1 Hz. The left foot, lifted, lands
// on tick 500: pads 0 and 1 take 38 N on that tick (a step of the landing) and 1 N more per tick,
// pads 2 and 3 1 N per tick from tick 550 (`toe_loads`; else pad 3 stays at 0 and pad 2 steps
// likewise a tick after pads 0-1: the right pads give up under 20 N per tick, no step of theirs);
// the right pads give up what the left take, R/4 each (R/3 each for pads 4, 5, 7 when pad 6 keeps
// its load). Readings alternate +-1 N.
struct TransferTrace {
  bool pad6_stuck = false;     // pad 6 reads its load of tick 0 (270 N) from tick 300
  bool pad6_keeps_load = false;
  bool toe_loads = true;       // false: pad 3 carries and reads 0 (+-1 N) throughout
  double pad5_offset_from_520 = 0.0;
};
double transfer_left_load(const TransferTrace& trace, std::size_t j, int k) {
  if (k < 500) return 0.0;
  if (j < 2) return 38.0 + (k - 500);
  if (trace.toe_loads) return std::max(0, k - 550);
  return j == 2 && k >= 501 ? 38.0 + (k - 501) : 0.0;
}
double transfer_load(const TransferTrace& trace, std::size_t j, int k) {
  if (j < 4) return transfer_left_load(trace, j, k);
  double left = 0.0;
  for (std::size_t i = 0; i < 4; ++i) left += transfer_left_load(trace, i, k);
  const double base = 250.0 + 10.0 * static_cast<double>(j - 4);
  if (j == 6) return trace.pad6_keeps_load ? base : base - left / 4.0;
  const double sine = 30.0 * std::sin(2.0 * std::numbers::pi * k * 1e-3 + static_cast<double>(j));
  return base + sine - left / (trace.pad6_keeps_load ? 3.0 : 4.0);
}
double transfer_reading(const TransferTrace& trace, std::size_t j, int k) {
  const double noise = k % 2 == 0 ? 1.0 : -1.0;
  if (j == 6 && trace.pad6_stuck && k >= 300) return 270.0 + noise;
  const double offset = j == 5 && k >= 520 ? trace.pad5_offset_from_520 : 0.0;
  return transfer_load(trace, j, k) + offset + noise;
}
std::vector<int> transfer_flags(const TransferTrace& trace, int ticks, double (*fz_error)(int)) {
  return left_landing_first_flags(
      ticks, [&](int k, std::size_t j, double) { return std::pair{transfer_load(trace, j, k), transfer_reading(trace, j, k)}; },
      fz_error);
}
double no_fz_error(int) { return 0.0; }

TEST(ContactForceFdi, AStillReadingIsJudgedThroughTheOtherFootsLanding) {
  // Pad 6 stuck while the left foot's landing takes its load away: the landing pads' steps are
  // their landing, not a fault's onset, so the windows are not restarted by them and the move of
  // the residual from the landing on names pad 6 (the oracle, with the pads' heights). Restarted
  // by them (as any step restarted them before), pad 6 was flagged on tick 663, not 603.
  const TransferTrace trace{.pad6_stuck = true};
  const auto airborne = [](std::size_t j, int k) { return j < 4 && k < 500; };
  const auto load = [&](std::size_t j, int k) { return transfer_load(trace, j, k); };
  const auto reading = [&](std::size_t j, int k) { return transfer_reading(trace, j, k); };
  const auto [expected, culprit] = still_windows_oracle(load, reading, 700, true, airborne);
  ASSERT_EQ(culprit, 6u);
  EXPECT_EQ(expected, 603);
  const auto first = transfer_flags(trace, 700, no_fz_error);
  EXPECT_EQ(first[6], expected);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 6) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
}

TEST(ContactForceFdi, AStepOfAPadWhoseFootIsNotLandingRestartsTheStillWindowsInsideALandingsGuard) {
  // Pad 6 keeps a steady load (read right), and pad 5, on the loaded foot, steps by +100 N on tick
  // 520, inside the left foot's landing guard, where the jump test judges no step. The step may be
  // a fault's onset: the windows restart, so the residual's move of 100 N is not blamed on pad 6,
  // the one still reading (without the restart, it was flagged frozen on tick 546).
  const TransferTrace trace{.pad6_keeps_load = true, .pad5_offset_from_520 = 100.0};
  const auto first = transfer_flags(trace, 650, no_fz_error);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 5) {
      EXPECT_EQ(first[j], -1) << "channel " << j;
    }
  }
}

// F_z 200 N above the loads' sum at the landing's impact: rising over ticks 500-540, back to 0 by
// tick 560 (the trunk IMU's error at an impact).
double impact_fz_error(int k) {
  if (k < 500 || k >= 560) return 0.0;
  return k < 540 ? 5.0 * (k - 500) : 200.0 - 10.0 * (k - 540);
}

TEST(ContactForceFdi, ALandingFootsPadAtItsAirLevelIsNotNamedWhileItsFootLands) {
  // Pad 3, the landing foot's toe, carries nothing yet and reads its air level, the only reading
  // on the ground that does not move while the impact moves the residual. It may be the one, but
  // a sole takes its load pad by pad: it is not named inside its foot's landing guard (0.15 s);
  // without the rule it was flagged frozen on tick 609.
  const TransferTrace trace{.toe_loads = false};
  const auto first = transfer_flags(trace, 700, impact_fz_error);
  for (std::size_t j = 0; j < kChannels; ++j) EXPECT_EQ(first[j], -1) << "channel " << j;
}

// The first tick the residual of heel_roll_flags with pad 3 dead (sum(x) - F_z: its +-8 N noise,
// 120 N short from the roll on tick 700), low-passed at 10 Hz from tick 0, is below
// -sum_threshold_N (80 N).
int heel_roll_shortfall_below_bound() {
  const double a = -std::expm1(-2.0 * std::numbers::pi * 10.0 * 1e-3);
  double smoothed = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const double residual = 8.0 * (k % 2 == 0 ? 1.0 : -1.0) - (k >= 700 ? 120.0 : 0.0);
    smoothed = k == 0 ? residual : smoothed + a * (residual - smoothed);
    if (smoothed < -80.0) return k;
  }
  return -1;
}

TEST(ContactForceFdi, NeighboursHandingLoadToADeadPadAreNotItsFaultAndTheDeadPadIsFound) {
  // Tick 700, past the guard (650): pads 0 and 1 step by -60 N each and the sum falls by 120 N.
  // That is their sensors' step, or pad 3's landing unread (it reads its air level and has
  // carried nothing since its foot landed): the jump cannot tell, so it names no one (it named
  // both offsets on tick 709 before). The unread-load test names pad 3 once the low-passed
  // residual is below -80 N and the smoother has settled (the oracle of the test above).
  const int below = heel_roll_shortfall_below_bound();
  ASSERT_GT(below, 700);
  const auto dead = heel_roll_flags(false, 700, 1400);
  EXPECT_EQ(dead[3], below + 80 + 1);
  // Flagged (substituted), pad 3 reads nothing of the next 90 N pads 0 and 1 hand it on tick 1100
  // (beyond the 80 N a substituted pad's step must clear): a stuck reading's load moving is no
  // step of its neighbours' either.
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 3) {
      EXPECT_EQ(dead[j], -1) << "channel " << j;
    }
  }
  // Read, the heel's landing is in the sum: nothing steps, no one is named.
  const auto healthy = heel_roll_flags(true, 700, 1400);
  for (std::size_t j = 0; j < kChannels; ++j) EXPECT_EQ(healthy[j], -1) << "channel " << j;
}

TEST(ContactForceFdi, APadThatCarriedLoadEarlierInItsStanceAndDiedAtItsAirLevelIsFoundAsItsLoadReturns) {
  // Pad 3 carries 30 N from the landing to tick 600, read right, then nothing; its sensor dies
  // there at its air level, and on tick 700 the roll hands it 120 N unread. What matters is that it
  // read nothing since the pads' sum last matched F_z (and was handed its neighbours' load), not
  // since its foot landed: the same shortfall, the same pad, found on the same tick as a pad dead
  // from the landing (the oracle of the test above), and its neighbours' steps are no group of
  // offsets (both named on tick 709 while only a pad unloaded since the landing counted).
  const int below = heel_roll_shortfall_below_bound();
  ASSERT_GT(below, 700);
  const auto dead = heel_roll_flags(false, 700, 1400, 600);
  EXPECT_EQ(dead[3], below + 80 + 1);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 3) {
      EXPECT_EQ(dead[j], -1) << "channel " << j;
    }
  }
  // Alive, its load leaving and returning is in the sum: no one is named.
  const auto healthy = heel_roll_flags(true, 700, 1400, 600);
  for (std::size_t j = 0; j < kChannels; ++j) EXPECT_EQ(healthy[j], -1) << "channel " << j;
}

// A heel landing late, past its foot's guard: the left foot lands on tick 500 on pads 0-2 (150 N
// each) while pad 3 carries nothing; on tick 700 pad 3 takes 25 N (`pad3_lands`, read right) and
// pad 2's load jolts by +30 N on the same tick, which F_z misses for 30 ticks (the trunk IMU does
// not see a pad's impact at once). Readings alternate +-1 N. Returns the tick each channel was
// first flagged (-1: never).
std::vector<int> late_heel_flags(bool pad3_lands) {
  return left_landing_first_flags(
      1000,
      [&](int k, std::size_t j, double noise) {
        double load = j >= 4 ? 200.0 + 10.0 * static_cast<double>(j) : 0.0;
        if (j < 4 && k >= 500) load = j == 3 ? (pad3_lands && k >= 700 ? 25.0 : 0.0) : 150.0;
        if (j == 2 && k >= 700) load += 30.0;
        return std::pair{load, load + noise};
      },
      [](int k) { return k >= 700 && k < 730 ? -30.0 : 0.0; });
}

TEST(ContactForceFdi, ANeighboursStepOnThePadsLateLandingTickIsNotJudged) {
  // The jolt steps pad 2 and the sum residual by 30 N alike (jump 20 N, confirmation 25 N at 2 N
  // of noise), as a sensor's offset would: alone (no landing beside it) it is named on tick 709.
  // On the tick pad 3 lands, whose impact F_z misses, it is not judged.
  EXPECT_EQ(late_heel_flags(false)[2], 709);
  const auto landing = late_heel_flags(true);
  for (std::size_t j = 0; j < kChannels; ++j) EXPECT_EQ(landing[j], -1) << "channel " << j;
}

TEST(ContactForceFdi, NeighboursHandingLoadToAReadingTheAirFoundOffIsNoStepOfTheirs) {
  // Pad 0 reads 150 N in the swing (the air test raises an offset: a reading frozen there reads
  // alike). It lands unloaded on tick 200 and on tick 400 (past the landing's guard) pads 1 and 2 hand it 50 N each in one
  // tick, which its stuck reading does not show: pads 1 and 2 step by -50 N and the sum by -100 N.
  // Until pad 0's reading has been seen to follow its load, those steps name no one (both were
  // named offsets on tick 409 before).
  const auto run = [](bool frozen) {
    Feet feet(suralp(), 1e-3);
    std::vector<int> first(kChannels, -1);
    for (int k = 0; k < 600; ++k) {
      const bool landed = k >= 200;
      feet.left_foot_at(landed ? 0.0 : 0.1);
      const double noise = k % 2 == 0 ? 1.0 : -1.0;
      double fz = 0.0;
      for (std::size_t j = 0; j < kChannels; ++j) {
        double load = j >= 4 ? moving(j, k, 0.0) : landed && j > 0 ? 100.0 : 0.0;
        if (k >= 400 && (j == 1 || j == 2)) load -= 50.0;
        if (k >= 400 && j == 0) load += 100.0;
        fz += load;
        feet.measured[j] = j >= 4 ? load : (j == 0 ? (frozen ? 150.0 : load + 150.0) : load) + noise;
      }
      feet.step(fz);
      if (k == 150) {
        EXPECT_EQ(feet.type(0), FaultType::offset) << "the airborne test raises it";
      }
      for (std::size_t j = 0; j < kChannels; ++j) {
        if (first[j] < 0 && feet.outs[ContactForceFdi::kFault][j] != 0.0) first[j] = k;
      }
    }
    return first;
  };
  const auto frozen = run(true);
  for (std::size_t j = 1; j < kChannels; ++j) EXPECT_EQ(frozen[j], -1) << "channel " << j;
  // An offset that reads its load + 150 N: the same hand-over is in its reading, and the sum stays.
  const auto offset = run(false);
  for (std::size_t j = 1; j < kChannels; ++j) EXPECT_EQ(offset[j], -1) << "channel " << j;
}

TEST(ContactForceFdi, LoadRockingBetweenTwoPadsForATickIsNoSpikeWhereItsFootsSumStaysSmooth) {
  // 1 kHz, 1 N of noise: the spike threshold is 30 N. Every 50 ticks from tick 100, 38 N moves from
  // pad 0 to pad 3 of the left foot for one tick and back (a sole rocking on its heel pad, as the
  // simulated SURALP's does at 1 N of noise): a 38 N spike on pad 3 and on pad 0, but the foot's
  // summed reading does not move. The same 38 N on pad 3 alone (tick 300) moves the sum by 38 N:
  // a spike, flagged on the tick after it (the tick that tells it from a step).
  ContactForceFdi::Params p = suralp();
  p.noise_std_N = 1.0;
  Feet rocking(p, 1e-3), spike(p, 1e-3);
  for (int k = 0; k < 400; ++k) {
    const bool rock = k >= 100 && k % 50 == 0;
    for (std::size_t j = 0; j < kChannels; ++j) rocking.measured[j] = spike.measured[j] = moving(j, k, 0.0);
    rocking.measured[3] += rock ? 38.0 : 0.0;
    rocking.measured[0] -= rock ? 38.0 : 0.0;
    spike.measured[3] += k == 300 ? 38.0 : 0.0;
    rocking.step();
    spike.step();
    ASSERT_EQ(rocking.type(3), FaultType::none) << "tick " << k;
    ASSERT_EQ(rocking.type(0), FaultType::none) << "tick " << k;
    ASSERT_EQ(spike.type(3), k >= 301 ? FaultType::spikes : FaultType::none) << "tick " << k;
  }
}

TEST(ContactForceFdi, ThePadsOfAFootThatIsNotLandingRingWithTheOtherFootsImpactAndAreNoNoiseBurst) {
  // 200 Hz. The left foot lands at tick 50 (its pads come down from 0.1 m); from tick 52 the right
  // foot's pad 5 rings with the impact, +-16 N (the +-16 N jitter the noise test above calls a
  // burst; the right foot's sum rings with it), for 20 ticks (0.1 s, within the 0.15 s guard):
  // no noise burst. The same ringing 0.2 s after the landing is one, once 6 large second
  // differences are in: its first tick's is large already (the step from 250 N to 316 N), so on
  // the sixth ringing tick.
  for (const int ring_from : {52, 90}) {
    SCOPED_TRACE("ringing from tick " + std::to_string(ring_from));
    Feet feet(suralp(), 5e-3);
    feet.left_foot_at(0.1);
    // Past the guard's end too (tick 80): the ringing counted inside it raises nothing after.
    for (int k = 0; k < ring_from + 50; ++k) {
      if (k == 50) feet.left_foot_at(0.0);
      for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = j < 4 && k < 50 ? 0.0 : moving(j, k, 0.0);
      if (k >= ring_from && k < ring_from + 20) feet.measured[5] = 300.0 + (k % 2 == 0 ? 16.0 : -16.0);
      feet.step();
      if (ring_from == 90 && k >= ring_from + 20) break;  // the burst's end is another test's
      const bool burst = ring_from == 90 && k >= ring_from + 5;
      ASSERT_EQ(feet.type(5), burst ? FaultType::noise : FaultType::none) << "tick " << k;
    }
  }
}

// Pad 3 stuck at 50 N from the start (raised on tick 20, substituted from the total force while
// loaded), the other pads healthy; 1 kHz, 1 N of noise (jump confirmation 12.5 N, three times
// that with a substituted channel: 37.5 N; sum_threshold_N 80 N). From tick 200 its true load
// goes elsewhere, unread: `moved` hands its 50 N to pads 1 and 2 for good (25 N each, one tick),
// otherwise it chatters: pad 0 takes the 50 N on odd ticks and hands it back on even ones.
std::vector<FaultType> neighbours_of_a_substituted_pad(bool moved) {
  ContactForceFdi::Params p = suralp();
  p.noise_std_N = 1.0;
  Feet feet(p, 1e-3);
  std::vector<FaultType> worst(kChannels, FaultType::none);
  for (int k = 0; k < 500; ++k) {
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) fz += feet.measured[j] = moving(j, k, 0.0);
    feet.measured[3] = 50.0;
    fz += 50.0 - moving(3, k, 0.0);
    if (k >= 200 && moved) {
      feet.measured[1] += 25.0;
      feet.measured[2] += 25.0;
    } else if (k >= 200 && k % 2 == 1) {
      feet.measured[0] += 50.0;
    }
    feet.step(fz);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (k >= 21 && j == 3) {
        EXPECT_NE(feet.type(3), FaultType::none) << "tick " << k;
      } else if (feet.type(j) != FaultType::none) {
        worst[j] = feet.type(j);
      }
    }
  }
  return worst;
}

TEST(ContactForceFdi, ASubstitutedPadsLoadMovingToItsNeighboursConfirmsNoGroupOfTheirSteps) {
  // The residual, which takes pad 3 as read, steps by +50 N with the two neighbours' +25 N steps:
  // beyond 37.5 N, it would confirm them as two offsets; within the 80 N bound of what the total
  // force leaves pad 3, it confirms nothing.
  const auto worst = neighbours_of_a_substituted_pad(true);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 3) {
      EXPECT_EQ(worst[j], FaultType::none) << "channel " << j;
    }
  }
}

TEST(ContactForceFdi, ANeighbourOfASubstitutedPadIsNotJudgedNoisyOrSpikyByTheLoadTheyTrade) {
  // Pad 0 swings by 50 N every tick (a 50 N spike on each, |d2| = 100 N, far above 4 sqrt(6) =
  // 9.8 N), and its foot's summed reading swings with it (pad 3's share is not in it): neither a
  // noise burst nor spikes on pad 0 while pad 3 is substituted.
  const auto worst = neighbours_of_a_substituted_pad(false);
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != 3) {
      EXPECT_EQ(worst[j], FaultType::none) << "channel " << j;
    }
  }
}

TEST(ContactForceFdi, AOneTickSpikeAtASlowLogRateIsASpikeNotAStep) {
  // 200 Hz, 2 N of noise: the jump window is 2 ticks, the confirmation 25 N. A 100 N spike on
  // loaded pad 2 at tick 100 moves the residual's 2-tick mean by 50 N, within 50 % of the jump: as
  // a group it would be confirmed as a +100 N offset on tick 101. Its reading is back on tick 101,
  // so it leaves the group, and the spike test names it on that tick.
  Feet feet(suralp(), 5e-3);
  for (int k = 0; k < 140; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    double fz = 0.0;
    for (double x : feet.measured) fz += x;
    if (k == 100) feet.measured[2] += 100.0;
    feet.step(fz);
    ASSERT_EQ(feet.type(2), k >= 101 ? FaultType::spikes : FaultType::none) << "tick " << k;
  }
}

TEST(ContactForceFdi, AOneTickSpikeBesideANoiseBurstAtASlowLogRateIsNoStep) {
  // 200 Hz again, pad 1 of the same foot reading a +-30 N noise burst from the start (flagged
  // noise: pad 2's excursions are then not judged as spikes, and a jump needs 3 x 25 N of residual
  // step). A 300 N spike on pad 2 at tick 100 moves the 2-tick mean by 150 N, within 50 % of the
  // jump and beyond 75 N: as a group it would be confirmed as a +300 N offset. Its reading is
  // back on tick 101, so it leaves the group: pad 2 is never flagged.
  Feet feet(suralp(), 5e-3);
  for (int k = 0; k < 140; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    feet.measured[1] = 250.0 + (k % 2 == 0 ? 30.0 : -30.0);
    double fz = 0.0;
    for (double x : feet.measured) fz += x;
    if (k == 100) feet.measured[2] += 300.0;
    feet.step(fz);
    ASSERT_EQ(feet.type(2), FaultType::none) << "tick " << k;
    if (k >= 20) {
      ASSERT_EQ(feet.type(1), FaultType::noise) << "tick " << k;
    }
  }
}

TEST(ContactForceFdi, AChannelFlaggedForSpikesEntersTheJumpTestsSumAsItsMedian) {
  // 500 Hz (a 5-tick jump window), 2 N of noise. Pad 0 spikes by 250 N at ticks 200, 250, 300
  // (flagged spikes from tick 201). At tick 305 pad 1's load falls by 60 N and the total force
  // with it: a healthy change. The window before it holds the 250 N spike of tick 300 (+50 N on
  // its mean): taken as read, the residual would step by -50 N, within 50 % of pad 1's -60 N, and
  // confirm it as an offset; taken as its median, the residual does not step.
  Feet feet(suralp(), 2e-3);
  for (int k = 0; k < 400; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    if (k >= 305) feet.measured[1] -= 60.0;
    double fz = 0.0;
    for (double x : feet.measured) fz += x;
    if (k == 200 || k == 250 || k == 300) feet.measured[0] += 250.0;
    feet.step(fz);
    ASSERT_EQ(feet.type(1), FaultType::none) << "tick " << k;
    if (k >= 201) {
      ASSERT_EQ(feet.type(0), FaultType::spikes) << "tick " << k;
    }
  }
}

TEST(ContactForceFdi, ASpikingPadsMedianLagAtItsLandingConfirmsNoNeighboursLoadShift) {
  // 200 Hz (a 2-tick jump window). Pad 3 spikes by 250 N at ticks 40, 60 and 80 (flagged spikes),
  // then hands its load to pad 2 over ticks 85-94 (10 N per tick, no step) and reads 0. At tick
  // 120 it lands again, 0 -> 80 N in one tick (a pad landing: no candidate itself), while pad 2
  // sheds 40 N in that tick and pad 0 40 N over ticks 116-123: healthy moves, the total force
  // with them. Its median of three (0, 0, 80) = 0 leaves -80 N in the residual of tick 120, and
  // the window's mean, -40 N, matched pad 2's -40 N step: an offset on a healthy pad (as at a
  // spiking heel's landing in tools/unseen_walks.py). Once tick 121 shows the rise stayed, tick
  // 120's residual takes the reading: no step.
  Feet feet(suralp(), 5e-3);
  for (int k = 0; k < 200; ++k) {
    const double wiggle = k % 2 == 0 ? 0.5 : -0.5;
    double load[kChannels];
    for (std::size_t j = 0; j < kChannels; ++j) load[j] = 100.0;
    const double handed = std::clamp((k - 84) * 10.0, 0.0, 100.0);  // pad 3 -> pad 2
    load[3] -= handed;
    load[2] += handed;
    if (k >= 120) {
      load[3] += 80.0;
      load[2] -= 40.0;
    }
    load[0] -= std::clamp((k - 115) * 5.0, 0.0, 40.0);
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = load[j] + (j % 2 == 0 ? wiggle : -wiggle);
      fz += load[j];
    }
    if (k == 40 || k == 60 || k == 80) feet.measured[3] += 250.0;
    feet.step(fz);
    for (std::size_t j = 0; j < 3; ++j) ASSERT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
    if (k >= 81 && k <= 121) {
      ASSERT_EQ(feet.type(3), FaultType::spikes) << "tick " << k;
    }
  }
}

TEST(ContactForceFdi, ANeighbourOfANoiseBurstIsNotJudgedSpikyByTheLoadItTrades) {
  // 1 kHz, 1 N of noise (spike threshold 30 N). Pad 1 reads a +-30 N noise burst (flagged noise);
  // every 50 ticks, on even ticks, pad 0 hands 38 N to pad 3 for one tick and takes it back. The
  // foot's summed reading carries pad 1's noise, which spikes the same way then (+60 N): the
  // rocking would pass for a spike of pad 0. While a neighbour reads a noise burst, pad 0's
  // excursions are not judged.
  ContactForceFdi::Params p = suralp();
  p.noise_std_N = 1.0;
  Feet feet(p, 1e-3);
  for (int k = 0; k < 600; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = moving(j, k, 0.0);
    feet.measured[1] = 250.0 + (k % 2 == 0 ? 30.0 : -30.0);
    if (k >= 200 && k % 50 == 0) {
      feet.measured[0] += 38.0;
      feet.measured[3] -= 38.0;
    }
    feet.step();
    ASSERT_EQ(feet.type(0), FaultType::none) << "tick " << k;
    ASSERT_EQ(feet.type(3), FaultType::none) << "tick " << k;
    if (k >= 100) {
      ASSERT_EQ(feet.type(1), FaultType::noise) << "tick " << k;
    }
  }
}

TEST(ContactForceFdi, AStuckOutputsStepBackToItsLoadIsItsEndNotANewOffset) {
  // Pad 2 carries 250 N, and from tick 500 its load falls at 400 N/s to 20 N (tick 1075) while its
  // output stays stuck at 250 N with its +-1 N noise: raised frozen by the still-reading test. At
  // tick 1200 the output reads its load again: a -230 N step. The follow test re-admits it once
  // its smoothed reading (10 Hz, a = 1 - e^(-2 pi 10 T) = 0.0609 per tick) has moved by 80 N:
  // 1 - (1 - a)^m >= 80 / 230 takes m = 7 updates, seen on tick 1207, before the jump's window
  // is complete (tick 1209): the step is the end of a flagged channel's fault, and is not then
  // taken for an offset's onset.
  Feet feet(suralp(), 1e-3);
  int frozen_at = -1, cleared_at = -1;
  for (int k = 0; k < 1600; ++k) {
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      const double load = j == 2 ? (k < 500 ? 250.0 : std::max(20.0, 250.0 - 0.4 * (k - 500)))
                                 : 200.0 + 10.0 * static_cast<double>(j) + 40.0 * std::sin(2.0 * std::numbers::pi * k * 1e-3 + static_cast<double>(j));
      fz += load;
      const double read = j == 2 && k >= 500 && k < 1200 ? 250.0 : load;
      feet.measured[j] = read + (k % 2 == 0 ? 1.0 : -1.0);
    }
    feet.step(fz);
    if (frozen_at < 0 && feet.type(2) == FaultType::frozen) frozen_at = k;
    if (frozen_at >= 0 && cleared_at < 0 && feet.type(2) == FaultType::none) cleared_at = k;
    if (cleared_at >= 0) {
      ASSERT_EQ(feet.type(2), FaultType::none) << "tick " << k;
    }
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 2) {
        ASSERT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
  EXPECT_GT(frozen_at, 500);
  EXPECT_LT(frozen_at, 1200);
  EXPECT_EQ(cleared_at, 1200 + 7);
}

// Pad 2 of the left foot (5 N steps, 2 N of noise: a healthy reading leaves its level every tick
// here, a stuck one is frozen after n_f = 77 ticks) carries 200 N, rises by 5 N per tick to 700 N
// from tick 100, falls back to 200 N from tick 400, and from tick 1000 rises again by 5 N per
// tick. Its sensor clips at 300 N in both rises (`clipped_again`), or only in the first: in the
// second it is healthy and reads 300 N exactly for 40 ticks while its load holds there. F_z is
// exact. Returns the first tick it is flagged from tick 1000 (-1: never) and the type then.
std::pair<int, FaultType> second_clip_flagged_at(bool clipped_again, int& readmitted_at) {
  Feet feet(suralp(5.0), 1e-3);
  readmitted_at = -1;
  bool flagged_before = false;
  for (int k = 0; k < 1300; ++k) {
    double load = k < 100 ? 200.0 : k < 200 ? 200.0 + 5.0 * (k - 100) : k < 400 ? 700.0 : k < 500 ? 700.0 - 5.0 * (k - 400) : 200.0;
    double reading = load + (k % 2 == 0 ? 0.0 : 4.75);
    if (k < 1000) {
      reading = std::min(reading, 300.0);
    } else if (clipped_again) {
      load = std::min(700.0, 200.0 + 5.0 * (k - 1000));
      reading = std::min(load + (k % 2 == 0 ? 0.0 : 4.75), 300.0);
    } else {
      load = k < 1020 ? 200.0 + 5.0 * (k - 1000) : k < 1060 ? 300.0 : std::min(700.0, 300.0 + 5.0 * (k - 1060));
      reading = k >= 1020 && k < 1060 ? 300.0 : load + (k % 2 == 0 ? 0.0 : 4.75);
    }
    double others = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) {
      feet.measured[j] = j == 2 ? reading : moving(j, k, 5.0);
      if (j != 2) others += feet.measured[j];
    }
    feet.step(others + load);
    if (k < 1000) {
      if (feet.type(2) != FaultType::none) flagged_before = true;
      if (flagged_before && readmitted_at < 0 && feet.type(2) == FaultType::none) readmitted_at = k;
    } else if (feet.type(2) != FaultType::none) {
      return {k, feet.type(2)};
    }
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 2) {
        EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
  return {-1, FaultType::none};
}

TEST(ContactForceFdi, APadBackOnTheLevelItWasFoundClippedAtIsSaturatedOnceItsLoadShowsMore) {
  // The first clip is found by the repeat test (and re-admitted once the reading moves again).
  // The second: the reading is within q / 2 of its old ceiling from tick 1019 (299.75 N, then
  // 300 N); its leave-one-out force (the load) exceeds 300 + sum_threshold_N = 380 N from tick
  // 1037 (385 N), so it is saturated on the next tick, 1038, where the repeat test alone waits
  // until 1019 + 77 = 1096 (measured with this rule switched off).
  int readmitted_at = -1;
  const auto [clipped_at, clipped_type] = second_clip_flagged_at(true, readmitted_at);
  ASSERT_GE(readmitted_at, 0);
  EXPECT_LT(readmitted_at, 1000);
  EXPECT_EQ(clipped_at, 1038);
  EXPECT_EQ(clipped_type, FaultType::saturation);
  // Healthy in the second rise: it reads 300 N while it carries 300 N, then above: not flagged.
  const auto [healthy_at, healthy_type] = second_clip_flagged_at(false, readmitted_at);
  EXPECT_EQ(healthy_at, -1) << "flagged " << to_string(healthy_type);
}

// Pad 2 carries 200 N; on tick 50 its load jolts to 360 N as its sensor starts to read twice its
// load (720 N: a jump of 520 N, which the onset takes as k = 1 + 520 / 200 = 3.6), and the load
// then swings by 200 N at 2.5 Hz. F_z is exact. Returns the type on the last tick, with the
// recovered value and the load then.
FaultType gain_after_a_jolted_onset(int ticks, double& recovered, double& load) {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < ticks; ++k) {
    const double swing = k < 50 ? 200.0 : 360.0 + 200.0 * std::sin(2.0 * std::numbers::pi * 2.5 * (k - 50) * 1e-3);
    load = swing + (k % 2 == 0 ? 0.0 : 1.0);
    step_pad2(feet, k, load, k < 50 ? load : 2.0 * load);
  }
  recovered = feet.outs[ContactForceFdi::kRecovered][2];
  return feet.type(2);
}

TEST(ContactForceFdi, AGainsKIsRefittedOnItsReadingAgainstItsLeaveOneOutForce) {
  // Typed gain once the load has moved far enough from where both models meet (tick 400), with
  // the onset's k (3.6): recovered 2 L / 3.6 = 0.56 L. Its reading against the (exact)
  // leave-one-out force spans sum_threshold_N (80 N) of load over clear_s within the next 50
  // ticks: the fit x = k v gives k = 2 exactly, 44 % from the k held, and is taken. Without the
  // refit (switched off, not kept) the last tick recovers 282 N of a 505 N load.
  double recovered = 0.0, load = 0.0;
  ASSERT_EQ(gain_after_a_jolted_onset(1000, recovered, load), FaultType::gain);
  EXPECT_NEAR(recovered, load, 1e-6 * load);
}

// Pad 2 (left foot) held as a gain (k = 2) as in the rising-load test above. The right foot lifts on
// tick 600 and lands on tick 700 (its guard: 150 ticks). On tick 710 pad 2's load falls 500 -> 250 N
// (its reading 1000 -> 500: a step back by the gain's size at that load), and on tick 720 to 0 (its
// reading too). From tick 720 F_z reads 250 N more than the loads (an impact's error that stays).
// Returns pad 2's type on tick 1100.
FaultType gain_after_its_load_left_in_another_foots_guard() {
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 1100; ++k) {
    const double load = k < 100 ? 200.0 : k < 710 ? std::min(500.0, 200.0 + (k - 100)) : k < 720 ? 250.0 : 0.0;
    const bool right_up = k >= 600 && k < 700;
    std::fill(feet.height.begin() + 4, feet.height.end(), right_up ? 0.1 : 0.0);
    double fz = load + (k >= 720 ? 250.0 : 0.0);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j == 2) continue;
      feet.measured[j] = j >= 4 && right_up ? (k % 2 == 0 ? 1.0 : -1.0) : moving(j, k, 0.0);
      if (!(j >= 4 && right_up)) fz += feet.measured[j];
    }
    const double noise = k % 2 == 0 ? 0.0 : 1.0;
    feet.measured[2] = k < 50 ? load + noise : 2.0 * load + noise;
    feet.step(fz);
    if (k == 599) {
      EXPECT_EQ(feet.type(2), FaultType::gain);
    }
  }
  return feet.type(2);
}

TEST(ContactForceFdi, AGainWhosePadWentToItsAirLevelIsNotEndedByTheResidualsStep) {
  // After the guard the residual has stepped by -250 N, the end a gain of k = 2 at 1000 N predicts
  // (-(1 - 1/k) 1000 / k). But pad 2 reads 0 by then: its load left, and a gain's error left with
  // it, ended or not. It stays a gain (switched off, the rule lets the step re-admit it).
  EXPECT_EQ(gain_after_its_load_left_in_another_foots_guard(), FaultType::gain);
}

// The first channel other than `pad` that is flagged, -1 if none.
int other_flagged(const Feet& feet, std::size_t pad) {
  for (std::size_t j = 0; j < kChannels; ++j) {
    if (j != pad && feet.type(j) != FaultType::none) return static_cast<int>(j);
  }
  return -1;
}

// Both soles' loads as read (left pads 0-3, right pads 4-7); returns their sum, F_z.
double read_soles(Feet& feet, const std::array<double, 4>& left, const std::array<double, 4>& right) {
  double sum = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    feet.measured[i] = left[i];
    feet.measured[4 + i] = right[i];
    sum += left[i] + right[i];
  }
  return sum;
}

// A foot's four pads carrying `share` of an 1100 N robot on a plane (the CoP a little forward and
// to the left), each with a small deterministic noise of its own (under 0.5 N), so that the
// sole's plane relation has a fault-free spread to be judged against.
std::array<double, 4> sole_loads(int k, double share, std::size_t foot) {
  std::array<double, 4> load{};
  for (std::size_t i = 0; i < 4; ++i) {
    const double x = i < 2 ? 1.0 : -1.0, y = i % 2 == 0 ? 1.0 : -1.0;
    const double noise = 0.5 * std::sin(k * (1.3 + 0.7 * static_cast<double>(i + 4 * foot)));
    load[i] = share * (1100.0 / 4.0 + 20.0 * x + 10.0 * y) + (share > 0.0 ? noise : 0.0);
  }
  return load;
}

TEST(ContactForceFdi, AGainHeldAsAnOffsetIsNoEndAndItsNeighboursNoOnsetsWhereTheOtherFootsLandingMovesTheirLoads) {
  // The right foot alone on the ground, pad 4 (its front-left pad, 305 N) reading 1.5 times its
  // load from tick 2000: raised as an offset of 152.5 N. The left foot lands on tick 2300 and
  // takes half the weight on that tick (a fast handover, as the simulated 48 kg biped's landings
  // are). Every right pad steps down by half its load, pad 4 by 0.75 of it. Inside the landing's
  // guard the right sole's plane judges those steps, and the plane moved: pad 4's error (k - 1) L
  // halved with its load. Read as an offset (as held), that is pad 4 stepping back by about its
  // offset and its neighbours stepping by their loads: the plane's verdict re-admitted pad 4 on
  // tick 2309 (measured with the rule off). Read through the gain its onset implies, pad 4's
  // step explains the plane's: no verdict. The load's move (152.5 N) is under the offset-or-gain test's
  // 2 sum_threshold_N (160 N), so the pad stays an offset; it must stay flagged, and nobody else be.
  auto p = suralp();
  p.points = kSuralpSole;
  Feet feet(p, 1e-3);
  for (int k = 0; k < 2600; ++k) {
    const bool landed = k >= 2300;
    feet.left_foot_at(landed ? 0.0 : 0.03);
    const double right_share = landed ? 0.5 : 1.0;
    const auto right = sole_loads(k, right_share, 1);
    const auto left = sole_loads(k, 1.0 - right_share, 0);
    const double sum = read_soles(feet, left, right);
    if (k >= 2000) feet.measured[4] += 0.5 * right[0];
    feet.step(sum);
    if (k >= 2015) {
      ASSERT_NE(feet.type(4), FaultType::none) << "tick " << k;
    }
    ASSERT_EQ(other_flagged(feet, 4), -1) << "tick " << k;
  }
}

TEST(ContactForceFdi, AnOffsetThatMayBeAGainIsNotEndedByItsReadingsStepToItsAirLevel) {
  // Both feet down, pad 4 carrying 150 N and reading 1.5 times its load from tick 2000: raised as
  // an offset of 75 N. From tick 2300 its foot rolls off: its other pads unload to 0 and lift by
  // tick 2400 while pad 4 unloads to 100 N, and pad 4 leaves last, over ticks 2400-2405 (20 N a
  // tick, its reading 30 N), the left foot taking the load smoothly. Its first step (-30 N)
  // starts a jump group, and the residual's step over the window (the gain's error leaving with
  // the load) confirms it: taken as the offset's step back (|-30 + 75| within 0.4 x 75 plus the
  // confirmation step), the pad was re-admitted on tick 2410 (measured with the rule off).
  // But a gain reads 0 in the air too: a step to the air level is the load leaving. The load's
  // move (150 N) is under the offset-or-gain test's 2 sum_threshold_N (160 N); the air test then
  // sees zero in the air and takes the onset's gain.
  auto p = suralp();
  p.points = kSuralpSole;
  Feet feet(p, 1e-3);
  for (int k = 0; k < 2700; ++k) {
    const double roll = std::clamp((k - 2300) / 100.0, 0.0, 1.0);  // the heel and pad 5 unloading
    const double toe = k < 2400 ? 150.0 - 50.0 * roll : std::max(0.0, 100.0 - 20.0 * (k - 2400));
    const std::array<double, 4> right = {toe, 140.0 * (1.0 - roll), 130.0 * (1.0 - roll), 120.0 * (1.0 - roll)};
    const double right_sum = right[0] + right[1] + right[2] + right[3];
    double sum = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      const double noise = 0.5 * std::sin(k * (1.3 + 0.7 * static_cast<double>(i)));
      const double noise_right = right[i] > 0.0 ? 0.5 * std::sin(k * (1.1 + 0.9 * static_cast<double>(i))) : 0.0;
      feet.measured[i] = (1100.0 - right_sum) / 4.0 + noise;
      feet.measured[4 + i] = right[i] + noise_right;
      feet.height[4 + i] = right[i] > 0.0 ? 0.0 : 0.03;
      sum += feet.measured[i] + feet.measured[4 + i];
    }
    if (k >= 2000) feet.measured[4] += 0.5 * right[0];
    feet.step(sum);
    if (k >= 2015) {
      ASSERT_NE(feet.type(4), FaultType::none) << "tick " << k;
    }
    ASSERT_EQ(other_flagged(feet, 4), -1) << "tick " << k;
  }
  EXPECT_EQ(feet.type(4), FaultType::gain);
  EXPECT_NEAR(feet.outs[ContactForceFdi::kFaultEstimate][4], 0.0, 1.0);  // in the air: 0 / k
}

// Both feet down, pad 4 carrying 150 N, +60 N offset from tick 2000 (raised under load: it may be a
// gain x 1.4). Over ticks 2300-2400 its load moves to the left foot; on the ground and unloaded,
// it reads its offset. The offset ends on tick `end` with a step to the air level. Returns the
// tick pad 4 was re-admitted on (-1: not by the trace's end), checking that no other pad is flagged.
int offset_on_an_unloaded_pad_readmitted_at(int end) {
  auto p = suralp();
  p.points = kSuralpSole;
  Feet feet(p, 1e-3);
  int readmitted = -1;
  for (int k = 0; k < end + 200; ++k) {
    const double pad4 = 150.0 * (1.0 - std::clamp((k - 2300) / 100.0, 0.0, 1.0));
    const std::array<double, 4> right = {pad4, 140.0, 130.0, 120.0};
    const double right_sum = right[0] + right[1] + right[2] + right[3];
    double sum = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      feet.measured[i] = (1100.0 - right_sum) / 4.0 + 0.5 * std::sin(k * (1.3 + 0.7 * static_cast<double>(i)));
      feet.measured[4 + i] = right[i] + 0.5 * std::sin(k * (1.1 + 0.9 * static_cast<double>(i)));
      sum += feet.measured[i] + feet.measured[4 + i];
    }
    if (k >= 2000 && k < end) feet.measured[4] += 60.0;
    feet.step(sum);
    if (k >= 2015 && k < end) {
      EXPECT_NE(feet.type(4), FaultType::none) << "tick " << k;
    }
    if (readmitted < 0 && k >= end && feet.type(4) == FaultType::none) readmitted = k;
    EXPECT_EQ(other_flagged(feet, 4), -1) << "tick " << k;
  }
  return readmitted;
}

TEST(ContactForceFdi, AnOffsetThatReadItsSizeOnAnUnloadedPadEndsWithItsStepToTheAirLevel) {
  // Before its end the pad read 60 N on no load: x - b lay on its leave-one-out force, x / k
  // 43 N off it. A gain would have read 0 there, so the step to 0 is the offset's end, re-admitted
  // once the jump window after it is complete (10 ticks). Taking every step to the air level of an
  // offset that may be a gain as its load leaving kept it flagged to the trace's end (measured).
  const int end = 2500;
  EXPECT_EQ(offset_on_an_unloaded_pad_readmitted_at(end), end + 9);
}

// The right foot alone on the ground (sole_loads), pad 4 +80 N from tick 2000 (raised under its
// 305 N: it may be a gain x 1.26); the left foot lands on tick 2300 and takes half the weight over
// 50 ms; the offset ends on tick 2320, inside the landing's guard, while the load still moves.
// Returns the tick pad 4 was re-admitted on (-1: not within 300 ticks of the end), checking
// that no other pad is flagged.
int offset_ending_in_a_landing_readmitted_at() {
  auto p = suralp();
  p.points = kSuralpSole;
  Feet feet(p, 1e-3);
  int readmitted = -1;
  for (int k = 0; k < 2620; ++k) {
    const bool landed = k >= 2300;
    feet.left_foot_at(landed ? 0.0 : 0.03);
    const double right_share = 1.0 - 0.5 * std::clamp((k - 2299) / 50.0, 0.0, 1.0);
    const auto right = sole_loads(k, right_share, 1);
    const auto left = sole_loads(k, 1.0 - right_share, 0);
    const double sum = read_soles(feet, left, right);
    if (k >= 2000 && k < 2320) feet.measured[4] += 80.0;
    feet.step(sum);
    if (readmitted < 0 && k >= 2320 && feet.type(4) == FaultType::none) readmitted = k;
    EXPECT_EQ(other_flagged(feet, 4), -1) << "tick " << k;
  }
  return readmitted;
}

TEST(ContactForceFdi, AnOffsetThatMayBeAGainAndEndsInALandingIsJudgedByItsSolesPlane) {
  // Its step (-80 N) moves the plane by w times it; read through the gain it implies, by
  // w (1 - 1/k) of it less: still beyond the plane's noise, so no load move explains it and the
  // plane's verdict re-admits the pad when the window after the step is complete (9 ticks).
  // Giving no verdict on a foot with such an offset at all re-admitted it only on tick 2501,
  // 0.172 s later (measured).
  EXPECT_EQ(offset_ending_in_a_landing_readmitted_at(), 2320 + 9);
}

}  // namespace
}  // namespace ftsense::biped

namespace ftsense::biped {
namespace {

// A heel landing on a flat foot, as a 180 kg biped's (tools/unseen_walks.py --robot heavy_biped)
// does it, at 1 kHz: both feet on the ground, pad 2 (the left heel) unloaded and reading its zero
// level (0, 1 N alternately) until tick 300, when it takes 60 N and then 3 N more per tick (to
// 150 N, on tick 330) from pad 0, its toe (F_z steady: the trunk IMU does not see load moving along a sole).
// F_z also carries `fz_error` N that no pad reads (the leave-one-out force's error). On each tick
// `bounce(k)` says, the heel lets go for one tick: it reads its zero level and its load is lost
// to the foot's sum (F_z, from the trunk, does not see that either). Returns the first tick and
// channel any test flags, (-1, -1) if none does in 600 ticks; `jitter_from` (if >= 0) adds a
// noise burst of +-20 N to the heel's reading from that tick on, and the heel's flag is then
// returned in `heel`. On a bounce, the toe takes `toe_takes_N` of the heel's load for that tick
// (`toe_keeps`: and keeps it from then on).
template <class Bounce>
std::pair<int, int> heel_landing(double fz_error, Bounce bounce, int jitter_from = -1,
                                 std::vector<FaultType>* heel = nullptr, double toe_takes_N = 0.0,
                                 bool toe_keeps = false) {
  bool toe_took = false;
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 600; ++k) {
    const double alternation = k % 2 == 0 ? 0.0 : 1.0;
    const double heel_load = k < 300 ? 0.0 : std::min(150.0, 60.0 + 3.0 * (k - 300));
    toe_took = toe_took || bounce(k);
    feet.measured[0] = 400.0 - heel_load + alternation + (bounce(k) || (toe_keeps && toe_took) ? toe_takes_N : 0.0);
    feet.measured[1] = 300.0 + alternation;
    feet.measured[2] = (bounce(k) ? 0.0 : heel_load) + alternation;
    if (jitter_from >= 0 && k >= jitter_from) feet.measured[2] += k % 2 == 0 ? 20.0 : -20.0;
    feet.measured[3] = alternation;
    double fz = 700.0 + fz_error;
    for (std::size_t j = 4; j < kChannels; ++j) fz += feet.measured[j] = moving(j, k, 0.0);
    feet.step(fz);
    if (heel != nullptr) heel->push_back(feet.type(2));
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (feet.type(j) != FaultType::none && (heel == nullptr || j != 2)) return {k, static_cast<int>(j)};
    }
  }
  return {-1, -1};
}

TEST(ContactForceFdi, AHeelThatLandsWhereTheLeaveOneOutForceStraysAboveTheSensorsNoiseIsStillALanding) {
  // The leave-one-out force says 16 N where the heel reads 0 (a 180 kg robot's total force
  // error; the sensors' 4 sigma is 8 N): still "no load", within the total force's error bound
  // (sum_threshold_N, 80 N), so the heel's first 60 N is its landing, and its bounce at 69 N three
  // ticks later, inside the landing's ring, is no spike (30 sigma: 60 N). (Before: the landing was
  // not one, and the bounce was a spike on tick 304.)
  const auto flagged = heel_landing(16.0, [](int k) { return k == 303; });
  EXPECT_EQ(flagged, std::make_pair(-1, -1)) << "tick " << flagged.first << ", channel " << flagged.second;
}

TEST(ContactForceFdi, AHeelThatBouncesAfterItsLandingsRingHasDiedOutIsNoSpike) {
  // The heel lands on tick 300 and rises by 3 N a tick (below jump_threshold_N, 20 N: its ring is
  // over by tick 310); carrying 150 N, it lets go for a tick on ticks 340 and 350, 0.04 and 0.05 s
  // after its landing, inside touchdown_guard_s (0.15 s). Its leave-one-out force, 150 N, is beyond
  // "no load" (80 N), so neither return is a new landing; each is a step to its air level and
  // back, its contact made again, no spike. (Before: a spike on tick 341.)
  const auto flagged = heel_landing(0.0, [](int k) { return k == 340 || k == 350; });
  EXPECT_EQ(flagged, std::make_pair(-1, -1)) << "tick " << flagged.first << ", channel " << flagged.second;
  // The same bounce 0.2 s after its landing (past the guard) is a spike, as on any loaded pad.
  const auto late = heel_landing(0.0, [](int k) { return k == 500; });
  EXPECT_EQ(late, std::make_pair(501, 2));
}

TEST(ContactForceFdi, AHeelThatLetsGoForATickWhileItsToeTakesSomeOfItsLoadIsNoSpike) {
  // The bounce of the test above, 0.2 s after the landing (past its guard), while the toe takes
  // 40 N of the heel's 150 N on that tick (a 180 kg biped's heel chatters so, a tick every 7 ms,
  // for 0.15 s after its landing: tools/unseen_walks.py --robot heavy_biped --faults, walk 9). The
  // foot's sum still drops by 110 N (as an impact sheds it), but two pads made opposite one-tick
  // excursions beyond what noise makes on a tick, z sqrt(3/2) sigma_x = 5.71 x 1.22 x 2 N =
  // 14.0 N: load rocked between them, no sensor's spike. (Before: a spike on tick 501, as
  // without the toe.) The toe taking 16 N (an excursion of 15 N: the readings alternate by 1 N)
  // is enough; 14 N (13 N) says nothing: a spike.
  const auto bounce = [](int k) { return k == 500; };
  for (const double taken : {40.0, 16.0}) {
    const auto rocked = heel_landing(0.0, bounce, -1, nullptr, taken);
    EXPECT_EQ(rocked, std::make_pair(-1, -1)) << "toe takes " << taken << " N: tick " << rocked.first << ", channel " << rocked.second;
  }
  EXPECT_EQ(heel_landing(0.0, bounce, -1, nullptr, 14.0), std::make_pair(501, 2));
  // The toe stepping up by 40 N on that tick and staying there (an excursion of 19-20 N, beyond
  // the bar, but a step: it moved by 40 N over the two ticks, twice its excursion) is no load
  // that came back: the heel's excursion is a spike. (A review's finding: the first version took
  // any opposite excursion.) The toe's own step is no jump confirmed (F_z does not see it), so
  // the heel is the first channel flagged.
  EXPECT_EQ(heel_landing(0.0, bounce, -1, nullptr, 40.0, true), std::make_pair(501, 2));
}

TEST(ContactForceFdi, AHeelWhoseContactChattersAsItsFootRollsIsNoNoiseBurst) {
  // From its landing, the heel lets go for a tick every 6 ticks for 0.14 s (the 180 kg biped's
  // outer heel): each dip makes three large second differences, half the ticks, each beside its
  // air level (the noise test's 50-tick window holds 26 of them by tick 354).
  // Not a noise burst, nor spikes. (Before: flagged on tick 354.)
  const auto flagged = heel_landing(0.0, [](int k) { return k >= 300 && k < 440 && (k - 300) % 6 == 5; });
  EXPECT_EQ(flagged, std::make_pair(-1, -1)) << "tick " << flagged.first << ", channel " << flagged.second;
}

TEST(ContactForceFdi, ANoiseBurstThatBeginsInsideItsPadsLandingGuardIsStillOne) {
  // The heel lands on tick 300 with no bounce; from tick 340, inside its landing's guard, its
  // reading jitters +-20 N around its load (never near its air level): a noise burst, flagged on
  // its 27th tick, as the same burst is from tick 500, past the guard (on tick 526).
  std::vector<FaultType> heel;
  const auto flagged = heel_landing(0.0, [](int) { return false; }, 340, &heel);
  EXPECT_EQ(flagged, std::make_pair(-1, -1)) << "tick " << flagged.first << ", channel " << flagged.second;
  ASSERT_EQ(heel.size(), 600u);
  const auto first = std::find(heel.begin(), heel.end(), FaultType::noise);
  ASSERT_NE(first, heel.end());
  EXPECT_EQ(first - heel.begin(), 366);
  heel.clear();
  EXPECT_EQ(heel_landing(0.0, [](int) { return false; }, 500, &heel), std::make_pair(-1, -1));
  ASSERT_EQ(heel.size(), 600u);
  EXPECT_EQ(std::find(heel.begin(), heel.end(), FaultType::noise) - heel.begin(), 526);
  EXPECT_TRUE(std::all_of(heel.begin(), heel.begin() + 340, [](FaultType f) { return f == FaultType::none; }));
}

}  // namespace
}  // namespace ftsense::biped

namespace ftsense::biped {
namespace {

TEST(ContactForceFdi, ALoadedPadsDownwardSpikeClippedAtItsZeroLevelIsASpikeNotALanding) {
  // 1 kHz, both feet flat; pad 2 carries 70 N (its leave-one-out force too: below "no load" for a
  // landing, the total force's error, 80 N) and reads 0 for one tick on tick 400 (a downward spike
  // its driver clips at 0), F_z steady. One tick at the zero level is no unloading: the return
  // is no landing, and the dip is a spike on the next tick. (With the wide bar and no second tick
  // at the zero level asked for: taken as a landing, never flagged.)
  Feet feet(suralp(), 1e-3);
  for (int k = 0; k < 500; ++k) {
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) fz += feet.measured[j] = j == 2 ? 70.0 + (k % 2) : moving(j, k, 0.0);
    if (k == 400) feet.measured[2] = 0.0;
    feet.step(fz);
    ASSERT_EQ(feet.type(2), k >= 401 ? FaultType::spikes : FaultType::none) << "tick " << k;
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 2) {
        ASSERT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
  }
}

// An unloaded pad on the ground (its leave-one-out force 0) reads a noise burst of `std_N` around
// its zero level from tick 300, drawn by std::mt19937(seed 41); returns the tick it is first
// flagged noise (-1: never) and checks no other channel is flagged.
int unloaded_noise_burst_flagged_at(double std_N) {
  Feet feet(suralp(), 1e-3);
  std::mt19937 rng(41);
  std::normal_distribution<double> burst(0.0, std_N);
  for (int k = 0; k < 600; ++k) {
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = j == 2 ? (k % 2) : moving(j, k, 0.0);
    if (k >= 300) feet.measured[2] = burst(rng);
    double fz = 0.0;
    for (std::size_t j = 0; j < kChannels; ++j) fz += j == 2 ? 0.0 : feet.measured[j];
    feet.step(fz);
    for (std::size_t j = 0; j < kChannels; ++j) {
      if (j != 2) {
        EXPECT_EQ(feet.type(j), FaultType::none) << "channel " << j << ", tick " << k;
      }
    }
    if (feet.type(2) == FaultType::noise) return k;
  }
  return -1;
}

TEST(ContactForceFdi, ANoiseBurstOnAnUnloadedPadIsNoContactChatter) {
  // Its readings leave and regain the air level tick after tick, and each return from it is a
  // landing (the pad's leave-one-out force is 0): inside that guard, the noise test would take
  // them for a contact chattering, but half of them lie below the air level, which a contact
  // cannot read. Seed: std::mt19937(41). A 30 N burst is flagged on tick 343 (without the chatter
  // rule at all, 335; with the rule taking any reading at the air level as chatter, never).
  EXPECT_EQ(unloaded_noise_burst_flagged_at(30.0), 343);
}

// The left foot lands on tick 500 with l_foot/p1 unloaded (its share on p2-p4, 400 N each), p1
// held as a gain k_held: its reading was k_held times its load over ticks [100, 300), in stance,
// raised a gain there, and the fault ended in the air (ticks 300-500), where p1 read 0 either way. On tick 800 p1 takes 170 N from its
// air level while p2 +100, p3 -100 and p4 -140 N step with it (a heel rolled onto late), and from
// tick 600 the total force reads `bias` N more than the pads carry (its error; a pad at its air
// level then has a leave-one-out force of that much, so its step is no pad landing). Returns the
// first tick from 800 on where p1 is no longer a gain (-1: none by tick 1500), and counts in
// `others` the ticks x channels other than p1 flagged.
int held_gain_takes_load_cleared_at(double k_held, double bias, int& others) {
  Feet feet(suralp(), 1e-3);
  int cleared = -1;
  others = 0;
  for (int k = 0; k < 1500; ++k) {
    const bool lifted = k >= 300 && k < 500;
    feet.left_foot_at(lifted ? 0.1 : 0.0);
    const double load = lifted ? 0.0 : k < 300 ? 200.0 : 300.0;
    for (std::size_t j = 0; j < kChannels; ++j) feet.measured[j] = j < 4 ? load + (k % 2) : moving(j, k, 0.0);
    if (k >= 500) {
      for (std::size_t j = 1; j < 4; ++j) feet.measured[j] += 100.0;
      feet.measured[0] = k % 2;
    }
    if (k >= 800) {
      feet.measured[0] += 170.0;
      feet.measured[1] += 100.0;
      feet.measured[2] -= 100.0;
      feet.measured[3] -= 140.0;
    }
    double truth = 0.0;
    for (double x : feet.measured) truth += x;
    if (k >= 100 && k < 300) feet.measured[0] *= k_held;
    feet.step(truth + (k >= 600 ? bias : 0.0));
    if (k == 499) {
      EXPECT_EQ(feet.type(0), FaultType::gain) << "k_held " << k_held;
    }
    if (k >= 800 && cleared < 0 && feet.type(0) != FaultType::gain) cleared = k;
    for (std::size_t j = 1; j < kChannels; ++j) others += feet.type(j) != FaultType::none ? 1 : 0;
  }
  return cleared;
}

TEST(ContactForceFdi, AHeldGainThatTakesItsLoadFromItsAirLevelBesideItsNeighboursStepsNamesNoOnset) {
  // Its correction x / k errs by (1/k - 1) 170 N once it is loaded, if the gain ended in the air
  // (it read its air level there either way), and the residual steps by that with the group of
  // the four steps: one fault's end, or three healthy sensors' onsets. The fewer faults: no
  // group is formed; the stance comparison ends the gain. Before (2026-12-06), p2-p4 were named
  // offsets on tick 809 for k 0.6 and 2.0, and p1 stayed a gain.
  for (const double k_held : {0.6, 2.0}) {
    int others = 0;
    const int cleared = held_gain_takes_load_cleared_at(k_held, 20.0, others);
    std::printf("held gain k %.1f, ended in the air: dropped at tick %d; others flagged %d ticks\n", k_held, cleared,
                others);
    EXPECT_EQ(others, 0) << "k_held " << k_held;
    EXPECT_GE(cleared, 800) << "k_held " << k_held;
    EXPECT_LE(cleared, 800 + 50) << "k_held " << k_held;  // within clear_s of its load
  }
}

}  // namespace
}  // namespace ftsense::biped
