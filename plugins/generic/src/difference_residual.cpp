#include "ftsense/generic/difference_residual.hpp"

namespace ftsense::generic {

DifferenceResidual::DifferenceResidual(const Params& /*params*/, const StageContext& context) {
  const std::size_t dim = context.wired_dim("measured", 1);
  ports_.add_input(PortSpec{"measured", dim, std::string(kAnyUnit), "the measured signal", PortRole::measured}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"virtual", dim, std::string(kAnyUnit), "the virtual sensor's estimate of the same quantity",
                            PortRole::virtual_estimate}
                       .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"residual", dim, std::string(kAnyUnit), "measured - virtual"}.sized_by("as `measured`"));
}

void DifferenceResidual::step(const StepIO& io) noexcept {
  const auto measured = io.in(kMeasured);
  const auto estimate = io.in(kVirtual);
  const auto residual = io.out(kResidual);
  for (std::size_t j = 0; j < residual.size(); ++j) residual[j] = measured[j] - estimate[j];
}

}  // namespace ftsense::generic
