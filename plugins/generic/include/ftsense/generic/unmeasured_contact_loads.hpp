#pragma once
// The loads of contact points whose sensors cannot be used (frozen, saturated, invalid), from
// what the total vertical force leaves and, on rigid soles, from the plane a sole's loads lie on.
//
// Model. Channel j of foot f carries N_j [N]. Two relations hold on healthy data:
//   sum      sum_j N_j = F_z + e_s,  e_s the total force's error (variance s_s^2)
//   plane    a rigid sole on pads of equal stiffness sinks by a plane, so in full contact each pad's
//            load is affine in its position: N_j = a_f + b_f x_j + c_f y_j, (x_j, y_j) [m] the pad
//            in the foot frame. With P the points' rows [1 x_j y_j], the loads of a foot then
//            satisfy W^T N_f = e_p, W the orthonormal basis of the null space of P^T (n - rank P
//            relations; four pads on a rectangle: one, (N_1 + N_4 - N_2 - N_3) / 2 = 0), e_p the
//            sole's departure from the model (variance s_p^2 per relation).
// The unknown loads u (substituted channels on the ground) minimise
//   (sum_k u_k - l)^2 / s_s^2 + sum_{usable feet f, relations r} (w_r^T N_f)^2 / s_{p,f,r}^2,
//   l = F_z - sum of the known loads,
// subject to u_k >= lb_k (a pad only pushes: 0; a saturated pad carries at least its ceiling,
// its reading), solved by Cholesky on the normal equations and an active set (the most violated
// bound is fixed, at most once per unknown). Without a usable plane relation the sum alone is
// one equation for m unknowns, and the loads share l equally (the minimum-norm answer), which
// the closed form gives exactly. Two unknown pads whose columns of W are equal (diagonal pads of
// a rectangle) stay apart only by the sum; the plane then fixes what they carry together.
//
// s_s^2 and s_{p,f,r}^2 are measured on the log itself, as cumulative mean squares: the sum
// residual on ticks where no channel is flagged, each relation on ticks where a foot's pads are all
// healthy, on the ground and loaded (observe_sum, observe_foot). A relation is used once both have
// kMinSamples; before, the sum alone decides. Whether a foot is in full contact (the plane holds
// only then: a pad that lifts reads 0, not the plane's negative value) is the caller's to say.
//
// Channels: feet x points, foot after foot. Allocation-free after construction.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace ftsense::generic {

class UnmeasuredContactLoads {
 public:
  // A variance from 100 samples is known within about +-14 % (sqrt(2 / 100)).
  static constexpr double kMinSamples = 100.0;

  // `points`: the contact points of one foot, every foot alike (foot frame, m); empty: no plane
  // relations (point feet, or a sole whose loads are not known to lie on a plane).
  UnmeasuredContactLoads(std::span<const std::array<double, 2>> points, std::size_t points_per_foot,
                         std::size_t feet);

  [[nodiscard]] std::size_t relations_per_foot() const noexcept { return relations_; }
  // The basis W (points_per_foot x relations_per_foot, row-major): relation r of point i.
  [[nodiscard]] double relation_weight(std::size_t point, std::size_t relation) const noexcept {
    return weights_[point * relations_ + relation];
  }

  // The fault-free RMS of relation r on foot f [N]; NaN before kMinSamples ticks.
  [[nodiscard]] double relation_rms(std::size_t foot, std::size_t relation) const noexcept;

  void reset() noexcept;
  // A tick where no channel is flagged: the sum residual sum_j N_j - F_z [N].
  void observe_sum(double residual) noexcept;
  // A tick where foot f's pads are all healthy, on the ground and loaded: their readings [N].
  void observe_foot(std::size_t foot, std::span<const double> loads) noexcept;

  // Fills loads[k] for every k with unknown[k] != 0; the other entries are the known loads.
  // lower_bound[k]: what channel k carries at least [N]. plane_usable[f] != 0: foot f is in full
  // contact (its relations may be used). leftover: l = F_z - the known loads' sum [N].
  void solve(std::span<double> loads, std::span<const char> unknown, std::span<const double> lower_bound,
             std::span<const char> plane_usable, double leftover) noexcept;

  // Whether the relations of the last solve fix what foot f's unknowns carry together (the sum
  // and the feet's plane relations it used, restricted to its unknowns: their indicator lies in
  // those rows' span). True for a foot without unknowns. Where it is false the loads found there
  // are the equal share of what the relations leave to unknowns on several feet, not a measure.
  [[nodiscard]] bool foot_total_determined(std::size_t foot) noexcept;

 private:
  // The normal equations over the unknowns not held at their bounds (m unknowns in all).
  void solve_free(std::span<double> loads, double leftover, std::size_t m) noexcept;

  std::size_t points_per_foot_;
  std::size_t feet_;
  std::size_t relations_ = 0;
  std::vector<double> weights_;       // W, points_per_foot x relations
  double sum_square_ = 0.0, sum_count_ = 0.0;
  std::vector<double> relation_square_;  // per foot and relation
  std::vector<double> relation_count_;   // per foot
  // Work space, sized at construction.
  std::vector<std::size_t> unknowns_;   // channel of each unknown
  std::vector<char> fixed_;             // per unknown: held at its bound
  std::vector<char> foot_rows_;         // per foot: its relations enter this solve
  std::vector<double> rhs_;             // per foot and relation: -w^T (known loads)
  std::vector<double> lower_;           // per unknown
  std::vector<double> normal_;          // n x n over the n free unknowns (stride n), then its Cholesky factor
  std::vector<double> gradient_;        // n, then the solution
  std::size_t solved_unknowns_ = 0;     // m of the last solve
  std::vector<double> basis_;           // orthonormal rows of the last solve's relations, over its m unknowns
};

}  // namespace ftsense::generic
