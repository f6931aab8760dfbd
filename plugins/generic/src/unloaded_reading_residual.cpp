#include "ftsense/generic/unloaded_reading_residual.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ftsense/channel_values.hpp"

namespace ftsense::generic {

void UnloadedReadingResidual::Params::describe(ParamSchema<Params>& schema) {
  schema.add("settle_s", &Params::settle_s,
             "time a channel must have been unable to carry load before it is judged")
      .unit("s")
      .at_least(0.0)
      .plausible(0.0, 5.0, "a part of a swing phase (0.2 to 1 s)");
  schema.add("zero", &Params::zero,
             "reading z_j of a healthy unloaded sensor, in the reading's unit; one value applies to all")
      .count_at_least(1);
}

UnloadedReadingResidual::UnloadedReadingResidual(const Params& params, const StageContext& context)
    : settle_s_(params.settle_s), sample_period_s_(context.sample_period_s()) {
  const std::size_t dim = context.wired_dim("signal", params.zero.size());
  zero_ = channel_values(params.zero, dim, "zero");
  ports_.add_input(
      PortSpec{"signal", dim, std::string(kAnyUnit), "the readings x", PortRole::measured}.sized_by("as wired"));
  ports_.add_input(PortSpec{"loadable", dim, std::string(kDimensionless),
                            "1 while channel j can carry load (its contact point on the ground), 0 while it cannot "
                            "(below 1/2: cannot)",
                            PortRole::virtual_estimate}
                       .sized_by("as `signal`"));
  ports_.add_output(PortSpec{"residual", dim, std::string(kAnyUnit),
                             "x_j - z_j while channel j has been unable to carry load for settle_s, else NaN"}
                        .sized_by("as `signal`"));
  unloaded_for_s_.assign(dim, 0.0);
}

void UnloadedReadingResidual::reset() noexcept { std::fill(unloaded_for_s_.begin(), unloaded_for_s_.end(), 0.0); }

void UnloadedReadingResidual::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto loadable = io.in(kLoadable);
  const auto r = io.out(kResidual);
  for (std::size_t j = 0; j < zero_.size(); ++j) {
    // Unknown (NaN) counts as loadable: nothing is judged on a guess.
    if (loadable[j] < 0.5) {
      unloaded_for_s_[j] += sample_period_s_;
    } else {
      unloaded_for_s_[j] = 0.0;
    }
    // Half a tick of slack: settle_s of k ticks judges from the k-th unloaded tick on.
    const bool judged = unloaded_for_s_[j] >= settle_s_ - 0.5 * sample_period_s_ && unloaded_for_s_[j] > 0.0;
    r[j] = judged ? x[j] - zero_[j] : std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace ftsense::generic
