#include "ftsense/text_file.hpp"

#include <cerrno>
#include <fstream>
#include <system_error>

namespace ftsense {

std::string read_text_file(const std::filesystem::path& path, std::string_view what, std::size_t max_bytes) {
  namespace fs = std::filesystem;
  const std::string name = path.string();
  const std::string role(what);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    if (ec.value() == ELOOP) {
      throw TextFileError(name + ": the " + role + " is a loop of symbolic links; point the link at the file");
    }
    throw TextFileError(name + ": cannot open the " + role + ": no such file; check the path");
  }
  if (fs::is_directory(status)) {
    throw TextFileError(name + ": is a directory, not a " + role + "; give the file inside it");
  }
  if (!fs::is_regular_file(status)) {
    throw TextFileError(name + ": is not a regular file (a device, pipe or socket); give the " + role +
                        " as a file");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw TextFileError(name + ": cannot read the " + role + " (" + ec.message() + ")");
  if (size > max_bytes) {
    throw TextFileError(name + ": is " + std::to_string(size) + " bytes; a " + role + " is at most " +
                        std::to_string(max_bytes >> 20) + " MiB, so this is not one: check the path");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw TextFileError(name + ": cannot open the " + role + "; check the read permission");
  std::string text(static_cast<std::size_t>(size), '\0');
  file.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(file.gcount()));  // a file that shrank meanwhile
  if (file.bad()) throw TextFileError(name + ": reading the " + role + " failed");
  return text;
}

}  // namespace ftsense
