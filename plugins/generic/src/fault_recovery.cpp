#include "ftsense/generic/fault_recovery.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "ftsense/generic/median_of_three.hpp"
#include "ftsense/generic/quantity_bounds.hpp"
#include "ftsense/low_pass_gain.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

void FaultRecovery::Params::describe(ParamSchema<Params>& schema) {
  schema.add_choice("correction", &Params::correction,
                    "subtract the fault estimate always (paper) or only while the channel is flagged",
                    {{"always", Correction::always}, {"when_flagged", Correction::when_flagged}});
  schema.add("substitute_types", &Params::substitute_types,
             "fault type names whose channel takes the virtual value instead");
  schema.add("blend_types", &Params::blend_types,
             "fault type names whose channel takes the virtual value plus a low-pass of measured - "
             "virtual (a noise burst: the reading still carries the load)");
  schema.add("median_types", &Params::median_types,
             "fault type names whose channel takes the median of its last three readings (spikes: one "
             "reading off both neighbours)");
  schema.add("lower_bound_types", &Params::lower_bound_types,
             "fault type names whose reading is a lower bound of the quantity (saturation at the top of its "
             "range): the recovered value is at least the reading, and where it is the reading the channel is "
             "not substituted; a type here is recovered as its list above says first. Only where the type means "
             "the top of the range (a force pad's clip): a clip at the bottom bounds from above");
  schema.add("blend_cutoff_hz", &Params::blend_cutoff_hz,
             "cut-off f_c of that low-pass, below 1 / (2 T): the band where the virtual value's own "
             "error lies")
      .unit("Hz")
      .greater_than(0.0).plausible(plausible::cutoff_hz());
  schema.add("floor", &Params::floor,
             "the least value the measured quantity can take (0 for a force pad that is pressed, never pulled), "
             "in the reading's unit: a flagged channel's recovered value is held at or above it; empty: none; one "
             "value applies to all");
  schema.add("ceiling", &Params::ceiling,
             "the greatest value the measured quantity can take, in the reading's unit: a flagged channel's "
             "recovered value is held at or below it; empty: none; one value applies to all");
}

void FaultRecovery::Params::validate(Diagnostics& diag, std::string_view path) const {
  std::vector<std::string> names;
  for (FaultType t : all_fault_types()) names.emplace_back(to_string(t));
  const auto check = [&](const std::vector<std::string>& types, std::string_view key) {
    for (std::size_t i = 0; i < types.size(); ++i) {
      if (!fault_type_from_string(types[i])) {
        diag.error(json_pointer_append(std::string(path) + "/" + std::string(key), i),
                   "unknown fault type '" + types[i] + "'; " + suggest(types[i], names));
      }
    }
  };
  check(substitute_types, "substitute_types");
  check(blend_types, "blend_types");
  check(median_types, "median_types");
  check(lower_bound_types, "lower_bound_types");
  // A fault type is recovered one way: a later list may not repeat an earlier one's name.
  const std::vector<std::pair<std::string_view, const std::vector<std::string>*>> lists{
      {"substitute_types", &substitute_types}, {"blend_types", &blend_types}, {"median_types", &median_types}};
  for (std::size_t later = 1; later < lists.size(); ++later) {
    for (std::size_t i = 0; i < lists[later].second->size(); ++i) {
      const std::string& type = (*lists[later].second)[i];
      for (std::size_t earlier = 0; earlier < later; ++earlier) {
        const auto& other = *lists[earlier].second;
        if (std::find(other.begin(), other.end(), type) == other.end()) continue;
        diag.error(json_pointer_append(std::string(path) + "/" + std::string(lists[later].first), i),
                   "'" + type + "' is also in " + std::string(lists[earlier].first) +
                       "; a fault type is recovered one way: remove it from one of the two lists");
      }
    }
  }
}

namespace {
std::size_t fault_code_index(const std::string& name) {
  return static_cast<std::size_t>(*fault_type_from_string(name));  // the enumerator is its code
}
}  // namespace

FaultRecovery::FaultRecovery(const Params& params, const StageContext& context)
    : correction_(params.correction) {
  mode_by_type_.fill(Mode::correct);
  // validate() refused unknown names and a type in two lists.
  for (const auto& t : params.substitute_types) mode_by_type_[fault_code_index(t)] = Mode::substitute;
  for (const auto& t : params.blend_types) mode_by_type_[fault_code_index(t)] = Mode::blend;
  for (const auto& t : params.median_types) mode_by_type_[fault_code_index(t)] = Mode::median;
  lower_bound_.fill(false);
  for (const auto& t : params.lower_bound_types) lower_bound_[fault_code_index(t)] = true;
  blend_gain_ = low_pass_gain(params.blend_cutoff_hz, context.sample_period_s(), "blend_cutoff_hz");
  const std::size_t dim = context.wired_dim("measured", 1);
  QuantityBounds bounds = quantity_bounds(params.floor, params.ceiling, dim);
  floor_ = std::move(bounds.floor);
  ceiling_ = std::move(bounds.ceiling);
  ports_.add_input(PortSpec{"measured", dim, std::string(kAnyUnit), "the monitored sensor"}.sized_by("as wired"));
  ports_.add_input(PortSpec{"fault_estimate", dim, std::string(kAnyUnit), "the estimated fault eta_hat"}
                       .sized_by("as `measured`"));
  ports_.add_input(PortSpec{"virtual", dim, std::string(kAnyUnit), "the virtual sensor's value"}
                       .sized_by("as `measured`"));
  ports_.add_input(PortSpec{"fault", dim, std::string(kDimensionless), "1 while the channel is flagged"}
                       .sized_by("as `measured`"));
  ports_.add_input(PortSpec{"fault_type", dim, std::string(kDimensionless), "the channel's fault type code"}
                       .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"recovered", dim, std::string(kAnyUnit), "the signal to use downstream"}
                        .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"correction", dim, std::string(kAnyUnit),
                             "what a relation's other channels subtract from this reading (sum_constraint_residual's "
                             "correction, one tick late): measured - recovered where that is the reading less an offset, "
                             "drift or gain estimate, else 0"}
                        .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"substituted", dim, std::string(kDimensionless),
                             "1 where the recovered value is the virtual one (substituted, a fallback on it, or an "
                             "estimate of measured - virtual): the reading stands for nothing (sum_constraint_residual's "
                             "substituted, one tick late)"}
                        .sized_by("as `measured`"));
  last_.assign(dim, 0.0);
  difference_lp_.assign(dim, 0.0);
  difference_seen_.assign(dim, 0);
  previous_readings_.assign(dim, {0.0, 0.0});
  previous_count_.assign(dim, 0);
}

