#include "ftsense/io/output_file.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>
#include <system_error>

namespace ftsense::io {

namespace {

// The temporary files of this process, for the signal handler: fixed storage, so that the
// handler only reads memory and calls unlink (both async-signal-safe).
constexpr int kSlots = 32;
constexpr std::size_t kPathBytes = 4096;
std::array<std::array<char, kPathBytes>, kSlots> g_paths{};
std::array<std::atomic<bool>, kSlots> g_in_use{};
std::mutex g_slots_mutex;

extern "C" void remove_partial_outputs_and_die(int signal_number) {
  for (int i = 0; i < kSlots; ++i) {
    if (g_in_use[static_cast<std::size_t>(i)].load()) ::unlink(g_paths[static_cast<std::size_t>(i)].data());
  }
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

void install_handlers_once() {
  static const bool installed = [] {
    for (int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, remove_partial_outputs_and_die);
    return true;
  }();
  (void)installed;
}

int claim_slot(const std::filesystem::path& path) {
  const std::string text = path.string();
  if (text.size() >= kPathBytes) return -1;  // not removed on a signal; still never looks complete
  std::lock_guard lock(g_slots_mutex);
  for (int i = 0; i < kSlots; ++i) {
    auto& used = g_in_use[static_cast<std::size_t>(i)];
    if (used.load()) continue;
    std::memcpy(g_paths[static_cast<std::size_t>(i)].data(), text.c_str(), text.size() + 1);
    used.store(true);
    return i;
  }
  return -1;
}

void release_slot(int slot) {
  if (slot >= 0) g_in_use[static_cast<std::size_t>(slot)].store(false);
}

}  // namespace

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) noexcept {
  std::error_code ec;
  const bool same = std::filesystem::equivalent(a, b, ec);
  return !ec && same;
}

void check_output_path(const std::filesystem::path& output, const std::vector<std::string>& inputs,
                       const std::string& what) {
  if (output == "-") return;  // standard output
  std::error_code ec;
  const auto status = std::filesystem::status(output, ec);
  if (std::filesystem::is_directory(status)) {
    throw OutputError(output.string() + ": " + what + " is a directory; give a file name inside it");
  }
  const std::string text = output.lexically_normal().string();
  const bool device_path = text.rfind("/dev/", 0) == 0 || text.rfind("/proc/", 0) == 0;
  if (device_path || (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))) {
    throw OutputError(output.string() + ": " + what +
                      " is not a regular file (a device, pipe or terminal); give a file name, or '-' for standard "
                      "output (the program's messages then go to standard error)");
  }
  for (const std::string& input : inputs) {
    if (!input.empty() && input != "-" && same_file(output, input)) {
      throw OutputError(output.string() + ": " + what + " is the input " + input +
                        " (or links to it); writing it would destroy the input, so choose another file name");
    }
  }
}

OutputFile::OutputFile(std::filesystem::path target, const std::vector<std::string>& inputs, const std::string& what)
    : target_(std::move(target)) {
  check_output_path(target_, inputs, what);
  if (target_ == "-") {
    to_stdout_ = true;
    return;
  }
  // Through a symbolic link, the file it names is replaced, not the link.
  std::error_code ec;
  if (std::filesystem::is_symlink(target_, ec)) target_ = std::filesystem::weakly_canonical(target_, ec);
  install_handlers_once();
  temporary_ = target_;
  temporary_ += ".partial-" + std::to_string(::getpid());
  slot_ = claim_slot(temporary_);
  file_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!file_) {
    release_slot(slot_);
    slot_ = -1;
    throw OutputError(target_.string() + ": cannot create the " + what +
                      " file; check that its folder exists and is writable");
  }
}

OutputFile::~OutputFile() {
  if (to_stdout_) return;
  if (!committed_) {
    file_.close();
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
  }
  release_slot(slot_);
}

void OutputFile::commit() {
  if (to_stdout_) {
    std::cout.flush();
    if (!std::cout) throw OutputError("standard output: writing failed (closed pipe or full disk)");
    committed_ = true;
    return;
  }
  file_.flush();
  const bool written = static_cast<bool>(file_);
  file_.close();
  std::error_code ec;
  if (!written || file_.fail()) {
    std::filesystem::remove(temporary_, ec);
    throw OutputError(target_.string() + ": writing failed (disk full?); nothing was written under that name");
  }
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) {
    const std::string why = ec.message();
    std::filesystem::remove(temporary_, ec);
    throw OutputError(target_.string() + ": cannot replace it (" + why + ")");
  }
  committed_ = true;
}

}  // namespace ftsense::io
