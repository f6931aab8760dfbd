#include "ftsense/generic/change_guard.hpp"

#include <algorithm>
#include <cmath>
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
    : tolerance_(params.tolerance), scope_(params.scope) {
  const double ticks = std::round(params.hold_s / context.sample_period_s());
  if (!(ticks >= 1.0 && ticks <= 1e9)) {
    throw ConfigError("/params/hold_s", " = " + format_number(params.hold_s) + " s is " + format_number(ticks) +
                                            " ticks of " + format_number(context.sample_period_s()) +
                                            " s; the guard needs at least one tick");
  }
  hold_ticks_ = static_cast<std::size_t>(ticks);
  const std::size_t dim = context.wired_dim("state", 1);
  ports_.add_input(PortSpec{"state", dim, std::string(kAnyUnit),
                            "the state other signals follow abruptly (contact flags, a gait phase)",
                            PortRole::virtual_estimate}
                       .sized_by("as wired"));
  ports_.add_output(PortSpec{"guard", dim, std::string(kDimensionless),
                             "1 on the round(hold_s / T) ticks from a change of the channels in scope, else 0"}
                        .sized_by("as `state`"));
  previous_.assign(dim, 0.0);
  since_change_.assign(dim, hold_ticks_);
}

void ChangeGuard::reset() noexcept {
  std::fill(previous_.begin(), previous_.end(), 0.0);
  std::fill(since_change_.begin(), since_change_.end(), hold_ticks_);
  started_ = false;
}

void ChangeGuard::step(const StepIO& io) noexcept {
  const auto state = io.in(kState);
  const auto guard = io.out(kGuard);
  std::size_t latest_change = hold_ticks_;
  for (std::size_t j = 0; j < previous_.size(); ++j) {
    const bool known = std::isfinite(state[j]);
    const bool changed =
        !known || (started_ && (!std::isfinite(previous_[j]) || std::abs(state[j] - previous_[j]) > tolerance_));
    // 0 on the changing tick; the guard holds while under hold_ticks_.
    since_change_[j] = changed ? 0 : std::min(since_change_[j] + 1, hold_ticks_);
    previous_[j] = state[j];
    latest_change = std::min(latest_change, since_change_[j]);
  }
  started_ = true;
  for (std::size_t j = 0; j < previous_.size(); ++j) {
    const std::size_t since = scope_ == Scope::any ? latest_change : since_change_[j];
    guard[j] = since < hold_ticks_ ? 1.0 : 0.0;
  }
}

}  // namespace ftsense::generic
