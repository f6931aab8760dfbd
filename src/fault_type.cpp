#include "ftsense/fault_type.hpp"

#include <array>

namespace ftsense {

namespace {
constexpr std::array kAll{FaultType::none,   FaultType::unclassified, FaultType::offset,
                          FaultType::drift,  FaultType::frozen,       FaultType::gain,
                          FaultType::noise,  FaultType::spikes,       FaultType::invalid,
                          FaultType::saturation};
}  // namespace

std::string_view to_string(FaultType type) noexcept {
  switch (type) {
    case FaultType::none: return "none";
    case FaultType::unclassified: return "unclassified";
    case FaultType::offset: return "offset";
    case FaultType::drift: return "drift";
    case FaultType::frozen: return "frozen";
    case FaultType::gain: return "gain";
    case FaultType::noise: return "noise";
    case FaultType::spikes: return "spikes";
    case FaultType::invalid: return "invalid";
    case FaultType::saturation: return "saturation";
  }
  return "unknown";
}

std::optional<FaultType> fault_type_from_string(std::string_view name) noexcept {
  for (FaultType t : kAll) {
    if (to_string(t) == name) return t;
  }
  return std::nullopt;
}

std::span<const FaultType> all_fault_types() noexcept { return kAll; }

}  // namespace ftsense
