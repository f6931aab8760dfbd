#pragma once
// Centre of pressure of one foot (method.md section 3, the corrected paper eq. 10-12).
//
// For a rotationally stable robot the foot force F_i acts along a line through the CoM c. Its
// centre of pressure is where that line meets the sole plane, in foot frame i (origin o_i on the
// sole plane under the ankle, rotation R_i from the foot's roll, pitch, yaw):
//
//   d = R_i^T (c - o_i),   f = R_i^T F_i,   r_i = d_xy - (d_z / f_z) f_xy
//
// equivalently r_i = [-M_y / f_z, M_x / f_z] with M = d x f, the moment about the foot origin.
// r_i is clamped to the support polygon (the convex hull of the contact points). When
// f_z < min_normal_force_N (swing, flight, a foot barely touching) there is no division: the
// CoP is the polygon's centroid, `loaded` is 0 and normal_force is max(f_z, 0). A non-finite
// input (the IMU or kinematics not available) makes cop and normal_force NaN and loaded 0.

#include <array>
#include <string_view>
#include <vector>

#include "ftsense/biped/frames.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class FootCop {
 public:
  static constexpr std::string_view name = "foot_cop";
  static constexpr std::string_view summary =
      "CoP of one foot where the force line through the CoM meets the sole (eq. 10-12, corrected)";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"({"points": [[0.12, 0.075], [0.12, -0.075], [-0.12, 0.075], [-0.12, -0.075]]})";

  struct Params {
    std::vector<std::array<double, 2>> points;
    double min_normal_force_N = 5.0;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kCom, kForce, kFootPos, kFootRpy };
  enum Output : std::size_t { kCop, kNormalForce, kLoaded };

  FootCop(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const StepIO& io) noexcept;

 private:
  Ports ports_;
  SupportPolygon polygon_;
  double min_normal_force_N_;
};

}  // namespace ftsense::biped
