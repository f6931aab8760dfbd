#include "ftsense/sim/sensor_models.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ftsense::sim {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

Rng::Rng(std::uint64_t seed, std::uint64_t stream)
    : eng_(splitmix64(splitmix64(seed) ^ splitmix64(stream + 0x5851F42D4C957F2DULL))) {}

double Rng::uniform() { return static_cast<double>(eng_() >> 11) * 0x1.0p-53; }

double Rng::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
  const double u2 = uniform();
  const double rad = std::sqrt(-2.0 * std::log(u1));
  const double ang = 2.0 * std::numbers::pi * u2;
  spare_ = rad * std::sin(ang);
  has_spare_ = true;
  return rad * std::cos(ang);
}

ForceChannelModel::ForceChannelModel(int channel, double noise_std, std::vector<FaultSpec> faults,
                                     double dt, std::uint64_t seed, double sample_period, double resolution,
                                     std::optional<double> zero_below)
    : noise_std_(noise_std),
      dt_(dt),
      sample_period_(sample_period > 0.0 ? sample_period : dt),
      resolution_(resolution),
      zero_below_(zero_below),
      rng_(seed, 100 + static_cast<std::uint64_t>(channel)) {
  std::uint64_t stream = 1000 + 100 * static_cast<std::uint64_t>(channel);
  std::sort(faults.begin(), faults.end(),
            [](const FaultSpec& a, const FaultSpec& b) { return a.start_s < b.start_s; });
  for (auto& f : faults) {
    const auto start = static_cast<std::int64_t>(std::llround(f.start_s / dt));
    const std::int64_t end = f.end_s ? static_cast<std::int64_t>(std::llround(*f.end_s / dt))
                                     : std::numeric_limits<std::int64_t>::max();
    faults_.push_back(Active{f, start, end, FaultState{Rng(seed, stream++), 0.0, false}});
  }
}

double apply_fault(const FaultSpec& f, double elapsed_s, double tick_s, double y,
                   std::optional<double> previous, FaultState& state) {
  switch (f.type) {
    case FaultType::offset: return y + f.offset_N;
    case FaultType::drift: return y + f.slope_N_s * elapsed_s;
    case FaultType::frozen:
      if (!state.frozen_set) {
        state.frozen_value = f.value_N ? *f.value_N : previous.value_or(y);
        state.frozen_set = true;
      }
      return f.std_N > 0.0 ? state.frozen_value + f.std_N * state.rng.normal() : state.frozen_value;
    case FaultType::gain: return y * f.gain;
    case FaultType::noise: return y + f.std_N * state.rng.normal();
    case FaultType::spikes:
      if (state.rng.uniform() < f.rate_hz * tick_s) y += (state.rng.uniform() < 0.5 ? -1.0 : 1.0) * f.amplitude_N;
      return y;
    case FaultType::invalid: return std::numeric_limits<double>::quiet_NaN();
    case FaultType::saturation: return std::clamp(y, f.min_N, f.max_N);
    case FaultType::none:
    case FaultType::unclassified: break;  // not sensor models: no scenario names them
  }
  return y;
}

ForceChannelModel::Output ForceChannelModel::step(std::int64_t k, double true_force) {
  double y = true_force + (noise_std_ > 0.0 ? noise_std_ * rng_.normal() : 0.0);
  FaultType code = FaultType::none;
  for (auto& a : faults_) {
    if (k < a.start_tick || k >= a.end_tick) continue;
    code = a.spec.type;
    y = apply_fault(a.spec, static_cast<double>(k - a.start_tick) * dt_, sample_period_, y,
                    has_last_ ? std::optional<double>(last_output_) : std::nullopt, a.state);
    break;  // faults on one channel never overlap (checked when loading the scenario)
  }
  // + 0.0 turns the -0 of a small negative reading into 0 (printed "0", not "-0").
  if (resolution_ > 0.0 && std::isfinite(y)) y = resolution_ * std::round(y / resolution_) + 0.0;
  // The driver clamps what the ADC gives it (NaN compares false and stays NaN).
  if (zero_below_ && y < *zero_below_) y = 0.0;
  last_output_ = y;
  has_last_ = true;
  return {y, code};
}

}  // namespace ftsense::sim
