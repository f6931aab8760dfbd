#pragma once
// A fault's onset shape from its level measured now and then: a ramp (drift) or a step (offset).
//
// Some channels show their fault only at times: a foot's force sensor in the air reads its fault
// and nothing else, but a foot is in the air a third of a stride or less. Each such window gives
// levels y_i [the channel's unit] at times t_i [s] with variances v_i (its mean at the samples'
// mean time, sigma^2 / n_i; or, as contact_force_fdi keeps them, the two uncorrelated levels of
// its least-squares line, which carry its slope too), plus what averaging does not remove (a
// quantiser's bias where the noise is too small to dither it). The caller keeps the healthy
// windows (LevelHistory) and adds the one that shows the fault. Two shapes explain the m points,
// each with three parameters (c the healthy level):
//
//   step (offset):  y_i = c for i < j,  c + b for i >= j                        (j = 0..m-1)
//   ramp (drift):   y_i = c + s max(0, t_i - t0),  t_{j-1} <= t0 <= t_j         (j = 1..m-2)
//                   or, with no healthy point before it (j = 0), a line a + s t through all
//
// each fitted by weighted least squares (w_i = 1 / v_i) at its best j. c is fitted, not taken as
// 0: a sensor's level in the air need not be 0 (the mass of a sole below a load cell). S is a
// fit's chi-square, sum w_i (y_i - model_i)^2 (dimensionless). The ramp is chosen when
//
//   S_step - S_ramp > z^2                  (the step's likelihood is e^{z^2/2} times lower)
//   S_ramp <= chi2_{max(m-3,1)}(Phi(z))    (and the ramp explains the points within their noise)
//
// and the step otherwise, ties included: a fault seen once after healthy points fits both exactly
// (a ramp that began just before it), so it stays a step until a second faulty point shows a slope.
// Three points on a line (one healthy, two faulty) fit the ramp exactly, and the decision then
// rests on the step's misfit alone: one fault growing, not two steps, the second a coincidence.
// The second condition keeps a step that fell inside one window (half its samples healthy: a level
// between the two) from being taken for a ramp, which fits it better than a step does but not
// within the noise; where the points scatter beyond their stated variance (unmodelled errors) no
// shape fits and the answer is the step, what a detector that saw only the last level would say.
//
// Plain arithmetic, O(m^2) for m points (a few dozen at most); no allocation. A variance that is
// not a positive finite number makes the answer a step (nothing to weigh the level by).

#include <array>
#include <cstddef>
#include <span>

namespace ftsense::generic {

struct LevelPoint {
  double t_s = 0.0;       // when the level holds [s] (a window's mean time, or a time on its line)
  double level = 0.0;     // the level there [channel unit]
  double variance = 0.0;  // of that level [unit^2], > 0
};

// The latest healthy windows of one channel, oldest first when read. Fixed capacity: the oldest
// is dropped when full (a ramp needs its last healthy point and the ones after it, not history).
class LevelHistory {
 public:
  static constexpr std::size_t kCapacity = 16;
  void push(const LevelPoint& point) noexcept;
  void clear() noexcept { count_ = next_ = 0; }
  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  // Copies the points oldest first into `out` (at least size() long); returns how many.
  std::size_t ordered(std::span<LevelPoint> out) const noexcept;

 private:
  std::array<LevelPoint, kCapacity> points_{};
  std::size_t count_ = 0;
  std::size_t next_ = 0;
};

struct OnsetShape {
  bool ramp = false;
  std::size_t first_faulty = 0;  // the first point after the onset (the step's j or the ramp's)
  double onset_s = 0.0;          // t0 of the ramp (the step: t of its first faulty point)
  double healthy_level = 0.0;    // c
  double slope = 0.0;            // s [unit/s] of the ramp (0 for a step)
  double step_chi2 = 0.0;        // S_step at its best j
  double ramp_chi2 = 0.0;        // S_ramp at its best j (S_step when fewer than 3 points)
};

// points: time order, at least 3 for a ramp (fewer: a step); z > 0: the decision's normal quantile.
[[nodiscard]] OnsetShape onset_shape(std::span<const LevelPoint> points, double z) noexcept;

// Where a level is a mean over a stretch of time (a block of samples) rather than a line's, a step
// can fall inside one: that point lies anywhere between the two levels, and with one or two
// points after it a ramp fits better than the plain step. The third shape, a step within point k:
//
//   y_i = c for i < k,  anything at i = k,  c + b for i > k          (k = 1..m-2)
//
// returns its least chi-square over k (4 parameters: c, b, k and the free point); +infinity with
// fewer than 3 points or a variance that is not a positive finite number. With 3 points it is 0
// (k = 1 leaves one point each side), so no ramp beats it: such a caller needs 4 at least. A caller with such
// levels takes a ramp only when it beats this by z^2 too.
[[nodiscard]] double step_within_a_point_chi2(std::span<const LevelPoint> points) noexcept;

}  // namespace ftsense::generic
