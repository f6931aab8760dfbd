#pragma once
// Isolation of a sensor that reads nothing of a load it carries: a foot's pad dead at its air
// level through a landing, among pads whose readings share one sum residual.
//
// Why. Channels that sum to a reference (a robot's pads and its total vertical force) share the
// sum residual e = sum x - R: a loaded foot's pads are alike in it, and no tick's level tells them
// apart. But a sensor dead at its air level (a broken cable, a driver that reads its zero) reads
// nothing of its load while the pads beside it, on the same foot, do. So the pad that could be
// carrying the shortfall is the one loadable pad that has read nothing since its foot landed.
//
// Model (unit U of the signal). Channels are grouped twice: `group_size` channels share a sum
// residual e (one input per group) and an alarm (a detector on the group's residuals), and within
// it `contact_group_size` consecutive channels share a contact (a foot's pads: the `loadable`
// input says while they can carry load). A healthy reading is x = L + a_j + n, L >= 0 its load,
// a_j its air level (what it reads unloaded), n white noise of standard deviation sigma
// (`noise_std`) quantised in steps of q (`resolution`). Each reading is low-passed, l_t = l_{t-1} +
// a (x_t - l_{t-1}), a = 1 - exp(-T / tau), tau = `smoothing_s`; while channel j cannot carry
// load, its air level is l (the last value before its landing). Since its landing (the tick its
// loadable input rises), channel j has read load once
//
//   |l - a_j| > q + 2 z m sigma sqrt(a / (2 - a))
//
// (both are low-passes of its noise; z the two-sided normal quantile of alpha = T /
// false_alarm_interval_s, m = `noise_margin`). Channel j is a candidate while the group's alarm
// is up and
//   - its reading has not left the band (either way) since its landing;
//   - every neighbour in its contact group has read load (its reading rose past the band) since
//     its landing: the foot is down flat with weight on it (a point foot has no neighbour, and is
//     never judged here; a sole on its heel has toe pads that read nothing yet either);
//   - its contact group has carried load (some channel of it read load) for `min_loaded_s` since
//     its landing: heel strike to foot flat loads a sole's pads one by one, 0.1 s by default;
//   - the group's alarm was down on some tick since j's landing (the shortfall began after the
//     foot was down: a dead pad shows at its landing, a fault elsewhere raised before it says
//     nothing of this foot);
//   - the low-passed e is below -z s_e (s_e = `residual_noise_std`, e's fault-free RMS: the
//     readings are short of the reference by more than its error, as a load read as nothing leaves
//     them), and it has not been above +z s_e since the contact group carried load (a pad read as
//     nothing only takes load away: a sum over its reference is another fault's, a noise burst's).
// The one candidate of a group is named (`fault` 1, `fault_type` frozen), on a tick whose sum
// residual is a number and whose reading is; two or more name nobody. A name then holds while
// the alarm stays up and the channel, still able to carry load, has not left its air level, and
// drops with the first of those that fails (a second candidate does not take it away); the type
// a stuck reading has is for a downstream part (stuck_hold) to keep. The first tick a contact
// carries load counts as one tick of min_loaded_s.
// What it cannot tell: a healthy pad that carries nothing through a stance (a sole rolled on its
// edge) while another fault of the group leaves the readings short, beside neighbours that all
// read load. Allocation-free: per-channel state sized at construction.

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class UnreadLoadIsolator {
 public:
  static constexpr std::string_view name = "unread_load_isolator";
  static constexpr std::string_view summary =
      "names the one loadable channel that read nothing since its contact group landed while the sum falls short";
  static constexpr std::string_view example_params = R"([{}])";

  // `ftsense calibrate` measures each reading's white noise and quantisation step (tick_noise.hpp).
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
      {"residual_noise_std", "sum_residual", FaultFreeStatistic::rms},
  });

  struct Params {
    int group_size = 0;
    int contact_group_size = 0;
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    std::vector<double> residual_noise_std{1.0};
    double smoothing_s = 0.02;
    double min_loaded_s = 0.1;
    double noise_margin = 1.5;
    double false_alarm_interval_s = 86400.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kSignal, kSumResidual, kAlarm, kLoadable };
  enum Output : std::size_t { kFault, kFaultType };

  UnreadLoadIsolator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // q + 2 z m sigma sqrt(a / (2 - a)) for channel j: how far from its air level it reads load.
  [[nodiscard]] double load_band(std::size_t j) const noexcept { return band_[j]; }

 private:
  struct Channel {
    double lp = 0.0;
    bool lp_started = false;
    bool finite_now = false;    // this tick's reading is a number
    double air_level = 0.0;
    bool air_known = false;     // it has been seen unable to carry load
    bool loadable = false;
    std::int64_t foot_loaded_ticks = 0;  // since its landing, ticks its contact group carried load
    bool read_load = false;     // since its landing, its reading rose past the band
    bool moved = false;         // since its landing, its reading left the band either way
    bool clear_since = false;   // the group's alarm was down on some tick since its landing
    bool sum_over = false;      // since its contact carried load, the low-passed e rose above +bound
  };

  [[nodiscard]] bool candidate(std::size_t j, std::size_t group) const noexcept;

  Ports ports_;
  std::size_t channels_ = 0, group_size_ = 0, groups_ = 0, contact_size_ = 0;
  std::vector<double> band_;
  std::vector<double> shortfall_bound_;  // per group: z s_e
  std::vector<Channel> state_;
  std::vector<double> e_lp_;
  std::vector<char> e_started_;
  std::vector<long> named_;  // per group: the channel named, -1 none
  double lp_gain_ = 0.0;
  long min_loaded_ticks_ = 0;
};

}  // namespace ftsense::generic
