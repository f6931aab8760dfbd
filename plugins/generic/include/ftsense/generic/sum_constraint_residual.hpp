#pragma once
// Constraint residual "these channels sum to this reference", with a leave-one-out virtual
// sensor per channel and the residuals' fault signatures (analytical redundancy).
//
// Model. The channels come in groups of g (`group_size`, as wired: all of them by default); the
// readings x_i of group G sum to its reference R_G (input `reference`, one value per group, in
// the readings' unit: the pads or feet of a robot and the total vertical force from the IMU),
//
//   sum_{i in G} x_i = R_G + e,       e the reference's error (the model's, not the sensors').
//
// A channel that cannot carry load (input `loadable` below 1/2, when `loadable` is on: its contact
// point off the ground, by kinematics) reads 0 when healthy. Per channel j of group G:
//
//   v_j        = R_G - sum_{i in G, i != j} x_i    while j can carry load (NaN and a missing
//                                                  `loadable` count as can)
//              = 0                                  while it cannot
//   virtual_j  = max(v_j, virtual_min)             (what physics allows: a force sensor that only
//                                                  pushes has virtual_min 0; default none)
//   residual_j = x_j - v_j        = sum_G x - R_G   (can carry load: the group's sum residual;
//                                                   v_j unbounded, so the residuals stay linear
//                                                   in the readings, as the signature says)
//                                 = x_j             (cannot: its own reading)
//   signature  S_ij = d residual_i / d x_j = 1 for every j of G   (row i can carry load)
//                                          = delta_ij               (row i cannot)
//   row_weight w_i = 1 / L_G   (row i can carry load; L_G of the group's channels can)
//                  = 1         (row i cannot)
//
// The rows of the channels that can carry load are L_G copies of one number, the group's sum
// residual: one observation, not L_G. A statistic that sums the squares of whitened rows (the
// isolator's GLR) weighs row i by w_i, so the sum counts once, and each reading off the ground
// once on its own.
//
// A fault f on channel j shifts the residuals by f S_.j: every loaded row and j's own row. The
// loaded channels' columns are alike, so a fault on a loaded channel is not told from its loaded
// neighbours' until one of them leaves the ground (signature_isolator then says "cannot judge"
// rather than guess); a channel whose contact is off the ground is seen on its own row too.
//
// With `correction` on, input c (per channel) gives the readings as recovered, x_i - c_i, and the
// virtual values take the others as corrected:
//
//   v_j = R_G - sum_{i in G, i != j} (x_i - c_i)
//
// and input `substituted` (1 where reading i stands for nothing: its recovery is the virtual
// value, as for a frozen, saturated or invalid sensor) makes its load unknown while it can carry
// load, so the others' virtual values are NaN (the relation cannot judge them: one equation, two
// unknown loads), and 0 while it cannot (a foot in the air carries nothing, whatever its sensor
// reads). A non-finite c_i counts as substituted.
//
// while the residuals and signatures stay the readings' own (the detectors see the faults as they
// are). Wire a recovery's correction one tick late (fault_recovery's `correction` through
// previous_tick): a fault found and corrected on one channel then leaves the others' virtual
// values, and with them their classification and recovery. Only corrections made of a channel's
// own readings belong there (fault_recovery gives 0 for a substituted or blended channel, and
// says substituted): a substituted value is R_G less the others, and fed back it would hand each
// of them its own reading. What still reaches v_j from x_j: a fault estimate that was fitted while channel j's
// reading was in its channel's virtual value (a second fault during the first's fit).
//
// A non-finite reading (or reference) makes every value that depends on it NaN: the residuals of
// the group's loaded channels (not judged downstream: a CUSUM holds, the isolator waits), the
// virtual sensors of the others. The non-finite channel's own virtual value stays finite when the
// rest of its group is, so recovery has what the other channels leave. Units: any; all of a
// group's readings and its reference share one. Allocation-free: nothing is sized per tick.

#include <span>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class SumConstraintResidual {
 public:
  static constexpr std::string_view name = "sum_constraint_residual";
  static constexpr std::string_view summary =
      "channels that sum to a reference: leave-one-out virtual sensors, residuals and their fault signatures";
  // For the config reference's port table and the schema (plugin.hpp): inputs loadable and correction
  // are optional.
  static constexpr std::string_view example_params = R"([{}, {"loadable": true, "correction": true}])";

  struct Params {
    int group_size = 0;
    bool loadable = false;
    bool correction = false;
    std::vector<double> virtual_min{};
    static void describe(ParamSchema<Params>& schema);
  };

  // kCorrection and kSubstituted come one earlier when `loadable` is off (the enum names the
  // order with every input on).
  enum Input : std::size_t { kSignal, kReference, kLoadable, kCorrection, kSubstituted };
  enum Output : std::size_t { kVirtual, kResidual, kSignature, kSumResidual, kRowWeight };

  SumConstraintResidual(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  // With `correction`: whether channel i's load is known to the others' virtual values, and what
  // it is (the model above).
  [[nodiscard]] bool load_known(std::span<const double> x, std::span<const double> correction,
                                std::span<const double> substituted, std::size_t i, bool can_carry) const noexcept;
  [[nodiscard]] double load_of(std::span<const double> x, std::span<const double> correction,
                               std::span<const double> substituted, std::size_t i) const noexcept;

  Ports ports_;
  std::size_t channels_ = 0;
  std::size_t group_size_ = 0;
  std::size_t groups_ = 0;
  bool loadable_ = false;
  bool correction_ = false;
  std::vector<double> virtual_min_;  // per channel; -inf: none
};

}  // namespace ftsense::generic
