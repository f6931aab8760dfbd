#pragma once
// Reading a whole text file (a config, a URDF, a scenario, a thresholds or faults file) with
// bounds: regular files only, at most kMaxTextFileBytes. A device (/dev/zero), a pipe, a
// directory or a huge file is refused with what it is, before anything is read into memory.

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ftsense {

// 64 MiB: a thousand times the largest config or URDF shipped; a bigger file is not one.
inline constexpr std::size_t kMaxTextFileBytes = std::size_t{64} << 20;

class TextFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The file's content. Throws TextFileError "<path>: <what is wrong>; <what to do>", where `what`
// names the file's role ("config file", "URDF").
[[nodiscard]] std::string read_text_file(const std::filesystem::path& path, std::string_view what,
                                         std::size_t max_bytes = kMaxTextFileBytes);

}  // namespace ftsense
