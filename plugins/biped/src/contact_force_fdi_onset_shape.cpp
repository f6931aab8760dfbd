// The shape of a fault's onset: the air's levels of each swing and the sum residual's block means, which tell
// a drift that grew through them from an offset that stepped (generic::onset_shape).
#include "ftsense/biped/contact_force_fdi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>

#include "ftsense/generic/onset_shape.hpp"
#include "contact_force_fdi_detail.hpp"

namespace ftsense::biped {

using namespace contact_force_fdi_detail;

std::size_t ContactForceFdi::air_levels_of_window(const Channel& c, double drop_reading, double drop_time,
                                                  std::span<generic::LevelPoint> out) const noexcept {
  // A mean of n readings is off by the readings' sigma^2 / n and by the quantiser's bias, which no
  // n removes where the noise does not dither it: (q / 2) exp(-2 pi^2 sigma_n^2 / q^2), q / 2
  // without noise, and above the first harmonic's amplitude (q / pi) exp(...) that dominates once
  // the noise dithers (0.007 N for 1 N of noise on 2 N steps, 1.1 N on 5 N steps). It is one
  // bias for the window, shared by its two levels: each carries it twice over, so that their
  // mean carries it whole.
  const bool drop = !std::isnan(drop_reading);
  const double u_drop = drop ? drop_time - c.air_origin_s : 0.0;
  const double n = c.airborne_count - (drop ? 1.0 : 0.0);
  if (!(n >= 1.0)) return 0;
  const double sum_x = c.airborne_sum - (drop ? drop_reading : 0.0);
  const double sum_u = c.airborne_u_sum - u_drop;
  const double mean_u = sum_u / n, mean_x = sum_x / n;
  const double suu = c.airborne_uu_sum - (drop ? u_drop * u_drop : 0.0) - n * mean_u * mean_u;
  const double sux = c.airborne_ux_sum - (drop ? u_drop * drop_reading : 0.0) - n * mean_u * mean_x;
  const double bias_sq = quantiser_bias_N_ * quantiser_bias_N_;  // the mean's; a level's is twice it
  const double reading_var = reading_sigma_N_ * reading_sigma_N_;
  const double t_mean = c.air_origin_s + mean_u;
  if (!(n >= 3.0 && suu > 0.0)) {
    out[0] = {t_mean, mean_x, reading_var / n + bias_sq};
    return 1;
  }
  const double slope = sux / suu;
  const double d = std::sqrt(suu / n);
  out[0] = {t_mean - d, mean_x - slope * d, 2.0 * (reading_var / n + bias_sq)};
  out[1] = {t_mean + d, mean_x + slope * d, 2.0 * (reading_var / n + bias_sq)};
  return 2;
}

void ContactForceFdi::close_air_window(Channel& c) noexcept {
  if (c.type != FaultType::none || c.air_window_flagged || c.airborne_count < min_airborne_samples_) return;
  std::array<generic::LevelPoint, 2> levels{};
  const std::size_t count = air_levels_of_window(c, std::numeric_limits<double>::quiet_NaN(), 0.0, levels);
  for (std::size_t i = 0; i < count; ++i) c.air_levels.push(levels[i]);
}

void ContactForceFdi::type_air_onset(Channel& c, double x, double t) noexcept {
  std::array<generic::LevelPoint, generic::LevelHistory::kCapacity + 2> points{};
  const std::size_t healthy = c.air_levels.ordered(points);
  c.air_levels.clear();
  if (healthy == 0) return;
  // This swing's window without the tick's reading (the air's fit takes that one itself).
  const std::size_t m =
      healthy + air_levels_of_window(c, x, t, std::span(points.data() + healthy, 2));
  if (m == healthy) return;
  const generic::OnsetShape shape = generic::onset_shape(std::span(points.data(), m), relation_z_);
  // A ramp that begins within this swing is this swing's alone: a step inside it under
  // jump_threshold_N (one level between, one full) fits that ramp exactly. The swings before
  // must show the fault growing.
  if (!shape.ramp || shape.first_faulty >= healthy) return;
  start_drift_from_levels(c, t, std::span(points.data() + shape.first_faulty, m - shape.first_faulty), 0.0, {});
}

void ContactForceFdi::start_drift_from_levels(Channel& c, double t, std::span<const generic::LevelPoint> history,
                                              double healthy_level,
                                              std::span<const generic::LevelPoint> swing) noexcept {
  // The fit weighs a reading 1: a level counts as the readings its variance is worth.
  const double reading_variance = reading_sigma_N_ * reading_sigma_N_;
  c.type = FaultType::drift;
  c.fit.clear(t);
  for (const generic::LevelPoint& p : history) c.fit.add(p.t_s, p.level - healthy_level, reading_variance / p.variance);
  for (const generic::LevelPoint& p : swing) c.fit.add(p.t_s, p.level, reading_variance / p.variance);
  c.fit_has_air = true;
  c.air_refit = false;
}

void ContactForceFdi::observe_sum_block(double residual, bool usable, bool clean, double t) noexcept {
  if (usable) {
    sum_block_sum_ += residual;
    sum_block_t_sum_ += t;
    ++sum_block_count_;
  }
  sum_block_clean_ = sum_block_clean_ && clean;
  if (++sum_block_ticks_ < sum_block_target_ticks_) return;
  // A block's mean scatters by the reference's error over the block (correlated over a stride, so
  // not sigma^2 / n). It is measured on the blocks' second differences, d = m_k - 2 m_{k-1} +
  // m_{k-2}, of three full blocks in a row in which no channel was flagged: d ~ N(0, 6 v) for
  // independent means of variance v, and the reference's bias, a constant or a ramp in it (an
  // unflagged drift: what type_sum_onset looks for) adds nothing. A step (an unflagged offset)
  // adds to two of them: so v is read from the median of the latest kCapacity d^2, which one step
  // does not move and which forgets (standing and walking scatter differently).
  const bool full = sum_block_clean_ && sum_block_count_ == sum_block_target_ticks_;
  const double mean = sum_block_count_ > 0 ? sum_block_sum_ / sum_block_count_ : 0.0;
  if (full && sum_block_full_run_ >= 2) {
    const double d = mean - 2.0 * sum_block_last_means_[1] + sum_block_last_means_[0];
    sum_block_d2_[sum_block_d2_next_] = d * d;
    sum_block_d2_next_ = (sum_block_d2_next_ + 1) % sum_block_d2_.size();
    sum_block_d2_count_ = std::min(sum_block_d2_count_ + 1, sum_block_d2_.size());
  }
  sum_block_full_run_ = full ? std::min(sum_block_full_run_ + 1, 2) : 0;
  sum_block_last_means_[0] = sum_block_last_means_[1];
  sum_block_last_means_[1] = mean;
  // A block with under half its ticks usable is dropped (its mean is another, shorter average).
  // Its variance is kept relative to a full block's (type_sum_onset scales it by v).
  if (2 * sum_block_count_ >= sum_block_target_ticks_) {
    sum_levels_.push({sum_block_t_sum_ / sum_block_count_, mean,
                      static_cast<double>(sum_block_target_ticks_) / sum_block_count_});
  }
  sum_block_ticks_ = sum_block_count_ = 0;
  sum_block_sum_ = sum_block_t_sum_ = 0.0;
  sum_block_clean_ = true;
}

void ContactForceFdi::type_sum_onset(Channel& c, double x, double t) noexcept {
  const auto variance = sum_block_variance();
  if (!variance || !(c.airborne_count >= 1.0)) return;
  const double block_variance = *variance;
  std::array<generic::LevelPoint, generic::LevelHistory::kCapacity + 1> points{};
  const std::size_t blocks = sum_levels_.ordered(points);
  if (blocks < 3) return;
  for (std::size_t i = 0; i < blocks; ++i) points[i].variance *= block_variance;
  // The blocks alone must rise along a ramp; then the ramp must go on to the level the air reads:
  // the air's mean, at its mean time, joins them as one more level (on the residual's healthy
  // level c, as the blocks' fit gives it: the air test's premise is that a healthy pad reads 0 in
  // the air), and the ramp must still win. A step inside a block leaves c, c + f b, c + b, which a
  // ramp fits exactly for f <= 1/2 (a block is a mean, not its line), but the air then reads c + b, not the
  // ramp's level further on (a review's finding); and the ramp must beat a step inside one block
  // (step_within_a_point_chi2) by z^2 as it beats the plain step: with the step's block partway
  // and one or two full ones after it, the ramp still fits better than the plain step.
  const generic::OnsetShape blocks_shape = generic::onset_shape(std::span(points.data(), blocks), relation_z_);
  if (!blocks_shape.ramp) return;
  const double n = c.airborne_count;
  const double air_mean = c.airborne_sum / n;
  const double air_time = c.air_origin_s + c.airborne_u_sum / n;
  const double reading_variance = reading_sigma_N_ * reading_sigma_N_;
  const double air_variance = reading_variance / n + quantiser_bias_N_ * quantiser_bias_N_;
  if (!(air_time > points[blocks - 1].t_s)) return;
  points[blocks] = {air_time, blocks_shape.healthy_level + air_mean, air_variance};
  const generic::OnsetShape shape = generic::onset_shape(std::span(points.data(), blocks + 1), relation_z_);
  // The ramp must have begun before this swing (the swing's own readings are the air's) and be the
  // channel's fault: of the air's sign, and by this swing's mean time at the level the air reads
  // above 0, within z of the two's noise (a block's and the air mean's).
  if (!shape.ramp || !(shape.onset_s < c.air_origin_s) || shape.first_faulty == 0) return;
  // A block is a mean: a step may fall inside one, and the ramp must beat that shape too.
  if (!(generic::step_within_a_point_chi2(std::span(points.data(), blocks + 1)) - shape.ramp_chi2 >
        relation_z_ * relation_z_)) {
    return;
  }
  const double ramp_level = shape.slope * (air_time - shape.onset_s);
  const double bound = relation_z_ * std::sqrt(block_variance + air_variance);
  if (!(ramp_level * air_mean > 0.0) || !(std::abs(ramp_level - air_mean) <= bound)) return;
  std::size_t ramp_end = shape.first_faulty;  // the ramp's blocks before this swing
  while (ramp_end < blocks && points[ramp_end].t_s < c.air_origin_s) ++ramp_end;
  std::array<generic::LevelPoint, 2> levels{};
  const std::size_t count = air_levels_of_window(c, x, t, levels);
  start_drift_from_levels(c, t, std::span(points.data() + shape.first_faulty, ramp_end - shape.first_faulty),
                          shape.healthy_level, std::span(levels.data(), count));
}

void ContactForceFdi::raise_jump_onset(Channel& c, double jump, double load_before, double t) noexcept {
  c.onset_load = load_before;  // the load the onset jump left (onset_gain)
  c.reads_as_gain = false;
  raise(c, FaultType::offset, t);
  c.fit.clear(t);
  c.fit.add(t, jump, 1.0);
  c.offset = jump;
  c.slope = 0.0;
}

std::optional<double> ContactForceFdi::sum_block_variance() const noexcept {
  // v from fewer second differences is not known well enough to weigh a shape by.
  constexpr std::size_t kMinSecondDifferences = 8;
  // The median of chi-square with 1 degree of freedom: d^2 / (6 v)'s, for d ~ N(0, 6 v).
  constexpr double kChiSquare1Median = 0.45493642311957283;
  if (sum_block_d2_count_ < kMinSecondDifferences) return std::nullopt;
  std::array<double, generic::LevelHistory::kCapacity> d2 = sum_block_d2_;
  const auto middle = d2.begin() + static_cast<std::ptrdiff_t>(sum_block_d2_count_ / 2);
  std::nth_element(d2.begin(), middle, d2.begin() + static_cast<std::ptrdiff_t>(sum_block_d2_count_));
  return *middle / (6.0 * kChiSquare1Median);
}

}  // namespace ftsense::biped
