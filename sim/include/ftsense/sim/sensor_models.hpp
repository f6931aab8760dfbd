#pragma once
// Sensor noise and fault injection for the simulated logs.
//
// Random numbers: std::mt19937_64 (its output sequence is fixed by the C++ standard), uniform
// u = (x >> 11) 2^-53 and normals by Box-Muller, both written here, so a (scenario, seed) pair
// gives the same numbers with any standard library. Every channel has its own stream seeded
// from (seed, stream id) through splitmix64, so adding a fault on one channel leaves the noise
// of every other channel unchanged.
//
// Force channel, per tick k (time t_k = k dt), true normal force N:
//   y = N + sigma n_k                     (sensor noise, n_k ~ N(0,1))
//   y = fault(y) if a fault is active on the channel (t_start <= t < t_end), one model per
//   sensor fault type of include/ftsense/fault_type.hpp (every type but none and unclassified):
//     offset      y + offset_N
//     drift       y + slope_N_s (t - t_start)
//     frozen      value_N, or (no value given) the channel's output at the tick before t_start,
//                 plus std_N m_k (0: an exact repeat; > 0: a frozen output that still carries
//                 electrical noise, m_k ~ N(0,1) from the fault's stream)
//     gain        gain y
//     noise       y + std_N m_k            (burst noise, m_k ~ N(0,1) from the fault's stream)
//     spikes      y + s_k amplitude_N with probability rate_hz dt per tick, s_k = +-1 equally
//     invalid     NaN (dropout)
//     saturation  clamp(y, min_N, max_N)
//   y = q round(y / q) with the resolution q > 0 (an ADC quantises whatever reaches it, faults
//   included; NaN stays NaN);
//   y = 0 if y < z, with `zero_below` z given: the zero clamp of a driver that reports an unloaded
//   foot as exactly 0 N (a foot in the air reads exact zeros but for noise above z; a negative
//   reading, even a fault's, reads 0).
#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/fault_type.hpp"

namespace ftsense::sim {

[[nodiscard]] std::uint64_t splitmix64(std::uint64_t x);

/// Seeded generator with a portable uniform and normal sampler.
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream);
  [[nodiscard]] double uniform();  ///< in [0, 1)
  [[nodiscard]] double normal();   ///< standard normal (Box-Muller, pairs cached)

 private:
  std::mt19937_64 eng_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

/// Force channels of the biped: 0..3 = l_foot/p1..p4, 4..7 = r_foot/p1..p4.
inline constexpr std::array<std::string_view, 8> kForceChannels = {
    "l_foot/p1", "l_foot/p2", "l_foot/p3", "l_foot/p4",
    "r_foot/p1", "r_foot/p2", "r_foot/p3", "r_foot/p4"};
/// Force channels of the quadruped, one per foot, in kQuadrupedLegs order (lf, rf, lh, rh).
inline constexpr std::array<std::string_view, 4> kQuadrupedForceChannels = {"lf_foot", "rf_foot", "lh_foot",
                                                                            "rh_foot"};

struct FaultSpec {
  int channel = 0;  ///< index into the simulated robot's channel list (kForceChannels, kQuadrupedForceChannels)
  FaultType type = FaultType::offset;
  double start_s = 0.0;
  std::optional<double> end_s;     ///< absent: until the end
  double offset_N = 0.0;           ///< offset
  double slope_N_s = 0.0;          ///< drift
  std::optional<double> value_N;   ///< frozen; absent: last value
  double gain = 1.0;               ///< gain
  double std_N = 0.0;              ///< noise; frozen: the noise it keeps
  double rate_hz = 0.0;            ///< spikes
  double amplitude_N = 0.0;        ///< spikes
  double min_N = -1e300;           ///< saturation
  double max_N = 1e300;            ///< saturation
};

/// Default noise of the quadruped's foot force sensors (the biped's is SensorParams'): 0.5 N is
/// 0.4 % of the 13 kg robot's weight, as 2 N is 0.2 % of the 114 kg biped's for one of 8 pads.
inline constexpr double kQuadrupedForceNoiseStdN = 0.5;

struct SensorParams {
  double force_noise_std_N = 2.0;
  double force_resolution_N = 0.0;  ///< quantisation step of the force readings; 0: none
  std::optional<double> force_zero_below_N;  ///< readings below this read exactly 0; absent: none
  double acc_noise_std_m_s2 = 0.05;
  std::array<double, 3> acc_bias_m_s2 = {0.02, -0.015, 0.03};
  double gyro_noise_std_rad_s = 0.002;
  std::array<double, 3> gyro_bias_rad_s = {0.001, -0.0008, 0.0005};
  double encoder_noise_std_rad = 1e-4;
  double base_rpy_noise_std_rad = 0.0;
  /// A fault of the IMU's accelerometer (the virtual sensor's own input): a step offset added
  /// to the specific force [m/s^2] from start_s until end_s (absent: the end). Disabled when
  /// start_s is absent.
  std::optional<double> acc_fault_start_s;
  std::optional<double> acc_fault_end_s;
  std::array<double, 3> acc_fault_offset_m_s2 = {0.0, 0.0, 0.0};
};

/// What a fault model keeps between samples: its own random stream (noise bursts, spikes) and the
/// value a frozen channel holds.
struct FaultState {
  Rng rng;
  double frozen_value = 0.0;
  bool frozen_set = false;
};

/// The fault models of this header applied to one sample y of an active fault: `elapsed_s` after
/// its start, `tick_s` the sample period (a spike occurs with probability rate_hz tick_s),
/// `previous` the channel's output the sample before (frozen without value_N holds it; none: y).
/// Shared by the simulator and `ftsense inject` (faults on a recorded log).
[[nodiscard]] double apply_fault(const FaultSpec& f, double elapsed_s, double tick_s, double y,
                                 std::optional<double> previous, FaultState& state);

/// One force channel: noise plus the faults scheduled on it (non-overlapping in time).
class ForceChannelModel {
 public:
  /// `dt` is the simulation tick (k counts them); `sample_period` the sensor's (a multiple of dt:
  /// step is then called every sample_period / dt ticks); `resolution` the quantisation step;
  /// `zero_below` the driver's zero clamp (none: no clamp).
  ForceChannelModel(int channel, double noise_std, std::vector<FaultSpec> faults, double dt,
                    std::uint64_t seed, double sample_period = 0.0, double resolution = 0.0,
                    std::optional<double> zero_below = std::nullopt);
  struct Output {
    double value;
    FaultType fault;
  };
  /// Measured value at tick k from the true force.
  Output step(std::int64_t k, double true_force);

 private:
  struct Active {
    FaultSpec spec;
    std::int64_t start_tick;
    std::int64_t end_tick;  // exclusive; INT64_MAX if open
    FaultState state;
  };
  double noise_std_;
  double dt_;
  double sample_period_;
  double resolution_;
  std::optional<double> zero_below_;
  Rng rng_;
  std::vector<Active> faults_;
  double last_output_ = 0.0;
  bool has_last_ = false;
};

}  // namespace ftsense::sim
