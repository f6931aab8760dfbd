#pragma once
// What each contact point carries, from the relations its neighbours' loads keep, when its own
// reading stands for nothing: the virtual force a recovery substitutes.
//
// Channels: feet x points_per_foot loads N_j [U, the readings' unit], foot after foot, summing to
// a reference R (the total vertical force). Channel j's load is
//   known    x_j - c_j when j can carry load and its reading stands (c_j the recovery's
//            correction of the tick before, finite, and j not substituted then); 0 when j cannot
//            carry load (off the ground);
//   unknown  otherwise (a substituted or non-finite reading on the ground).
// The virtual value v_i of a channel that can carry load is the unknown loads' estimate
// (unmeasured_contact_loads.hpp) with i taken as unknown too: the least-squares loads under
//   sum      sum_j N_j = R + e_s
//   plane    W^T N_f = e_p for each foot f in full contact (every pad on the ground, every known
//            one reading above b_k), W the relations of the pads' layout `points` [m] (four pads on
//            a rectangle: N_1 - N_2 - N_3 + N_4 = 0 up to scale; empty or one point a foot: none)
// each weighed by its variance, every unknown at least `floor`. With i the only unknown that is
// the sum's leave-one-out value max(floor, R - sum_{j != i} N_j), as sum_constraint_residual's;
// with two unknowns or more on feet in full contact the planes set them apart. Where the
// relations fix what a foot's unknowns carry together but not each (two diagonal pads of a
// rectangle) they share it equally (the minimum-norm answer), each at least `floor`; where they
// do not fix even that (unknowns on two feet and no plane to part them) v_i is not a number:
// an equal share between feet is no measure (cannot judge). v_i = 0 for a channel that cannot
// carry load; NaN for every other while R is not finite (nothing is judged on a guess).
//
// b_k = z m sigma_k + q_k / 2 (quantity_bounds.hpp's margin, as physical_range_detector's: a reading
// within its noise of zero may be a pad that has lifted, off the plane), with sigma, q the
// readings' noise and quantisation step (`ftsense calibrate`), z at one false alarm per
// `false_alarm_interval_s`, m = `noise_margin`.
//
// The relations' variances are measured on the log itself (cumulative mean squares; used from
// 100 samples on, the sum alone before): the sum residual sum_j x_j - R on ticks where no
// channel was flagged (`flagged`, the tick before) and all readings and R are finite; each foot's
// relations on ticks where its pads are all unflagged, finite, on the ground and above b.
//
// Why: sum_constraint_residual's virtual value is not a number once two channels stand for
// nothing while they can carry load (the sum is one equation); a recovery then has only the
// faulty readings. Allocation-free per tick; O(channels) solves of at most channels unknowns.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/calibration.hpp"
#include "ftsense/generic/unmeasured_contact_loads.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class LoadApportioner {
 public:
  static constexpr std::string_view name = "load_apportioner";
  static constexpr std::string_view summary =
      "the virtual load of each contact point from the total force and, on rigid soles, the plane its "
      "foot's loads lie on: substituted channels' loads apportioned where the sum alone cannot";
  static constexpr std::string_view example_params =
      R"([{"points_per_foot": 4, "points": [[0.12, 0.075], [0.12, -0.075], [-0.12, 0.075], [-0.12, -0.075]]}, {"points_per_foot": 1}])";

  // `ftsense calibrate` measures each reading's white noise and quantisation step (tick_noise.hpp).
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std", "signal", FaultFreeStatistic::tick_noise},
      {"resolution", "signal", FaultFreeStatistic::resolution},
  });

  struct Params {
    int points_per_foot = 1;
    std::vector<std::array<double, 2>> points{};
    std::vector<double> floor{0.0};
    std::vector<double> noise_std{1.0};
    std::vector<double> resolution{0.0};
    double noise_margin = 1.5;
    double false_alarm_interval_s = 86400.0;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kSignal, kReference, kLoadable, kCorrection, kSubstituted, kFlagged };
  enum Output : std::size_t { kVirtual };

  LoadApportioner(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept { loads_.reset(); }
  void step(const StepIO& io) noexcept;

  // The bound b_k above which a known pad counts as loaded [U].
  [[nodiscard]] double loaded_above(std::size_t k) const noexcept { return loaded_above_[k]; }
  [[nodiscard]] const UnmeasuredContactLoads& relations() const noexcept { return loads_; }

 private:
  Ports ports_;
  std::size_t points_per_foot_ = 1;
  std::size_t feet_ = 0;
  UnmeasuredContactLoads loads_{{}, 1, 1};
  std::vector<double> floor_;         // per channel
  std::vector<double> loaded_above_;  // per channel, b_k
  // Work space, sized at construction.
  std::vector<double> known_;       // per channel: its load, or NaN when unknown
  std::vector<double> solved_;      // per channel: one solve's loads
  std::vector<char> unknown_;       // per channel: one solve's unknowns
  std::vector<char> plane_usable_;  // per foot: one solve's
};

}  // namespace ftsense::generic
