#pragma once
// A per-channel parameter given as one value for all channels or one value per channel, the
// convention of the generic plugins ("thresholds": [5] or [5, 7, 9] for three channels).

#include <cstddef>
#include <string_view>
#include <vector>

namespace ftsense {

// `values` expanded to `channels` entries: one value is repeated, `channels` values are kept.
// Throws ConfigError at "/params/<key>" for another count, at "/params/<key>/<j>" for a
// non-finite entry. With `empty_is_none`, an empty list gives `channels` NaN ("not given").
[[nodiscard]] std::vector<double> channel_values(const std::vector<double>& values, std::size_t channels,
                                                 std::string_view key, bool empty_is_none = false);

}  // namespace ftsense
