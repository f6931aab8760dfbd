#pragma once
// Strict JSON text: the one reader of every JSON document ftsense takes from a user (configs,
// scenarios, fault files, thresholds).
//
// JSON parsers are lenient where a config must not be: they keep the last of two equal keys,
// stop at a NUL byte as at the end of the text, and recurse without limit. This reader refuses
// all three, and turns every syntax error into "source:line:column: what".

#include <cstddef>
#include <string_view>

#include "ftsense/params.hpp"

namespace ftsense {

// Deepest nesting of arrays and objects accepted; a config needs a handful of levels, and JSON
// values are copied, compared and printed recursively (a deep text would overflow the stack).
inline constexpr std::size_t kMaxJsonDepth = 100;

// Parses `text` (named `source_name` in messages). Throws ConfigError: syntax errors, NUL bytes,
// numbers beyond the range of a double and nesting deeper than kMaxJsonDepth at
// "source:line:column"; duplicate object keys, every one of them, at their JSON Pointer.
[[nodiscard]] Json parse_json_text(std::string_view text, std::string_view source_name);

}  // namespace ftsense
