#include "ftsense/channel_values.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "ftsense/diagnostics.hpp"

namespace ftsense {

std::vector<double> channel_values(const std::vector<double>& values, std::size_t channels, std::string_view key,
                                   bool empty_is_none) {
  if (values.empty() && empty_is_none) return std::vector<double>(channels, std::numeric_limits<double>::quiet_NaN());
  const std::string path = json_pointer_append("/params", key);
  if (values.size() != 1 && values.size() != channels) {
    throw ConfigError(path, "has " + std::to_string(values.size()) + " entries but there are " +
                                std::to_string(channels) + " channels; give one value per channel or one for all");
  }
  for (std::size_t j = 0; j < values.size(); ++j) {
    if (!std::isfinite(values[j])) throw ConfigError(json_pointer_append(path, j), "is not a finite number");
  }
  return values.size() == channels ? values : std::vector<double>(channels, values.front());
}

}  // namespace ftsense
