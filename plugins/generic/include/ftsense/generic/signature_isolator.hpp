#pragma once
// Isolation of faulty channels by their signatures on a family of residuals (analytical
// redundancy: which residuals a fault excites, and how much).
//
// Model. Channels are grouped (`group_size` g channels each, as wired: a foot's sensors), and each
// group has one residual per channel, r_i (any unit, zero-mean when fault-free, standard deviation
// sigma_i, `residual_noise_std`). A fault of size f on channel j of the group shifts the group's
// residuals by f s_j, s_j the j-th column of the group's signature matrix S (g x g, input
// `signature`, row i = residual i, S_ij = d r_i / d x_j; it may change tick by tick: a
// leave-one-out regression gives S = I - C while its relations hold, the identity of a sensor's
// own residual when they do not). Row i weighs w_i (input `row_weight` when `row_weights` is on,
// else 1): rows that are copies of one number (sum_constraint_residual's loaded rows) share one
// observation's weight. On the whitened residual z_i = sqrt(w_i) r_i / sigma_i and columns
// t_j = sqrt(w) s_j / sigma, with B the channels blamed so far (T_B their columns) and
// G = T_B' T_B, the least-squares fault sizes and what they leave are
//
//   f_B = G^-1 T_B' z,        E_B = |z|^2 - <T_B' z, f_B>,
//
// and a further channel j explains of what B leaves (its GLR gain; c = T_B' t_j)
//
//   gain_j = (<t_j, z> - <c, f_B>)^2 / (|t_j|^2 - <c, G^-1 c>)        (|z|^2 - E_j when B is empty).
//
// While any residual of the group is raised (input `alarm`, from a detector on r), the channel
// with the largest gain is blamed when the runner-up's gain is at least chi^2_1(1 - alpha) less
// (alpha = T / false_alarm_interval_s: hypotheses are told apart as surely as a detector keeps its
// false-alarm rate); otherwise nobody is blamed and the group's channels are reported
// `cannot_judge` (collinear sensors, whose signatures are nearly parallel, are not told apart by
// guessing). With `max_faults` above 1, a further channel is blamed on the same terms while the
// group stays raised, and only when its gain itself clears the margin (no detector stands behind
// what the blamed channels leave); while the best such gain clears it and no channel is singled
// out, the unblamed channels are `cannot_judge` (judged only while fewer than `max_faults` are
// blamed and every blamed channel is seen; a leftover that only spanned columns could explain is
// not reported). A column that the blamed columns span this tick (|t_j|^2 - <c, G^-1 c> at most
// 1e-9 |t_j|^2) is no candidate: its fault would be theirs. Blamed channels stay blamed while any
// residual of the group is raised, and are released when none is; and a blamed channel j whose
// own row sees no other channel this tick (S_jk = 0 for k != j: a foot in the air, whose row is
// its own reading) while its own detector is down is released then, whatever keeps the rest of
// the group raised: its own evidence has cleared (without it, an offset that ended in the air
// stayed blamed for 9 s beside another foot's faults, its correction poisoning the recovery). With one fault a group, the
// healthy neighbours whose residuals a fault excites are never blamed for it; with several, that
// holds as far as the signature is exact: a relative error e in S leaves about e f of a blamed
// fault f on the neighbours' rows, blamed once (e f / sigma)^2 clears the margin. Columns with
// |t_j|^2 below 1e-12 (a channel no residual sees this tick) are not candidates, and a blamed one
// keeps its last size (no further channel is blamed while one is unseen: its fault would be
// blamed on another). A blamed column that the earlier blamed columns span this tick keeps its
// last size too, and the others are fitted to what it leaves (two loaded feet both blamed: the
// later one keeps the size it had on the last tick it stood apart; any change along the shared
// direction, a growing drift among them, goes to the earlier blamed).
//
// Outputs per channel: fault (1 blamed), fault_type (unclassified when blamed: the type is a
// classifier's work), fault_estimate f_j of a blamed channel in the residual's unit (0
// otherwise), cannot_judge (1 while its group is raised and it is neither blamed nor told apart).
// Allocation-free: the work vectors are sized at construction; a raised group costs
// O(g^2 |B| + g |B|^2 + |B|^3) a tick.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class SignatureIsolator {
 public:
  static constexpr std::string_view name = "signature_isolator";
  static constexpr std::string_view summary =
      "blames the channels whose fault signatures explain the raised residuals (GLR), else cannot judge";
  // For the config reference's port table and the schema (plugin.hpp): input row_weight is optional.
  static constexpr std::string_view example_params = R"([{"group_size": 1}, {"group_size": 1, "row_weights": true}])";

  // `ftsense calibrate` measures each fault-free residual's RMS.
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"residual_noise_std", "residual", FaultFreeStatistic::rms},
  });

  struct Params {
    int group_size = 1;
    std::vector<double> residual_noise_std{1.0};
    double false_alarm_interval_s = 86400.0;
    int max_faults = 1;
    bool row_weights = false;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kResidual, kAlarm, kSignature, kRowWeight };
  enum Output : std::size_t { kFault, kFaultType, kFaultEstimate, kCannotJudge };

  SignatureIsolator(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // chi^2_1(1 - alpha): how much less the runner-up must explain, and a further fault at least.
  [[nodiscard]] double isolation_margin() const noexcept { return margin_; }

 private:
  // Least squares on the blamed columns listed in fit_index_[0, n) of the group starting at channel
  // `first`: their sizes into estimate_ (a spanned column keeps its own), what they leave of z
  // into fit_z_ minus T f (fit_z_ holds z minus the spanned columns' part; fit_size_ the others').
  void fit_blamed(std::size_t first, std::size_t n) noexcept;
  // x = G^-1 b on the factor fit_factor_ of the last fit_blamed (a spanned column's entry is 0).
  void solve_gram(std::size_t n, const double* b, double* x) const noexcept;

  Ports ports_;
  std::size_t group_size_;
  std::size_t groups_;
  std::size_t max_faults_;
  bool row_weights_;
  std::vector<double> inv_std_;
  double margin_;
  std::vector<std::size_t> blamed_count_;  // per group
  std::vector<std::size_t> blamed_order_;  // per group, g slots: its blamed channels, first blamed first
  std::vector<double> estimate_;           // per channel: its fault size while blamed
  // Work, sized g or g x g at construction.
  std::vector<double> z_, fit_z_, columns_, column_sq_;
  std::vector<char> usable_;
  std::vector<std::size_t> fit_index_;
  std::vector<double> fit_gram_, fit_factor_, fit_rhs_, fit_size_, cross_, solved_;
};

}  // namespace ftsense::generic
