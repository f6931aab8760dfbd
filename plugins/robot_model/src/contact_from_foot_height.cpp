#include "ftsense/robot_model/contact_from_foot_height.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ftsense/biped/stacked_feet.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::robot_model {

void ContactFromFootHeight::Params::describe(ParamSchema<Params>& schema) {
  schema.add("ground_height_m", &Params::ground_height_m, "height g of the ground plane z = g, world frame")
      .unit("m").plausible(plausible::ground_height_m());
  schema.add("touchdown_height_m", &Params::touchdown_height_m,
             "a foot in swing touches down when its height above the ground comes below this")
      .unit("m").greater_than(0.0).required().plausible(plausible::foot_height_m());
  const PlausibleRange foot_height = plausible::foot_height_m();
  schema.add("liftoff_height_m", &Params::liftoff_height_m,
             "a foot in contact lifts off when its height above the ground rises above this (>= "
             "touchdown_height_m: a hysteresis); 0: the touchdown height")
      .unit("m").at_least(0.0)
      .plausible(0.0, foot_height.high, "0: the touchdown height; else " + foot_height.reason);
}

void ContactFromFootHeight::Params::validate(Diagnostics& diag, std::string_view path) const {
  if (liftoff_height_m > 0.0 && liftoff_height_m < touchdown_height_m) {
    diag.error(json_pointer_append(path, "liftoff_height_m"),
               " = " + format_number(liftoff_height_m) + " is below touchdown_height_m = " +
                   format_number(touchdown_height_m) +
                   "; a foot lifts off at or above the height it touches down (0: the same height)");
  }
}

ContactFromFootHeight::ContactFromFootHeight(const Params& params, const StageContext& context)
    : ground_height_m_(params.ground_height_m),
      touchdown_height_m_(params.touchdown_height_m),
      liftoff_height_m_(params.liftoff_threshold_m()) {
  // Nothing wired sizes it for one foot; the pipeline reports the wire.
  const std::size_t feet = biped::stacked_feet(context, 1);
  const std::size_t dim = 3 * feet;
  ports_.add_input(PortSpec{"foot_pos", dim, "m", "foot frame origins (x, y, z) stacked foot after foot"}
                       .in_frame("world")
                       .sized_by("as wired: 3 per foot"));
  ports_.add_output(PortSpec{"contact", feet, std::string(kDimensionless),
                             "per foot: 1 in contact, 0 in swing, NaN while its height is not finite"}
                        .sized_by("feet (foot_pos / 3)"));
  state_.assign(feet, State::unknown);
}

void ContactFromFootHeight::reset() noexcept { std::fill(state_.begin(), state_.end(), State::unknown); }

void ContactFromFootHeight::step(const StepIO& io) noexcept {
  const auto foot_pos = io.in(kFootPos);
  const auto contact = io.out(kContact);
  for (std::size_t i = 0; i < state_.size(); ++i) {
    const double height = foot_pos[3 * i + 2] - ground_height_m_;
    if (!std::isfinite(height)) {
      contact[i] = std::numeric_limits<double>::quiet_NaN();  // unknown now; the state holds
      continue;
    }
    State& s = state_[i];
    if (s == State::unknown) {
      s = height < touchdown_height_m_ ? State::contact : State::swing;
    } else if (s == State::swing && height < touchdown_height_m_) {
      s = State::contact;
    } else if (s == State::contact && height > liftoff_height_m_) {
      s = State::swing;
    }
    contact[i] = s == State::contact ? 1.0 : 0.0;
  }
}

}  // namespace ftsense::robot_model
