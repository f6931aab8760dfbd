#pragma once
// The height above the ground of each contact point of each foot, from the feet's poses: what
// tells a force sensor that its point of the foot is in the air and must read zero.
//
// Feet: foot_pos stacks N foot frame origins o_i (world frame, z up, m), foot_rpy their roll,
// pitch, yaw (R_i = Rz(yaw) Ry(pitch) Rx(roll)); every foot carries the contact points
// (x_l, y_l) of `points` on its sole plane (foot frame). Point feet ("points" empty, or [[0, 0]])
// are spheres of radius r (`foot_radius_m`) centred on the foot origin, whose lowest point is r
// below it whatever the foot's orientation (a rolling ball), so they need no foot_rpy:
//
//   h_il = (o_i + R_i [x_l, y_l, 0])_z - r - g,        foot_height_i = min_l h_il
//
// The ground g is `ground_height_m` (ground_reference = plane) or the lowest point of all feet
// (ground_reference = lowest_point: on flat ground a foot is always down; immune to a drifting
// world height of the base estimate the feet's poses come from).
//
// Outputs: point_height (N x P values, foot after foot, each in the order of `points`; P = 1 for
// point feet) and foot_height (N) [m]. NaN for a foot whose pose is not finite (with
// lowest_point, every foot: the ground is then unknown). foot_rpy is a port only when a point
// lies off the foot origin. A foot_pos whose size is not a multiple of 3 is a ConfigError.
// step() does not allocate.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::robot_model {

class ContactPointHeight {
 public:
  static constexpr std::string_view name = "contact_point_height";
  static constexpr std::string_view summary =
      "height above the ground of each contact point of each foot, from the feet's poses (soles or point feet)";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"({"points": [[0.12, 0.075], [0.12, -0.075], [-0.12, 0.075], [-0.12, -0.075]]})";

  struct Params {
    std::vector<std::array<double, 2>> points;
    double foot_radius_m = 0.0;
    enum class GroundReference { plane, lowest_point };
    GroundReference ground_reference = GroundReference::plane;
    double ground_height_m = 0.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kFootPos, kFootRpy };
  enum Output : std::size_t { kPointHeight, kFootHeight };

  ContactPointHeight(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  Params params_;
  std::size_t feet_ = 1;
  bool oriented_ = false;  // a point lies off the foot origin: foot_rpy is read
};

}  // namespace ftsense::robot_model
