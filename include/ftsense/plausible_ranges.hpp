#pragma once
// Plausible ranges that several plugins' parameters share (params.hpp: a value outside its
// plausible range is a warning, not an error).
//
// They span every real legged robot, from a 1 kg toy to a 300 kg machine (weight 10 N to 3 kN,
// landing impacts up to about 10 kN), with feet tens of centimetres long, ticking at 100 Hz to
// 10 kHz (T = 10 ms to 0.1 ms), plus margin: a warning means a unit slip (grams for kilograms,
// millimetres for metres) or a typo (1e-300), never an unusual robot. A range used by one
// parameter only is written at that parameter.

#include "ftsense/params.hpp"

namespace ftsense::plausible {

// The total mass of a robot [kg].
inline PlausibleRange robot_mass_kg() {
  return {0.5, 1000.0, "robot mass: 1 kg toys to 300 kg machines"};
}

// Low-pass cut-off frequency f_c [Hz]: tau = 1 / (2 pi f_c) from 160 s down to the Nyquist
// frequency of the fastest loop.
inline PlausibleRange cutoff_hz() {
  return {1e-3, 5000.0, "a 160 s time constant to the Nyquist frequency of a 10 kHz loop"};
}

// A contact point's or sole outline point's coordinate in its foot frame [m].
inline PlausibleRange foot_point_m() {
  return {-1.0, 1.0, "feet are tens of centimetres long"};
}

// A height of a foot or pad above the ground that decides contact or flight [m].
inline PlausibleRange foot_height_m() {
  return {1e-5, 0.2, "micrometres to a step height of tens of centimetres"};
}

// The height of the ground plane in the world frame [m].
inline PlausibleRange ground_height_m() {
  return {-10.0, 10.0, "the floor lies within metres of the world origin"};
}

// A force threshold that judges a sensor: above its noise, below the largest load [N].
inline PlausibleRange force_threshold_N() {
  return {0.01, 1e4, "above sensor noise, below the landing impacts of a 300 kg robot (about 10 kN)"};
}

// A load below which a quantity (CoP, ZMP) is undefined: a small share of the weight [N].
inline PlausibleRange min_load_N() {
  return {0.01, 1000.0, "a small share of the weight: 10 N for a 1 kg robot, 3 kN for 300 kg"};
}

// A delay or hold time of a fault flag [s].
inline PlausibleRange flag_delay_s() {
  return {0.0, 60.0, "flags are delayed or held for up to seconds, not minutes"};
}

}  // namespace ftsense::plausible
