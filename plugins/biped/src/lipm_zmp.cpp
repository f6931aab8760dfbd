#include "ftsense/biped/lipm_zmp.hpp"

#include <cmath>
#include <limits>

#include "ftsense/biped/frames.hpp"
#include "ftsense/biped/stacked_feet.hpp"

namespace ftsense::biped {

void LipmZmp::Params::describe(ParamSchema<Params>& schema) {
  schema.add("com_offset_x_m", &Params::com_offset_x_m, "dx: world-frame correction of the model's CoM, forward")
      .unit("m").plausible(-0.1, 0.1, "a model's CoM is millimetres to centimetres off");
  schema.add("com_offset_y_m", &Params::com_offset_y_m, "dy: world-frame correction of the model's CoM, lateral")
      .unit("m").plausible(-0.1, 0.1, "a model's CoM is millimetres to centimetres off");
}

LipmZmp::LipmZmp(const Params& params, const StageContext& context) : params_(params) {
  // Nothing wired sizes it for two feet; the pipeline reports the wire.
  feet_ = stacked_feet(context, 2);
  const std::size_t dim = 3 * feet_;
  ports_.add_input(PortSpec{"total_force", 3, "N", "total ground reaction force F (e.g. m R_wb f_imu, low-passed)"}
                       .in_frame("world"));
  ports_.add_input(PortSpec{"com", 3, "m", "CoM position c"}.in_frame("world"));
  ports_.add_input(PortSpec{"foot_pos", dim, "m", "foot frame origins (x, y, z) stacked; the lowest z is the ground"}
                       .in_frame("world")
                       .sized_by("as wired: 3 per foot"));
  ports_.add_output(PortSpec{"zmp", 2, "m", "ZMP (x, y) on the ground; NaN when not ready"}.in_frame("world"));
}

void LipmZmp::step(const StepIO& io) noexcept {
  const auto f = io.in(kTotalForce);
  const auto c = io.in(kCom);
  const auto feet = io.in(kFootPos);
  const auto zmp = io.out(kZmp);
  double ground = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < feet_; ++i) ground = std::fmin(ground, feet[3 * i + 2]);
  const bool ready = all_finite(f) && all_finite(c) && all_finite(feet) && f[2] > 0.0;
  if (!ready) {
    zmp[0] = zmp[1] = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const double height = c[2] - ground;  // the offset is horizontal: c'_z = c_z
  zmp[0] = c[0] + params_.com_offset_x_m - height * f[0] / f[2];
  zmp[1] = c[1] + params_.com_offset_y_m - height * f[1] / f[2];
}

}  // namespace ftsense::biped
