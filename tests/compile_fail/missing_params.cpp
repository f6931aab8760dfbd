// Must NOT compile: no Params struct.
#include "ftsense/plugin_set.hpp"

struct Bad {
  static constexpr std::string_view name = "bad";
  static constexpr std::string_view summary = "breaks the contract";
  const ftsense::Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const ftsense::StepIO&) noexcept {}
  ftsense::Ports ports_;
};

int main() { return static_cast<int>(ftsense::PluginSet<Bad>::registry().names().size()); }
