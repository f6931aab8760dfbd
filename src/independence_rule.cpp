#include "ftsense/independence_rule.hpp"

#include <algorithm>
#include <iterator>

namespace ftsense {

void WireDependence::add(const SignalDependence& signal) {
  inputs_.insert(signal.inputs.begin(), signal.inputs.end());
  leaves_out_.insert(signal.leaves_out.begin(), signal.leaves_out.end());
  all_leave_one_out_ = all_leave_one_out_ && !signal.leaves_out.empty();
  empty_ = false;
}

std::set<std::string> WireDependence::shared_with(const std::set<std::string>& measured_inputs) const {
  std::set<std::string> independent = inputs_;
  if (!empty_ && all_leave_one_out_ && measured_inputs == leaves_out_) {
    for (const auto& name : leaves_out_) independent.erase(name);
  }
  std::set<std::string> shared;
  std::set_intersection(independent.begin(), independent.end(), measured_inputs.begin(), measured_inputs.end(),
                        std::inserter(shared, shared.begin()));
  return shared;
}

namespace {
void collect(const std::string& name, const std::vector<InputDerivation>& inputs, std::set<std::string>& out) {
  if (!out.insert(name).second) return;
  for (const auto& in : inputs) {
    if (in.name != name) continue;
    for (const auto& from : in.derived_from) collect(from, inputs, out);
  }
}
}  // namespace

std::set<std::string> input_dependencies(const std::string& name, const std::vector<InputDerivation>& inputs) {
  std::set<std::string> out;
  collect(name, inputs, out);
  return out;
}

std::string independence_breach(std::string_view virtual_what, std::string_view measured_what,
                                 const std::set<std::string>& shared) {
  std::string names;
  for (const auto& s : shared) names += (names.empty() ? "'" : ", '") + s + "'";
  return "independence rule: the virtual sensor " + std::string(virtual_what) + " is computed from " +
         (shared.size() > 1 ? "inputs " : "input ") + names + ", which is what " + std::string(measured_what) +
         " measures; a fault of that sensor would leak into its own reference (method.md section 0). Feed the "
         "virtual sensor from other signals (planned ZMP, kinematics)";
}

}  // namespace ftsense
