#pragma once
// One verdict per channel from the verdicts of several FDI parts (a signal validator judging the
// raw samples, an isolator and a classifier judging a constraint residual, ...).
//
// Model. n sources (`sources`) each give, per channel j, a flag f_kj (nonzero and finite: flagged)
// and a fault type code c_kj (fault_type.hpp), wired as one input each: `fault` = [f_1 ... f_n],
// `fault_type` = [c_1 ... c_n], source after source. Then
//
//   fault_j   = 1 if any source flags j, else 0
//   type_j    = the type of the flagging sources that comes first in `type_priority`; a flagged
//               source whose code is none, unclassified or not a type counts as unclassified,
//               which comes after every named type
//   source_j  = k (1-based) of the source whose type was taken; the first of equals; 0 unflagged
//   cannot_judge_j (with input `cannot_judge`) = 1 while its input is nonzero and finite and no
//               source flags j, else 0: a verdict from any part ends "cannot judge"
//
// Why a type order and not a source order: the evidence behind each type differs in how specific it
// is. A value that is not a number, or one at the sensor's range limit, is certain on one sample;
// a frozen output, then a gain, drift or offset fitted over seconds explain a channel's whole
// misbehaviour; a raised noise level or a spike count is what several of those also produce (a
// gain x1.5 scales the sensor's noise by 1.5). So the default order is invalid, saturation, frozen,
// gain, drift, offset, noise, spikes. Allocation-free: nothing is sized per tick.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "ftsense/fault_type.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class FaultMerge {
 public:
  static constexpr std::string_view name = "fault_merge";
  static constexpr std::string_view summary =
      "one fault flag and type per channel from several parts' verdicts, the most specific type first";
  // For the config reference's port table and the schema (plugin.hpp): input cannot_judge is optional.
  static constexpr std::string_view example_params = R"([{}, {"cannot_judge": true}])";

  struct Params {
    int sources = 2;
    std::vector<std::string> type_priority{"invalid", "saturation", "frozen", "gain",
                                           "drift",   "offset",     "noise",  "spikes"};
    bool cannot_judge = false;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
  };

  enum Input : std::size_t { kFault, kFaultType, kCannotJudge };
  enum Output : std::size_t { kMergedFault, kMergedType, kSource, kMergedCannotJudge };

  FaultMerge(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  std::size_t sources_ = 2;
  std::size_t channels_ = 1;
  bool cannot_judge_ = false;
  std::array<int, kFaultTypes.size()> rank_{};  // per type code: its place in the order, lower first
};

}  // namespace ftsense::generic
