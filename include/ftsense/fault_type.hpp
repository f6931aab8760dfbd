#pragma once
// Fault type codes, as written in the `<channel>/fault_type` output column and in the simulator's
// `truth/<channel>/fault` columns. The numbers are part of the user-facing contract: never reuse
// or renumber one (docs/architecture.md has the table).

#include <optional>
#include <span>
#include <string_view>

namespace ftsense {

enum class FaultType : int {
  none = 0,          // healthy
  unclassified = 1,  // a fault is detected, its type is not (yet) known
  offset = 2,        // constant bias: y = x + b
  drift = 3,         // bias growing in time: y = x + s (t - t0)
  frozen = 4,        // output stuck at a value, whatever the true force
  gain = 5,          // scale error: y = k x
  noise = 6,         // noise burst: variance far above nominal
  spikes = 7,        // isolated large outliers
  invalid = 8,       // NaN, Inf or missing sample (dropout)
  saturation = 9,    // clipped at a range limit
};

[[nodiscard]] std::string_view to_string(FaultType type) noexcept;
[[nodiscard]] std::optional<FaultType> fault_type_from_string(std::string_view name) noexcept;
[[nodiscard]] std::span<const FaultType> all_fault_types() noexcept;

}  // namespace ftsense
