#pragma once
// Isolation of a reading stuck at a load its channel no longer carries: the one loaded channel
// whose reading stood still while the shared sum residual moved.
//
// Model. The readings x_i of group G sum to a reference R (input `sum_residual`,
// e = sum_G x - R, sum_constraint_residual's). A healthy load that moves moves its reading with
// it, and R follows the group's total, so e stays. A reading stuck at c while its load L_j(t)
// moves makes e = c - L_j(t) + e_0: e moves by what the load left, and x_j does not. On block
// means (blocks of b = `block_s`), at every block's end while the group's alarm is up (any of
// its channels' input `alarm`), over the span of K + 1 blocks (K b = `span_s`) that ended a block
// before, with D s = s(the span's last block) - s(its first block):
//
//   moved      |D e| >= z_b sqrt(2) q / sqrt(b)  (beyond what two block means of fault-free e
//              differ by: q its noise density, `residual_noise_density`, measured by `ftsense
//              calibrate`; z_b the two-sided normal quantile at alpha = b / false_alarm_interval_s)
//   still      |D x_j| < follow_ratio |D e|
//   loaded     channel j could carry load (input `loadable`) and read above
//              floor + z m sigma_j + q_j / 2 on every tick of the span (a pad at its air level is
//              unread_load_isolator's), and its load, were it stuck, x_j - D e, is at least
//              floor - (z m sigma_j + q_j / 2) (a stuck pad cannot carry less than nothing)
//   unflagged  no channel of the group was flagged (input `flagged`, the tick before) within the
//              span or the block after it: a fault already found (a gain, a clip) moves e by its
//              own load's course, and a step of another reading (an offset's onset), which moves
//              e as a stuck load would, is named by the step isolators within a few ticks
//
// The one channel that is still and loaded, with e moved and the group unflagged, is named frozen
// (output `fault` 1, `fault_type` frozen; two or more: nobody, they cannot be told apart). The
// name holds while the group's alarm does and drops with it; stuck_hold downstream keeps a frozen
// channel flagged until its own reading moves. z m sigma + q / 2 is quantity_bounds.hpp's margin,
// sigma and q the readings' noise and quantisation step (`ftsense calibrate`), m = `noise_margin`,
// z at one false alarm per `false_alarm_interval_s` a tick.
//
// Known limits: a still reading on a loaded foot whose load stays while another reading's
// unflagged fault moves e slowly (a drift below the step's reach) is taken as stuck once e has
// moved beyond the bound and the span; a stuck reading whose load stays is not seen by anything.
// Units: any; e and x share one. Allocation-free per tick; O(g) at a block's end.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/calibration.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class StillReadingIsolator {
 public:
  static constexpr std::string_view name = "still_reading_isolator";
  static constexpr std::string_view summary =
      "names frozen the one loaded channel whose reading stood still while the shared sum residual moved";
  static constexpr std::string_view example_params = R"([{"residual_noise_density": [1.0]}])";

  // `ftsense calibrate` measures the noise density of the fault-free sum residual and each
  // reading's white noise and quantisation step.
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"residual_noise_density", "sum_residual", FaultFreeStatistic::noise_density},
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
  });

  struct Params {
    int group_size = 0;
    std::vector<double> residual_noise_density{1.0};
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    std::vector<double> floor{0.0};
    double block_s = 0.05;
    double span_s = 0.2;
    double follow_ratio = 0.25;
    double noise_margin = 1.5;
    double false_alarm_interval_s = 86400.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kSignal, kSumResidual, kAlarm, kLoadable, kFlagged };
  enum Output : std::size_t { kFault, kFaultType };

  StillReadingIsolator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // |D e| a move must reach, per group [U].
  [[nodiscard]] double move_bound(std::size_t group) const noexcept { return move_bound_[group]; }

 private:
  void judge(std::size_t group) noexcept;

  Ports ports_;
  std::size_t channels_ = 0, group_size_ = 0, groups_ = 0;
  int ticks_per_block_ = 1;
  std::size_t ring_ = 3;  // K + 2 blocks: the span and the block after it
  double follow_ratio_ = 0.25;
  std::vector<double> move_bound_;    // per group
  std::vector<double> loaded_above_;  // per channel: floor + margin
  std::vector<double> margin_;        // per channel: z m sigma + q / 2
  std::vector<double> floor_;         // per channel
  // The block being filled.
  std::vector<double> sum_e_, sum_x_;
  std::vector<int> ticks_e_, ticks_x_;
  std::vector<char> loaded_now_;   // per channel: loadable and above loaded_above_ on every tick so far
  std::vector<char> flagged_now_;  // per group: a channel flagged on a tick so far
  int tick_in_block_ = 0;
  // Rings of ring_ blocks: [group * ring_ + slot], [channel * ring_ + slot].
  std::vector<double> block_e_, block_x_;
  std::vector<char> block_loaded_, block_flagged_;
  std::size_t blocks_ = 0;
  std::vector<long> named_;  // per group: the channel in the group, -1 none
};

}  // namespace ftsense::generic
