#pragma once
// The median of three readings: an isolated spike among them never wins (spike recovery).

#include <algorithm>

namespace ftsense::generic {

[[nodiscard]] constexpr double median_of_three(double a, double b, double c) noexcept {
  return std::max(std::min(a, b), std::min(std::max(a, b), c));
}

}  // namespace ftsense::generic
