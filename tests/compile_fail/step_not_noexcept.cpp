// Must NOT compile: step() may throw. The plugin set names the broken rule.
#include "ftsense/plugin_set.hpp"

struct Bad {
  static constexpr std::string_view name = "bad";
  static constexpr std::string_view summary = "breaks the contract";
  struct Params {
    static void describe(ftsense::ParamSchema<Params>&) {}
  };
  Bad(const Params&, const ftsense::StageContext&) {}
  const ftsense::Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const ftsense::StepIO&) {}  // not noexcept
  ftsense::Ports ports_;
};

int main() { return static_cast<int>(ftsense::PluginSet<Bad>::registry().names().size()); }
