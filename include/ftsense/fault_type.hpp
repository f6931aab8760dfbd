#pragma once
// The fault types: the one table every part of ftsense refers to (detectors, recovery, the
// simulator and `ftsense inject`, `ftsense report`, the docs). Adding a fault type is a new
// enumerator with the next unused code plus its row in kFaultTypes, and the code that detects it
// (docs/architecture.md, "Adding a fault type").
//
// The numeric code is written in the `<channel>/fault_type` output column (as a double, like every
// port value) and in the simulator's `truth/<channel>/fault` columns. The codes are part of the
// user-facing contract: never reuse or renumber one.
//
// In the model descriptions, x is the true value and y the sensor's reading.

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace ftsense {

// The enumerator's value is its code.
enum class FaultType : int {
  none = 0,
  unclassified = 1,
  offset = 2,
  drift = 3,
  frozen = 4,
  gain = 5,
  noise = 6,
  spikes = 7,
  invalid = 8,
  saturation = 9,
};

struct FaultTypeInfo {
  FaultType type;
  std::string_view name;   // in configs, scenarios, reports; the enumerator's name
  std::string_view model;  // one line: what the reading does
};

// One row per fault type, in code order (row i has code i).
inline constexpr auto kFaultTypes = std::to_array<FaultTypeInfo>({
    {FaultType::none, "none", "healthy"},
    {FaultType::unclassified, "unclassified", "a fault is detected, its type is not (yet) known"},
    {FaultType::offset, "offset", "constant bias: y = x + b"},
    {FaultType::drift, "drift", "bias growing in time: y = x + s (t - t0)"},
    {FaultType::frozen, "frozen", "stuck at a value, whatever the true force: y = c"},
    {FaultType::gain, "gain", "scale error: y = k x"},
    {FaultType::noise, "noise", "noise burst: y = x + w, w of variance far above nominal"},
    {FaultType::spikes, "spikes", "isolated large outliers: y = x + a on single samples"},
    {FaultType::invalid, "invalid", "no value: NaN, Inf or a missing sample (dropout)"},
    {FaultType::saturation, "saturation", "clipped at a range limit: y = min(max(x, lo), hi)"},
});

namespace detail {
consteval bool rows_in_code_order() {
  for (std::size_t i = 0; i < kFaultTypes.size(); ++i) {
    if (static_cast<std::size_t>(kFaultTypes[i].type) != i) return false;
    for (std::size_t j = 0; j < i; ++j) {
      if (kFaultTypes[j].name == kFaultTypes[i].name) return false;
    }
  }
  return true;
}
}  // namespace detail
static_assert(detail::rows_in_code_order(), "kFaultTypes: row i must have code i, names unique");

// The type's name; "unknown" for a value outside the table (a cast from an unchecked integer).
[[nodiscard]] constexpr std::string_view to_string(FaultType type) noexcept {
  const auto i = static_cast<std::size_t>(type);
  return i < kFaultTypes.size() ? kFaultTypes[i].name : "unknown";
}

// The code as port values carry it.
[[nodiscard]] constexpr double fault_code(FaultType type) noexcept { return static_cast<double>(type); }

// The type of a code read from a port or a column; nullopt unless `code` is exactly one of the
// table's codes (NaN, Inf, 2.5, -1, 42 are not).
[[nodiscard]] constexpr std::optional<FaultType> fault_type_from_code(double code) noexcept {
  for (const FaultTypeInfo& row : kFaultTypes) {
    if (fault_code(row.type) == code) return row.type;
  }
  return std::nullopt;
}

[[nodiscard]] constexpr std::optional<FaultType> fault_type_from_string(std::string_view name) noexcept {
  for (const FaultTypeInfo& row : kFaultTypes) {
    if (row.name == name) return row.type;
  }
  return std::nullopt;
}

namespace detail {
constexpr std::array<FaultType, kFaultTypes.size()> all_types() {
  std::array<FaultType, kFaultTypes.size()> out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = kFaultTypes[i].type;
  return out;
}
inline constexpr auto kAllFaultTypes = all_types();
}  // namespace detail

// Every fault type, in code order.
[[nodiscard]] constexpr std::span<const FaultType> all_fault_types() noexcept { return detail::kAllFaultTypes; }

// The types that model a sensor's misbehaviour: every type but none (healthy) and unclassified (a
// detector's verdict, not a model). The simulator's scenarios and `ftsense inject` accept these.
[[nodiscard]] constexpr std::span<const FaultType> sensor_fault_types() noexcept {
  static_assert(kFaultTypes[0].type == FaultType::none && kFaultTypes[1].type == FaultType::unclassified);
  return all_fault_types().subspan(2);
}

// The table as Markdown (code, name, model): the generated block of docs/architecture.md,
// printed by `ftsense plugins --fault-types`.
[[nodiscard]] std::string fault_type_table_markdown();

}  // namespace ftsense
