#pragma once
// The limbs' inertia added to a total ground reaction force estimated from the trunk's IMU.
//
// F = M R_wb f_imu (total_ground_force, leg_force_split) takes every kilogram of the robot to
// accelerate like the trunk: F = M (a_t + g e_z), a_t = F / M - g e_z the trunk's acceleration
// [m/s^2], world frame. A swinging leg does not: the ground also pushes its links by what they
// accelerate beyond the trunk. Each link s of a leg (mass m_s) is taken to move with the share
// rho_s of its foot's motion relative to the hip, rho_s = the link CoM's distance from the hip
// over the foot's, leg straight (exact for a rigid leg swinging about the hip; the thigh barely
// follows a foot lifted by the knee). With the foot origin p_i [m, world frame],
//
//   F' = F + m_e sum_i (a_i - a_t),   m_e = sum_s m_s rho_s,   a_i = d^2 p_i / dt^2,   [N]
//
// m_e is `leg_effective_mass_kg`. The simulated SURALP's legs weigh 16 kg: hip links 2 kg at
// rho = 0, thigh 6.5 kg at 0.21, shank 4 kg at 0.62, ankle link 0.5 kg at 0.82, foot and pads
// 3 kg at 0.95-1 (sim/include/ftsense/sim/robot_model.hpp), m_e = 7.1 kg. There, the error of F_z
// below 10 Hz in a fault-free walk falls from 8.2 to 5.2 N RMS (slow gait) and from 12.6 to
// 8.4 N (fast gait) (ctest limb_inertia_total_force); taking the whole 16 kg to move with the foot
// leaves 6.8 and 10.5 N (its script with 16 kg in the config; docs/results.md). The acceleration
// is the second difference of p_i after two first-order low-passes of cut-off f_c (`cutoff_hz`,
// the legs' motion bandwidth; it rejects the positions' noise, which the second difference
// multiplies by 1 / T^2), exp-discretised so that the same f_c holds at any rate; a_t passes
// through the same two low-passes so that both terms lag alike (about 2 / (2 pi f_c) s).
// m_e = 0 returns F unchanged.
//
// Ports: total_force (3, N, world) and foot_pos (3 per foot, stacked as wired, m, world) in;
// total_force (3, N, world) out. A non-finite input gives NaN (the virtual sensor not ready) and
// leaves the filters as they were; the first finite sample of each position starts its filter
// there, and the correction is 0 until each filter has three samples. Allocation-free.

#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class LimbInertiaCorrection {
 public:
  static constexpr std::string_view name = "limb_inertia_correction";
  static constexpr std::string_view summary =
      "adds the swinging legs' inertia to a total ground force estimated from the trunk's acceleration";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params = R"({"mass_kg": 114.0, "leg_effective_mass_kg": 7.1})";

  struct Params {
    double mass_kg = 0.0;
    double leg_effective_mass_kg = 0.0;
    double cutoff_hz = 10.0;
    double gravity_m_s2 = 9.806;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kTotalForce, kFootPos };
  enum Output : std::size_t { kCorrectedForce };

  LimbInertiaCorrection(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  // Two cascaded first-order low-passes and the last three outputs, per signal.
  struct Smoothed {
    double first = 0.0, second = 0.0;
    double history[3] = {0.0, 0.0, 0.0};  // the last three outputs, newest first
    int samples = 0;                      // up to 3
    void add(double x, double gain) noexcept;
    [[nodiscard]] double second_difference() const noexcept {
      return history[0] - 2.0 * history[1] + history[2];
    }
  };

  Ports ports_;
  Params params_;
  double period_s_;
  double gain_;  // of each first-order low-pass per tick
  std::size_t feet_;
  std::vector<Smoothed> feet_pos_;  // 3 per foot
  Smoothed trunk_[3];               // a_t per axis
};

}  // namespace ftsense::biped
