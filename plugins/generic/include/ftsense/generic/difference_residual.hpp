#pragma once
// Difference residual: r = y_measured - y_virtual, per channel.
//
// The simplest residual generator. `measured` has role measured and `virtual` role
// virtual_estimate, so the pipeline applies the independence rule to it. Units pass through
// (both inputs must share one). A NaN in either input gives a NaN residual: downstream detectors
// flag it as invalid rather than the residual hiding it.

#include <string_view>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class DifferenceResidual {
 public:
  static constexpr std::string_view name = "difference_residual";
  static constexpr std::string_view summary =
      "residual r = measured - virtual, per channel (unit-generic)";

  struct Params {
    static void describe(ParamSchema<Params>& /*schema*/) {}
  };

  enum Input : std::size_t { kMeasured, kVirtual };
  enum Output : std::size_t { kResidual };

  DifferenceResidual(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
};

}  // namespace ftsense::generic
