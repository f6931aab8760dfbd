#pragma once
// A contact state per foot from the height of its frame origin, for logs without a contact plan.
//
// Input foot_pos stacks N foot frame origins p_i (world frame, z up, m): 3 N values, e.g. the
// wiring "foot_pos": ["input.l_foot_pos", "input.r_foot_pos"] gives N = 2. With the height
// h_i = p_i,z - g above the ground plane z = g (`ground_height_m`), foot i switches
//
//   swing -> contact   when h_i < h_td   (`touchdown_height_m`)
//   contact -> swing   when h_i > h_lo   (`liftoff_height_m` >= h_td; 0 means h_lo = h_td)
//
// and keeps its state in between: the band [h_td, h_lo] is a hysteresis, so a foot hovering at
// one height (or a noisy height near it) does not chatter. The first finite height after reset
// decides the initial state with h_td (contact when h_i < h_td). Output contact_i is 1 in
// contact, 0 in swing and NaN while h_i is not finite (unknown); the state holds through a NaN
// and is continued by the next finite height. The height is of the frame origin, not of the
// sole: choose h_td above the origin's height over the sole when standing.
//
// A foot_pos whose size is not a multiple of 3 is a ConfigError (/inputs/foot_pos).
// step() does not allocate.

#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::robot_model {

class ContactFromFootHeight {
 public:
  static constexpr std::string_view name = "contact_from_foot_height";
  static constexpr std::string_view summary =
      "contact state per foot from its height above the ground, with touchdown/liftoff hysteresis";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"({"touchdown_height_m": 0.02})";

  struct Params {
    double ground_height_m = 0.0;
    double touchdown_height_m = 0.0;
    double liftoff_height_m = 0.0;
    static void describe(ParamSchema<Params>& schema);
    void validate(Diagnostics& diag, std::string_view path) const;
    // h_lo of the header: liftoff_height_m, or touchdown_height_m when that is 0.
    [[nodiscard]] double liftoff_threshold_m() const noexcept {
      return liftoff_height_m > 0.0 ? liftoff_height_m : touchdown_height_m;
    }
  };

  enum Input : std::size_t { kFootPos };
  enum Output : std::size_t { kContact };

  ContactFromFootHeight(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  [[nodiscard]] std::size_t foot_count() const noexcept { return state_.size(); }

 private:
  enum class State : unsigned char { unknown, swing, contact };

  Ports ports_;
  double ground_height_m_;
  double touchdown_height_m_;
  double liftoff_height_m_;
  std::vector<State> state_;
};

}  // namespace ftsense::robot_model
