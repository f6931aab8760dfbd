#pragma once
// The independence rule (method.md section 0): a virtual sensor must not be computed from the
// sensor it judges, or a fault of that sensor leaks into its own reference and cancels in the
// residual. The pipeline checks it once, when it is built, for every stage input with role
// `virtual_estimate` against every input of the same stage with role `measured`, and for the
// monitor's `virtual` against its `measured`.
//
// Model. Every signal depends on a set of pipeline inputs D(s): an input depends on itself and,
// transitively, on the inputs it is `derived_from`; a stage output on everything its stage
// reads. A wire concatenating signals s_1..s_n depends on the union of their D(s_i).
// The rule: D(virtual) and D(measured) must not intersect, with one exception. An output marked
// `leave_one_out` computes channel j without channel j of its stage's measured input, whose
// dependencies L(s) it records. When every signal of the virtual wire is such an output and
// D(measured) == the union of their L(s), those inputs are independent channel by channel and do
// not count as shared.

#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace ftsense {

// What one signal depends on.
struct SignalDependence {
  std::set<std::string> inputs;      // D(s): pipeline input names
  std::set<std::string> leaves_out;  // L(s): non-empty only for leave-one-out outputs
};

// What a wire (one or more concatenated signals) depends on.
class WireDependence {
 public:
  void add(const SignalDependence& signal);
  [[nodiscard]] const std::set<std::string>& inputs() const noexcept { return inputs_; }
  // The inputs a virtual wire shares with a measured one under the rule above.
  [[nodiscard]] std::set<std::string> shared_with(const std::set<std::string>& measured_inputs) const;

 private:
  std::set<std::string> inputs_;
  std::set<std::string> leaves_out_;
  bool all_leave_one_out_ = true;
  bool empty_ = true;
};

struct InputDerivation {
  std::string name;
  std::vector<std::string> derived_from;
};
// D(input `name`): itself and, transitively, what it is derived from (cycles are harmless).
[[nodiscard]] std::set<std::string> input_dependencies(const std::string& name,
                                                       const std::vector<InputDerivation>& inputs);

// The sentence that explains a breach, e.g. "independence rule: the virtual sensor 'virtual' of
// stage 'residual' is computed from input 'forces', which is what 'measured' measures; ...".
[[nodiscard]] std::string independence_breach(std::string_view virtual_what, std::string_view measured_what,
                                              const std::set<std::string>& shared);

}  // namespace ftsense
