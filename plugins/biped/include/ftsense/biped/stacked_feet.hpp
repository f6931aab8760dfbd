#pragma once
// The number of feet a `foot_pos` input stacks: (x, y, z) per foot, foot after foot, as wired
// (e.g. ["input.l_foot_pos", "input.r_foot_pos"] is 2 feet; `fallback_feet` when nothing is
// wired). A size that is not a multiple of 3 is a ConfigError at /inputs/foot_pos.

#include <cstddef>
#include <string>

#include "ftsense/plugin.hpp"

namespace ftsense::biped {

[[nodiscard]] inline std::size_t stacked_feet(const StageContext& context, std::size_t fallback_feet) {
  const std::size_t dim = context.wired_dim("foot_pos", 3 * fallback_feet);
  if (dim % 3 != 0 || dim == 0) {
    throw ConfigError("/inputs/foot_pos", "carries " + std::to_string(dim) +
                                              " values; foot_pos stacks the (x, y, z) origins of the feet, a "
                                              "multiple of 3");
  }
  return dim / 3;
}

}  // namespace ftsense::biped
