#pragma once
// A stuck reading stays flagged while it stays stuck: the re-admission test of a frozen or
// clipped channel is its own reading moving again, not the residual that found it.
//
// Why. A reading frozen at c (or clipped at a ceiling c) is off from its load L by L - c, and
// L passes through c whenever the load moves across it: a foot's pad stuck at 276 N reads its load
// right twice a stance. There the residual x - v crosses zero, the detector on it drops its alarm,
// and an isolator releases the channel; once the load moves on, the residual rises again, but a
// loaded foot's pads share one sum residual and nobody can be named again until the foot lifts. So
// the channel comes back as healthy for most of each stance (on the demo's frozen_noisy walk, a
// pad frozen with its noise was flagged only while its foot was in the air). What does end a
// stuck episode is the reading leaving c: a sensor that works again reads its load, which moves.
//
// Model (unit U of the signal). A stuck reading is x_t = c + n_t, n white with standard deviation
// sigma (`noise_std`: its electrical noise stays when its load is lost) and quantised in steps of q
// (`resolution`). Per channel, from the first tick its input flags it with one of `types` (an
// episode), the part keeps the mean mu of the episode's finite readings (n of them) and, on every
// tick, a first-order low-pass l of the reading (l_t = l_{t-1} + a (x_t - l_{t-1}), a = 1 -
// exp(-T / tau), tau = `smoothing_s`). Stuck, l - mu is noise of standard deviation at most
// sigma (sqrt(a / (2 - a)) + 1 / sqrt(n)) (the sum of the two standard deviations: they are
// correlated) within the quantiser's q / 2, so the reading counts as moved when
//
//   |l - mu| > q / 2 + z m sigma (sqrt(a / (2 - a)) + 1 / sqrt(n)),
//
// z = the two-sided normal quantile of alpha = T / false_alarm_interval_s (a stuck reading's noise
// re-admits it by chance once an interval), m = `noise_margin` (a stuck output's noise is known
// within a factor, as signal_validator takes it).
// A sensor that stuck without its noise (a driver holding its last value) and works again may
// read its load near where it stuck (a pad stuck at its air level, back in the air), but its
// noise comes back. So the reading has also moved when the low-pass v of its squared tick-to-tick
// difference d^2 (d = x_t - x_{t-1}; E d^2 = 2 sigma_s^2 for a noise sigma_s) passes what the
// episode's own mean s of d^2 (over its n differences while the input flagged it) allows:
//
//   v > max(F s / L, 2 (sigma / m)^2 / F),   F = chi^2_nu(1 - alpha/2) / nu, L = chi^2_{n'}(alpha/2) / n',
//
// (the quantiles at the same two-sided z; chi-square by Wilson-Hilferty), nu = (2 - a) / (1.5 a)
// and n' = n / 1.5 the independent draws in v and in s (successive d share a reading: their
// squares correlate by 1/4), L the low end of the episode's own estimate; the second term keeps a
// noiseless stuck reading from being let go by the last bit of its quantiser. Until the episode
// has enough differences for L > 0 (n' above about 12 at z = 5.7), its noise is not known from
// below, and only the level test releases. s is not updated while held: a noise that comes back
// must not raise the bound it is judged against.
//
//   input flags j with a type in `types`      passed on; the episode goes on (mu takes x_t)
//   input flags j with another type           passed on; any episode ends (another fault now)
//   input does not flag j, episode running    held: fault 1 with the episode's type while the
//                                             reading has not moved; the tick it moves, the
//                                             episode ends and the channel is re-admitted
//   else                                      passed on (0)
//
// While held, mu keeps taking the readings (a stuck reading's mean only gets surer; a slow drift
// leaves l behind the mean and is let go). A non-finite reading is no evidence either way: it
// leaves mu and l as they were. The episode's type is the last held type the input gave.
// What it costs: a healthy channel wrongly flagged with a held type stays flagged until its
// reading moves by the bound above (a steadily loaded healthy sensor reads still too: held until
// its load moves). Nothing here names a channel; it only keeps what another part named.
//
// Outputs per channel: fault and fault_type (the input's, or the held flag), held (1 while the
// flag is this part's own, the input's being down), and with `cannot_judge` on, cannot_judge
// (the input's, 0 while held). Allocation-free: per-channel state sized at construction.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/fault_type.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class StuckHold {
 public:
  static constexpr std::string_view name = "stuck_hold";
  static constexpr std::string_view summary =
      "keeps a frozen or clipped channel flagged while its reading stays where it stuck";
  // For the config reference's port table and the schema (plugin.hpp): input cannot_judge is optional.
  static constexpr std::string_view example_params = R"([{}, {"cannot_judge": true}])";

  // `ftsense calibrate` measures each reading's white noise and quantisation step (tick_noise.hpp).
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
  });

  struct Params {
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    std::vector<std::string> types{"frozen"};
    double smoothing_s = 0.05;
    double noise_margin = 1.5;
    double false_alarm_interval_s = 86400.0;
    bool cannot_judge = false;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kSignal, kFault, kFaultType, kCannotJudge };
  enum Output : std::size_t { kHeldFault, kHeldType, kHeld, kHeldCannotJudge };

  StuckHold(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // The moved bound for channel j after n readings of its episode (the header's formula).
  [[nodiscard]] double moved_bound(std::size_t j, double n) const noexcept;
  // The bound on v for channel j, an episode whose n differences have mean square s.
  [[nodiscard]] double noise_bound(std::size_t j, double s, double n) const noexcept;

 private:
  struct Channel {
    double lp = 0.0;        // l: the low-passed reading
    bool lp_started = false;
    double previous = 0.0;  // the last finite reading
    bool has_previous = false;
    double lp_d2 = 0.0;     // v: the low-passed d^2
    bool lp_d2_started = false;
    bool in_episode = false;
    double mean = 0.0;      // mu over the episode's finite readings
    double count = 0.0;     // n
    double d2_mean = 0.0;   // s over the episode's differences
    double d2_count = 0.0;
    double noise_limit = 0.0;     // noise_bound(s, its count), taken when the input lets go
    bool noise_limit_set = false;
    double type_code = 0.0;  // the episode's type
  };

  Ports ports_;
  std::vector<double> half_step_;   // q / 2 per channel
  std::vector<double> noise_scale_;  // z m sigma per channel
  std::vector<double> noise_floor_;  // 2 (sigma / m)^2 / F per channel
  std::vector<Channel> channels_;
  std::array<bool, kFaultTypes.size()> held_type_{};
  double lp_gain_ = 0.0;
  double lp_noise_ = 0.0;  // sqrt(a / (2 - a))
  double z_ = 0.0;
  double noise_ratio_ = 1.0;  // F
  bool cannot_judge_ = false;
};

}  // namespace ftsense::generic
