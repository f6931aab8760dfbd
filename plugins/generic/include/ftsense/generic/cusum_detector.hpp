#pragma once
// Two-sided CUSUM change detector per channel, its threshold set by a false-alarm target.
//
// Model. Fault-free, the residual r_j (any unit) is stationary with centre c_j, standard
// deviation sigma_j and the autocorrelation of a first-order process, rho = exp(-T / tau_c) from
// one tick of period T to the next (tau_c [s] = 0: white; about 1 / (2 pi f_c) after a low-pass
// of cut-off f_c). A fault shifts its mean by at least delta_j (`min_change`). The detector
// whitens the normalised sample z = (r_j - c_j) / sigma_j exactly for that process,
//
//   e = (z - rho z_prev) / sqrt(1 - rho^2)          (white, unit variance when fault-free),
//
// which turns a mean shift mu of z into a shift mu sqrt(w) of e, w = (1 - rho) / (1 + rho)
// (the independent samples per tick), and runs the textbook CUSUM on e with reference value
// k_e = sqrt(w) delta_j / (2 sigma_j):
//
//   S+ = max(0, S+ + e - k_e),   S- = max(0, S- - e - k_e),   raised when S+ or S- >= h,
//
// with h from cusum_design.hpp so that the mean time between false alarms of the two-sided test
// is `false_alarm_interval_s` (2 x that interval, in ticks, per side); when even h = 0 keeps false
// alarms rarer (a change of many noise deviations), h is the least positive, 1e-9: one sample
// beyond k_e raises. A shift mu of z is then
// detected after about (h + 1.166) / (sqrt(w) mu - k_e) ticks: the same time in seconds at any
// rate, since sqrt(w) ~ sqrt(T / (2 tau_c)) and h ~ 1 / sqrt(w) as T shrinks. Without the
// whitening a correlated residual would move S like a smooth curve, not a random walk, and the
// false-alarm interval would miss its target.
//
// Re-admission: while raised, S+ and S- are held at most h, so once the residual is back at
// c_j they fall by k_e per tick and the channel clears when both reach 0, about h / k_e ticks
// after the fault ends, however long it lasted.
//
// A non-finite residual (the reference not ready, a sensor flagged invalid upstream) is not
// judged: S+ and S- hold, the flag holds, `judged` is 0 (a pad's air row holds its flag through
// the stance); the next finite sample only restarts the whitening (z_prev), as does the first
// after reset(). With input `reset` wired, a nonzero finite reset_j (another test's word that the
// change ended, e.g. rejoin_detector's) sets S+ = S- = 0 and drops the flag before the tick is
// judged; the whitening goes on. No flag is raised during the first `warmup_s` after reset()
// (S is held at 0). Types: a raised flag is unclassified (classification
// is another stage's work).

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class CusumDetector {
 public:
  static constexpr std::string_view name = "cusum_detector";
  static constexpr std::string_view summary =
      "two-sided CUSUM per channel with its threshold from a mean time between false alarms";
  // For the config reference's port table and the schema (plugin.hpp): input reset is optional.
  static constexpr std::string_view example_params = R"([{}, {"reset": true}])";

  // `ftsense calibrate` measures the fault-free residual's level, spread and memory.
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "residual", FaultFreeStatistic::standard_deviation},
      {"centers", "residual", FaultFreeStatistic::centre},
      {"correlation_time_s", "residual", FaultFreeStatistic::correlation_time},
  });

  struct Params {
    std::vector<double> noise_std{1.0};
    std::vector<double> min_change{4.0};
    std::vector<double> centers{0.0};
    double correlation_time_s = 0.0;
    double false_alarm_interval_s = 86400.0;
    double warmup_s = 0.0;
    bool reset = false;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kResidual, kReset };
  enum Output : std::size_t { kFault, kFaultType, kStatistic, kDirection, kJudged };

  CusumDetector(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // h of channel j, in units of the whitened sample e.
  [[nodiscard]] double threshold(std::size_t j) const noexcept { return threshold_[j]; }
  // k_e of channel j.
  [[nodiscard]] double reference_value(std::size_t j) const noexcept { return reference_[j]; }
  // w = (1 - rho) / (1 + rho): independent samples per tick.
  [[nodiscard]] double samples_per_tick() const noexcept { return samples_per_tick_; }

 private:
  Ports ports_;
  std::vector<double> inv_std_;
  std::vector<double> reference_;  // k_e of each channel
  std::vector<double> centers_;
  std::vector<double> threshold_;  // h_j
  double samples_per_tick_ = 1.0;
  double rho_ = 0.0;
  double inv_innovation_std_ = 1.0;  // 1 / sqrt(1 - rho^2)
  double sample_period_s_;
  double warmup_s_;
  bool reset_wired_;
  double start_time_s_ = 0.0;
  bool started_ = false;
  std::vector<double> upper_;
  std::vector<double> lower_;
  std::vector<double> previous_z_;
  std::vector<unsigned char> has_previous_;
  std::vector<unsigned char> raised_;
};

}  // namespace ftsense::generic
