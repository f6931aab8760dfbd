#pragma once
// The limbs' inertia added to a total ground reaction force estimated from the trunk's IMU.
//
// F = M R_wb f_imu (total_ground_force, leg_force_split) takes every kilogram of the robot to
// accelerate like the trunk: F = M (a_t + g e_z), a_t = F / M - g e_z the trunk's acceleration
// [m/s^2], world frame. A swinging leg does not: the ground also pushes its mass m_l (`leg_mass_kg`)
// by what it accelerates beyond the trunk. With each leg's mass taken to move with its foot
// (foot origin p_i, world frame, m),
//
//   F' = F + m_l sum_i (a_i - a_t),      a_i = d^2 p_i / dt^2,                      [N]
//
// On the simulated SURALP (legs of 16 kg, 114 kg in all) the error of F_z in a fault-free walk
// falls from 20 N to 11 N RMS (slow gait) and from 35 N to 17 N (fast gait) (tools: see
// docs/results.md). The acceleration is the second difference of p_i after two first-order
// low-passes of cut-off f_c (`cutoff_hz`, the legs' motion bandwidth; it rejects the positions'
// noise, which the second difference multiplies by 1 / T^2), exp-discretised so that the same
// f_c holds at any rate; a_t passes through the same two low-passes so that both terms lag alike
// (about 2 / (2 pi f_c) s). m_l = 0 returns F unchanged.
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
  static constexpr std::string_view example_params = R"({"mass_kg": 114.0, "leg_mass_kg": 16.0})";

  struct Params {
    double mass_kg = 0.0;
    double leg_mass_kg = 0.0;
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
