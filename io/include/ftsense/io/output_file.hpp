#pragma once
// An output file that is either whole or absent.
//
// The content goes to a temporary file beside the target ("<target>.partial-<pid>") and is
// renamed onto the target only by commit(), after a flush that succeeded. So a run that fails
// (a bad row, a full disk), is interrupted (SIGINT, SIGTERM: the temporary files are removed
// before the process ends) or throws never leaves a file under the final name that looks
// complete, and never destroys the previous result of the same name before the new one is whole.
// An output that is, or links to, one of the command's inputs is refused before anything is
// written, and so is one that exists but is not a regular file (a device, a pipe, a terminal:
// /dev/stdout would mix the data with the program's messages). The target "-" is standard output
// itself, written directly (a pipe cannot be whole or absent).

#include <filesystem>
#include <fstream>
#include <iostream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ftsense::io {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Whether `a` and `b` name the same existing file (through symbolic and hard links).
[[nodiscard]] bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) noexcept;

// Throws OutputError when `output` is a directory or the same file as one of `inputs`; `what`
// names the output in the message ("--output").
void check_output_path(const std::filesystem::path& output, const std::vector<std::string>& inputs,
                       const std::string& what);

class OutputFile {
 public:
  // Opens the temporary file. Throws OutputError when the target is refused (check_output_path)
  // or the temporary file cannot be created.
  explicit OutputFile(std::filesystem::path target, const std::vector<std::string>& inputs = {},
                      const std::string& what = "output");
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();  // not committed: the temporary file is removed

  [[nodiscard]] std::ostream& stream() noexcept { return to_stdout_ ? static_cast<std::ostream&>(std::cout) : file_; }
  [[nodiscard]] bool is_stdout() const noexcept { return to_stdout_; }
  [[nodiscard]] const std::filesystem::path& target() const noexcept { return target_; }
  // Flushes, checks that every write succeeded and renames onto the target. Throws OutputError
  // (the temporary file removed) when writing failed.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::ofstream file_;
  int slot_ = -1;  // in the list of files the signal handler removes
  bool committed_ = false;
  bool to_stdout_ = false;
};

}  // namespace ftsense::io
