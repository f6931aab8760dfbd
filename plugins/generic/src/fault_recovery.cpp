#include "ftsense/generic/fault_recovery.hpp"

#include <algorithm>
#include <cmath>

namespace ftsense::generic {

void FaultRecovery::Params::describe(ParamSchema<Params>& schema) {
  schema.add_choice("correction", &Params::correction,
                    "subtract the fault estimate always (paper) or only while the channel is flagged",
                    {{"always", Correction::always}, {"when_flagged", Correction::when_flagged}});
  schema.add("substitute_types", &Params::substitute_types,
             "fault type names whose channel takes the virtual value instead");
}

void FaultRecovery::Params::validate(Diagnostics& diag, std::string_view path) const {
  std::vector<std::string> names;
  for (FaultType t : all_fault_types()) names.emplace_back(to_string(t));
  for (std::size_t i = 0; i < substitute_types.size(); ++i) {
    if (!fault_type_from_string(substitute_types[i])) {
      diag.error(json_pointer_append(std::string(path) + "/substitute_types", i),
                 "unknown fault type '" + substitute_types[i] + "'; " + suggest(substitute_types[i], names));
    }
  }
}

FaultRecovery::FaultRecovery(const Params& params, const StageContext& context)
    : correction_(params.correction) {
  for (const auto& t : params.substitute_types) substitute_types_.push_back(*fault_type_from_string(t));
  const std::size_t dim = context.wired_dim("measured", 1);
  ports_.add_input(PortSpec{"measured", dim, std::string(kAnyUnit), "the monitored sensor"}.sized_by("as wired"));
  ports_.add_input(PortSpec{"fault_estimate", dim, std::string(kAnyUnit), "the estimated fault eta_hat"}
                       .sized_by("as `measured`"));
  ports_.add_input(PortSpec{"virtual", dim, std::string(kAnyUnit), "the virtual sensor's value"}
                       .sized_by("as `measured`"));
  ports_.add_input(PortSpec{"fault", dim, std::string(kDimensionless), "1 while the channel is flagged"}
                       .sized_by("as `measured`"));
  ports_.add_input(PortSpec{"fault_type", dim, std::string(kDimensionless), "the channel's fault type code"}
                       .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"recovered", dim, std::string(kAnyUnit), "the signal to use downstream"}
                        .sized_by("as `measured`"));
  last_.assign(dim, 0.0);
}

void FaultRecovery::reset() noexcept { std::fill(last_.begin(), last_.end(), 0.0); }

void FaultRecovery::step(const StepIO& io) noexcept {
  const auto measured = io.in(kMeasured);
  const auto fault_estimate = io.in(kFaultEstimate);
  const auto estimate = io.in(kVirtual);
  const auto fault = io.in(kFault);
  const auto type = io.in(kFaultType);
  const auto out = io.out(kRecovered);
  for (std::size_t j = 0; j < out.size(); ++j) {
    // A code that is not one of the table's is itself invalid data.
    const FaultType t = fault_type_from_code(type[j]).value_or(FaultType::invalid);
    const bool substitute = !std::isfinite(measured[j]) ||
                            std::find(substitute_types_.begin(), substitute_types_.end(), t) !=
                                substitute_types_.end();
    const bool correct = correction_ == Correction::always || fault[j] != 0.0;
    const double corrected = correct ? measured[j] - fault_estimate[j] : measured[j];
    double value = substitute ? estimate[j] : corrected;
    if (!std::isfinite(value)) value = substitute ? corrected : estimate[j];
    if (!std::isfinite(value)) value = last_[j];
    out[j] = value;
    last_[j] = value;
  }
}

}  // namespace ftsense::generic
