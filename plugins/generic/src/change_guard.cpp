#include "ftsense/generic/change_guard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace ftsense::generic {

void ChangeGuard::Params::describe(ParamSchema<Params>& schema) {
  schema.add("hold_s", &Params::hold_s, "how long the guard holds after a change (the transient's duration)")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.001, 5.0, "a landing's transient dies out within tenths of a second");
  schema.add("tolerance", &Params::tolerance, "a change larger than this counts (0: any change), in the input's unit")
      .at_least(0.0);
  schema.add_choice("scope", &Params::scope,
                    "any: every channel is guarded when any changes (a landing shifts every foot's load); own: "
                    "only the channel that changed",
                    {{"any", Scope::any}, {"own", Scope::own}});
}

ChangeGuard::ChangeGuard(const Params& params, const StageContext& context)
    : hold_s_(params.hold_s),
      tolerance_(params.tolerance),
      sample_period_s_(context.sample_period_s()),
      scope_(params.scope) {
  const std::size_t dim = context.wired_dim("state", 1);
  ports_.add_input(PortSpec{"state", dim, std::string(kAnyUnit),
                            "the state other signals follow abruptly (contact flags, a gait phase)",
                            PortRole::virtual_estimate}
                       .sized_by("as wired"));
  ports_.add_output(PortSpec{"guard", dim, std::string(kDimensionless),
                             "1 within hold_s after a change of the channels in scope, else 0"}
                        .sized_by("as `state`"));
  previous_.assign(dim, 0.0);
  since_change_s_.assign(dim, std::numeric_limits<double>::infinity());
}

void ChangeGuard::reset() noexcept {
  std::fill(previous_.begin(), previous_.end(), 0.0);
  std::fill(since_change_s_.begin(), since_change_s_.end(), std::numeric_limits<double>::infinity());
  started_ = false;
}

void ChangeGuard::step(const StepIO& io) noexcept {
  const auto state = io.in(kState);
  const auto guard = io.out(kGuard);
  double latest_change_s = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < previous_.size(); ++j) {
    const bool known = std::isfinite(state[j]);
    const bool changed =
        !known || (started_ && (!std::isfinite(previous_[j]) || std::abs(state[j] - previous_[j]) > tolerance_));
    since_change_s_[j] = changed ? 0.0 : since_change_s_[j] + sample_period_s_;
    previous_[j] = state[j];
    latest_change_s = std::min(latest_change_s, since_change_s_[j]);
  }
  started_ = true;
  // Half a tick of slack: hold_s of k ticks guards the changing tick and the k - 1 after it.
  const double hold = hold_s_ - 0.5 * sample_period_s_;
  for (std::size_t j = 0; j < previous_.size(); ++j) {
    const double since = scope_ == Scope::any ? latest_change_s : since_change_s_[j];
    guard[j] = since < hold ? 1.0 : 0.0;
  }
}

}  // namespace ftsense::generic
