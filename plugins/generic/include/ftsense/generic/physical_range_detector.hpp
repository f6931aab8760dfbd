#pragma once
// A reading the measured quantity cannot take, per channel, judged on its own tick.
//
// Sensor model (unit U of the reading): x = s + n + quantisation, n white with standard
// deviation sigma (`noise_std`), quantised in steps of q (`resolution`, 0: none), and the
// quantity s within what the physics allows, [floor_j, ceiling_j] (`floor`, `ceiling`: a force
// pad that is pressed, never pulled, has floor 0 N; either may be left out). Channel j is flagged
// on tick t when
//
//   x_j < floor_j - b_j   or   x_j > ceiling_j + b_j,     b_j = z m sigma_j + q_j / 2,
//
// z = Phi^-1(1 - alpha / 2), alpha = T / false_alarm_interval_s (a healthy reading at a bound
// crosses it with chance alpha / 2 per tick: false_alarm_target.hpp), m = `noise_margin` (a
// healthy noise known within a factor m, as signal_validator takes it). Units: floor, ceiling,
// sigma and q in U.
//
// What it finds: a sign flip of a loaded pad (it reads -L), a negative offset larger than b, a
// gain or an offset that carries a reading beyond what the structure can bear. It says the
// reading is wrong, not how: its type is unclassified, for fault_classifier to type from the
// channel's leave-one-out force once an isolator's merge passes it on. Why not a validator's
// limit: signal_validator's lower_limit and upper_limit are where a sensor clips (a reading AT
// the limit, typed saturation); this is where the quantity ends, and a reading beyond it by more
// than its noise cannot be a load. The flag lasts the ticks beyond only: a sign flip of a pad
// that lifts reads near zero again, and is judged by the other relations there.
// A non-finite reading is not flagged (signal_validator's invalid test is for it).
// Allocation-free per tick; O(channels).

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/calibration.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class PhysicalRangeDetector {
 public:
  static constexpr std::string_view name = "physical_range_detector";
  static constexpr std::string_view summary =
      "flags a reading beyond what the measured quantity can take (a pressed pad's floor of 0), by more than "
      "its noise allows at a false-alarm target";
  static constexpr std::string_view example_params = R"([{"floor": [0.0]}, {"floor": [0.0], "ceiling": [3000.0]}])";

  // `ftsense calibrate` measures each reading's white noise and quantisation step (tick_noise.hpp).
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
  });

  struct Params {
    std::vector<double> floor{};
    std::vector<double> ceiling{};
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    double noise_margin = 1.5;
    double false_alarm_interval_s = 86400.0;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kSignal };
  enum Output : std::size_t { kFault, kFaultType };

  PhysicalRangeDetector(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

  // The flags' bounds, floor_j - b_j and ceiling_j + b_j (-inf, +inf where none is given).
  [[nodiscard]] double lowest(std::size_t j) const noexcept { return lowest_[j]; }
  [[nodiscard]] double highest(std::size_t j) const noexcept { return highest_[j]; }

 private:
  Ports ports_;
  std::vector<double> lowest_, highest_;
};

}  // namespace ftsense::generic
