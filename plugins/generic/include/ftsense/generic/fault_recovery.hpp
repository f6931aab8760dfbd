#pragma once
// Recovery: the signal to hand downstream, per channel j (method.md section 5).
//
//   recovered_j = measured_j - fault_estimate_j       (offset, drift: the paper's N_meas - eta_hat)
//   recovered_j = virtual_j                           when the channel's fault type is one of
//                                                     `substitute_types` (default: frozen,
//                                                     invalid), or measured_j is not finite
//                                                     (a fault_type value that is not one of
//                                                     fault_type.hpp's codes counts as invalid)
//
// With correction = "when_flagged", measured_j passes through unchanged while fault_j = 0.
// The output is never NaN: if the chosen value is not finite, the other one is used, and if
// neither is, the last recovered value is held.

#include <string>
#include <string_view>
#include <vector>

#include "ftsense/fault_type.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class FaultRecovery {
 public:
  static constexpr std::string_view name = "fault_recovery";
  static constexpr std::string_view summary =
      "recovered = measured - fault estimate, or the virtual value for frozen/invalid channels";

  enum class Correction { always, when_flagged };

  struct Params {
    Correction correction = Correction::always;
    std::vector<std::string> substitute_types{std::string(to_string(FaultType::frozen)),
                                              std::string(to_string(FaultType::invalid))};
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kMeasured, kFaultEstimate, kVirtual, kFault, kFaultType };
  enum Output : std::size_t { kRecovered };

  FaultRecovery(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  Correction correction_;
  std::vector<FaultType> substitute_types_;
  std::vector<double> last_;
};

}  // namespace ftsense::generic
