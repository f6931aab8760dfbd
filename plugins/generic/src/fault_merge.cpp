#include "ftsense/generic/fault_merge.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace ftsense::generic {

void FaultMerge::Params::describe(ParamSchema<Params>& schema) {
  schema.add("sources", &Params::sources,
             "n, the parts whose verdicts are merged; inputs fault and fault_type each take n x channels values, "
             "source after source (the channels are the wired values / n: check n against the wiring)")
      .at_least(2)
      .at_most(16);
  schema.add("type_priority", &Params::type_priority,
             "fault type names, the most specific first: a channel several sources flag takes the first of their "
             "types in this list; unlisted named types follow in code order, unclassified last");
  schema.add("cannot_judge", &Params::cannot_judge,
             "adds input cannot_judge (one per channel) and output cannot_judge: 1 while that input is nonzero "
             "and finite and no source flags the channel");
}

void FaultMerge::Params::validate(Diagnostics& diag, std::string_view path) const {
  std::vector<std::string> names;
  for (FaultType t : sensor_fault_types()) names.emplace_back(to_string(t));
  for (std::size_t i = 0; i < type_priority.size(); ++i) {
    const auto type = fault_type_from_string(type_priority[i]);
    if (!type || *type == FaultType::none || *type == FaultType::unclassified) {
      diag.error(json_pointer_append(std::string(path) + "/type_priority", i),
                 "'" + type_priority[i] + "' is not a sensor fault type; " + suggest(type_priority[i], names));
      continue;
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (type_priority[k] == type_priority[i]) {
        diag.error(json_pointer_append(std::string(path) + "/type_priority", i),
                   "'" + type_priority[i] + "' is listed twice (first at " + std::to_string(k) + "); list each type once");
      }
    }
  }
}

FaultMerge::FaultMerge(const Params& params, const StageContext& context)
    : sources_(static_cast<std::size_t>(params.sources)), cannot_judge_(params.cannot_judge) {
  const std::size_t wired = context.wired_dim("fault", sources_);
  if (wired % sources_ != 0) {
    throw ConfigError("/params/sources", " = " + std::to_string(sources_) + " does not divide the " +
                                             std::to_string(wired) + " wired fault flags into whole sources");
  }
  channels_ = wired / sources_;
  // Listed types first, in the list's order; then the other named types in code order; unclassified
  // (and none, which never decides) last.
  int place = 0;
  rank_.fill(std::numeric_limits<int>::max());
  for (const std::string& name : params.type_priority) {
    rank_[static_cast<std::size_t>(*fault_type_from_string(name))] = place++;
  }
  for (FaultType t : sensor_fault_types()) {
    int& r = rank_[static_cast<std::size_t>(t)];
    if (r == std::numeric_limits<int>::max()) r = place++;
  }
  rank_[static_cast<std::size_t>(FaultType::unclassified)] = place;
  ports_.add_input(PortSpec{"fault", wired, std::string(kDimensionless),
                            "each source's flags, source after source (nonzero and finite: flagged)"}
                       .sized_by("sources x channels, as wired"));
  ports_.add_input(PortSpec{"fault_type", wired, std::string(kDimensionless),
                            "each source's fault type codes (fault_type.hpp), in the order of `fault`"}
                       .sized_by("as `fault`"));
  if (cannot_judge_) {
    ports_.add_input(PortSpec{"cannot_judge", channels_, std::string(kDimensionless),
                              "1 while a part cannot judge the channel (e.g. an isolator's)"}
                         .sized_by("fault / sources"));
  }
  ports_.add_output(PortSpec{"fault", channels_, std::string(kDimensionless), "1 while any source flags the channel"}
                        .sized_by("fault / sources"));
  ports_.add_output(PortSpec{"fault_type", channels_, std::string(kDimensionless),
                             "the flagging sources' type that comes first in type_priority; none when unflagged"}
                        .sized_by("fault / sources"));
  ports_.add_output(PortSpec{"source", channels_, std::string(kDimensionless),
                             "which source's type was taken (1 to n, as wired); 0 when unflagged"}
                        .sized_by("fault / sources"));
  if (cannot_judge_) {
    ports_.add_output(PortSpec{"cannot_judge", channels_, std::string(kDimensionless),
                               "1 while input cannot_judge is nonzero and finite and no source flags the channel, else 0"}
                          .sized_by("fault / sources"));
  }
}

void FaultMerge::step(const StepIO& io) noexcept {
  const auto flag = io.in(kFault);
  const auto code = io.in(kFaultType);
  const auto fault = io.out(kMergedFault);
  const auto type = io.out(kMergedType);
  const auto source = io.out(kSource);
  for (std::size_t j = 0; j < channels_; ++j) {
    FaultType best = FaultType::none;
    int best_rank = std::numeric_limits<int>::max();
    std::size_t best_source = 0;
    for (std::size_t k = 0; k < sources_; ++k) {
      const double f = flag[k * channels_ + j];
      if (!(std::isfinite(f) && f != 0.0)) continue;
      FaultType t = fault_type_from_code(code[k * channels_ + j]).value_or(FaultType::unclassified);
      if (t == FaultType::none) t = FaultType::unclassified;  // flagged: a fault, its type unknown
      const int rank = rank_[static_cast<std::size_t>(t)];
      if (best_source == 0 || rank < best_rank) {
        best = t;
        best_rank = rank;
        best_source = k + 1;
      }
    }
    fault[j] = best_source > 0 ? 1.0 : 0.0;
    type[j] = fault_code(best);
    source[j] = static_cast<double>(best_source);
    if (cannot_judge_) {
      const double c = io.in(kCannotJudge)[j];
      io.out(kMergedCannotJudge)[j] = best_source == 0 && std::isfinite(c) && c != 0.0 ? 1.0 : 0.0;
    }
  }
}

}  // namespace ftsense::generic
