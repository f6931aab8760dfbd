#pragma once
// What `ftsense calibrate` measures on fault-free logs for a plugin: the plugin lists the
// parameters that are statistics of its inputs (a detector's noise level and centre, a
// classifier's noise density), and calibrate runs the pipeline over the logs, measures them per
// channel after the pipeline's warm-up and writes them to the calibration file that
// `ftsense run --thresholds` applies. A plugin opts in with
//
//   static constexpr auto calibrated_params = std::to_array<ftsense::CalibratedParam>({
//       {"noise_std", "residual", ftsense::FaultFreeStatistic::standard_deviation}});
//
// Statistics of the fault-free samples r_k of an input (or of input - minus_input), per channel:
//   centre              mean(r)
//   standard_deviation  sqrt(mean((r - centre)^2))
//   rms                 sqrt(mean(r^2))
//   correlation_time    the e-folding time of the autocorrelation (generic/residual_statistics.hpp:
//                       -T / ln(rho1) for a first-order process, the lag where rho falls to 1/e
//                       for a smooth one; 0 when rho1 <= 0)
//   noise_density       q = sqrt(mean(n_i T m_i^2)), m_i the mean of the n_i finite samples of r
//                       in consecutive windows of w = kNoiseDensityWindowS seconds (n_i T = w when
//                       whole): the mean of r over w seconds has standard deviation q / sqrt(w)
//                       [unit sqrt(s)] (generic/noise_density.hpp)
//   tick_noise          the white noise of a reading that moves: median(|d2|) / (0.67449 sqrt(6)),
//                       d2 the second difference; for a quantised reading, from the share of
//                       tick-to-tick changes below half a step, from the binned d2 less q^2 / 12
//                       above (generic/tick_noise.hpp)
//   resolution          the quantisation step q of a reading: the lattice its changes lie on, 0
//                       when continuous (generic/tick_noise.hpp)
//   window_step         how much r steps between two consecutive windows of W = round(10 ms / T)
//                       ticks: median(|mean after - mean before|) / 0.67449
//                       (generic/window_step_noise.hpp)
//   guard_step          how much r steps across a guard (the ticks on which the input named by
//                       `guard_input` is nonzero): the mean of W finite unguarded ticks after it
//                       less that of the W before it, median(|.|) / 0.67449 (generic/guard_step_noise.hpp)
//
// A guard_step of 0 (a log without guards, or none the signal moved across) is written as 0 with a
// warning: for step_isolator's guard_step_std, 0 means steps inside a guard are not judged.
// A parameter is written as its plugin's schema takes it: a list of one value per channel, or,
// for a parameter of one number (a correlation time, a noise level every channel shares), the
// largest over the channels. Largest is the side on which no channel's healthy samples exceed
// what the plugin assumes, so only spreads, correlation times and resolutions may be one number
// (the plugin contract test checks it); a centre is always per channel.

#include <string_view>

namespace ftsense {

enum class FaultFreeStatistic { centre, standard_deviation, rms, correlation_time, noise_density, tick_noise,
                                resolution, window_step, guard_step };

// The window of the noise-density statistic: long against a stride or a gait cycle (whose
// periodic error averages out over it), short against the minutes of a calibration log.
inline constexpr double kNoiseDensityWindowS = 2.0;

struct CalibratedParam {
  std::string_view param;               // the parameter written (a list per channel, or one number: above)
  std::string_view input;               // the input port whose fault-free samples are measured
  FaultFreeStatistic statistic;
  std::string_view minus_input = {};    // when set, the samples are input - minus_input
  std::string_view guard_input = {};    // guard_step only: the input whose nonzero ticks are the guards
};

}  // namespace ftsense
