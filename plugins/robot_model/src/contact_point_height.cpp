#include "ftsense/robot_model/contact_point_height.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ftsense/biped/frames.hpp"
#include "ftsense/biped/stacked_feet.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::robot_model {

void ContactPointHeight::Params::describe(ParamSchema<Params>& schema) {
  schema.add("points", &Params::points,
             "contact points (x, y) of each foot on its sole plane, foot frame, every foot alike; empty: point feet "
             "at the foot origin")
      .unit("m").count_at_most(8).plausible(plausible::foot_point_m());
  schema.add("foot_radius_m", &Params::foot_radius_m,
             "radius r of a spherical point foot centred on the foot origin: its lowest point is r below it")
      .unit("m").at_least(0.0).plausible(0.0, 0.2, "a ball foot is millimetres to centimetres across");
  schema.add_choice("ground_reference", &Params::ground_reference,
                    "the ground the heights are measured from: the plane z = ground_height_m, or the lowest point "
                    "of all feet",
                    {{"plane", Params::GroundReference::plane}, {"lowest_point", Params::GroundReference::lowest_point}});
  schema.add("ground_height_m", &Params::ground_height_m, "height g of the ground plane z = g, world frame (plane)")
      .unit("m").plausible(plausible::ground_height_m());
}

ContactPointHeight::ContactPointHeight(const Params& params, const StageContext& context) : params_(params) {
  // Nothing wired sizes it for two feet; the pipeline reports the wire.
  feet_ = biped::stacked_feet(context, 2);
  const std::size_t dim = 3 * feet_;
  if (params_.points.empty()) params_.points = {{0.0, 0.0}};
  oriented_ = std::any_of(params_.points.begin(), params_.points.end(),
                          [](const std::array<double, 2>& p) { return p[0] != 0.0 || p[1] != 0.0; });
  const std::size_t n = feet_ * params_.points.size();
  ports_.add_input(PortSpec{"foot_pos", dim, "m", "foot frame origins (x, y, z) stacked foot after foot"}
                       .in_frame("world")
                       .sized_by("as wired: 3 per foot"));
  if (oriented_) {
    ports_.add_input(PortSpec{"foot_rpy", dim, "rad",
                              "foot orientations roll, pitch, yaw stacked foot after foot; a port only when a point "
                              "lies off the foot origin"}
                         .in_frame("foot in world")
                         .sized_by("3 per foot"));
  }
  ports_.add_output(PortSpec{"point_height", n, "m", "height above the ground of each contact point, foot after foot"}
                        .sized_by("feet x len(params.points) (1 for point feet)"));
  ports_.add_output(PortSpec{"foot_height", feet_, "m", "lowest contact point of each foot above the ground"}
                        .sized_by("feet (foot_pos / 3)"));
}

void ContactPointHeight::step(const StepIO& io) noexcept {
  const auto foot_pos = io.in(kFootPos);
  const auto point_height = io.out(kPointHeight);
  const auto foot_height = io.out(kFootHeight);
  const std::size_t points = params_.points.size();
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  bool all_known = true;
  for (std::size_t f = 0; f < feet_; ++f) {
    const auto pos = foot_pos.subspan(3 * f, 3);
    const auto rpy = oriented_ ? io.in(kFootRpy).subspan(3 * f, 3) : std::span<const double>();
    const bool known = biped::all_finite(pos) && biped::all_finite(rpy);
    all_known = all_known && known;
    // A point (x, y, 0) of the sole rises by the rotation's last row times it: R_zx x + R_zy y,
    // with R_zx = -sin(pitch), R_zy = cos(pitch) sin(roll) (frames.hpp). Yaw and cos(roll) do
    // not enter: two sines and a cosine per foot, not the whole rotation's three of each.
    double rise_x = 0.0, rise_y = 0.0;
    if (known && oriented_) {
      rise_x = -std::sin(rpy[1]);
      rise_y = std::cos(rpy[1]) * std::sin(rpy[0]);
    }
    double lowest = std::numeric_limits<double>::infinity();
    for (std::size_t l = 0; l < points; ++l) {
      const double h =
          known ? pos[2] + (rise_x * params_.points[l][0] + rise_y * params_.points[l][1]) - params_.foot_radius_m : kNaN;
      point_height[f * points + l] = h;
      lowest = std::min(lowest, h);
    }
    foot_height[f] = known ? lowest : kNaN;
  }
  double ground = params_.ground_height_m;
  if (params_.ground_reference == Params::GroundReference::lowest_point) {
    ground = all_known ? *std::min_element(foot_height.begin(), foot_height.end()) : kNaN;
  }
  for (double& h : point_height) h -= ground;
  for (double& h : foot_height) h -= ground;
}

}  // namespace ftsense::robot_model
