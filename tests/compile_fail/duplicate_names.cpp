// Must NOT compile: two plugins named alike in one set.
#include "ftsense/generic/generic_plugins.hpp"

struct AnotherLowPass : ftsense::generic::LowPass {
  using LowPass::LowPass;
};

int main() {
  return static_cast<int>(ftsense::generic::generic_plugins::with<AnotherLowPass>::registry().names().size());
}