void FaultRecovery::reset() noexcept {
  std::fill(last_.begin(), last_.end(), 0.0);
  std::fill(difference_lp_.begin(), difference_lp_.end(), 0.0);
  std::fill(difference_seen_.begin(), difference_seen_.end(), static_cast<unsigned char>(0));
  std::fill(previous_readings_.begin(), previous_readings_.end(), std::array<double, 2>{0.0, 0.0});
  std::fill(previous_count_.begin(), previous_count_.end(), static_cast<unsigned char>(0));
}


void FaultRecovery::step(const StepIO& io) noexcept {
  const auto measured = io.in(kMeasured);
  const auto fault_estimate = io.in(kFaultEstimate);
  const auto estimate = io.in(kVirtual);
  const auto fault = io.in(kFault);
  const auto type = io.in(kFaultType);
  const auto out = io.out(kRecovered);
  const auto own_correction = io.out(kCorrection);
  const auto substituted = io.out(kSubstituted);
  for (std::size_t j = 0; j < out.size(); ++j) {
    // A code that is not one of the table's is itself invalid data.
    const FaultType t = fault_type_from_code(type[j]).value_or(FaultType::invalid);
    const double difference = measured[j] - estimate[j];
    if (std::isfinite(difference)) {
      difference_lp_[j] = difference_seen_[j] ? difference_lp_[j] + blend_gain_ * (difference - difference_lp_[j])
                                              : difference;
      difference_seen_[j] = 1;
    }
    const Mode mode = mode_by_type_[static_cast<std::size_t>(t)];
    const bool substitute = !std::isfinite(measured[j]) || mode == Mode::substitute;
    const bool correct = correction_ == Correction::always || fault[j] != 0.0;
    const double corrected = correct ? measured[j] - fault_estimate[j] : measured[j];
    const bool blend = !substitute && std::isfinite(estimate[j]) && mode == Mode::blend;
    const bool median = !substitute && previous_count_[j] == 2 && mode == Mode::median;
    auto& previous = previous_readings_[j];
    double value = substitute ? estimate[j]
                   : blend    ? estimate[j] + difference_lp_[j]
                   : median   ? median_of_three(measured[j], previous[0], previous[1])
                              : corrected;
    if (std::isfinite(measured[j])) {
      previous[1] = previous[0];
      previous[0] = measured[j];
      previous_count_[j] = static_cast<unsigned char>(std::min(previous_count_[j] + 1, 2));
    } else {
      previous_count_[j] = 0;  // readings from before a gap are no neighbours of those after it
    }
    // What the others may take this reading for (output `correction`, header): corrected by a
    // fault model's estimate that lasts (offset, drift, gain); as it is (healthy, blended, a
    // median: a spike's correction is its own tick's, and read a tick late it would put the spike
    // into the others' virtual values on the tick after); or for nothing, where the value is the
    // virtual one (substituted, a fallback below, or an estimate of x - v, as fault_classifier's
    // for a fault not yet named).
    // (Mode::correct is neither blended nor a median.)
    const bool lasting_model = t == FaultType::offset || t == FaultType::drift || t == FaultType::gain;
    const bool corrected_by_model = !substitute && mode == Mode::correct && correct;
    bool stands_for_nothing = substitute || (corrected_by_model && fault[j] != 0.0 && !lasting_model);
    if (!std::isfinite(value)) {
      value = substitute ? corrected : estimate[j];
      stands_for_nothing = true;
    }
    if (!std::isfinite(value)) {
      value = last_[j];
      stands_for_nothing = true;
    }
    // A clipped reading bounds the value from below: where it is the larger, it is the value,
    // and stands for itself.
    if (fault[j] != 0.0 && lower_bound_[static_cast<std::size_t>(t)] && std::isfinite(measured[j]) &&
        !(value > measured[j])) {
      value = measured[j];
      stands_for_nothing = false;
    }
    const double lasting = measured[j] - value;
    if (fault[j] != 0.0) value = std::clamp(value, floor_[j], ceiling_[j]);
    out[j] = value;
    last_[j] = value;
    substituted[j] = stands_for_nothing ? 1.0 : 0.0;
    own_correction[j] = !stands_for_nothing && corrected_by_model && lasting_model && std::isfinite(lasting) ? lasting : 0.0;
  }
}

}  // namespace ftsense::generic
