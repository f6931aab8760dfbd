#pragma once
// The soles the contact-force QP benchmarks solve on: a 0.240 x 0.150 m foot with 4 points at its
// corners (SURALP, configs/suralp.json) or 8 points on its outline, W = 0.01 I.
#include "ftsense/biped/contact_force_qp.hpp"

namespace ftsense::biped::bench {

inline ContactGeometry sole(int points) {
  if (points == 4) return ContactGeometry::rectangle(0.240, 0.150);
  ContactGeometry geometry;  // 8 points on the outline
  geometry.points.resize(2, 8);
  geometry.points << 0.12, 0.12, 0.04, -0.06, -0.12, -0.12, -0.06, 0.04,  //
      0.05, -0.05, -0.075, -0.065, -0.04, 0.04, 0.065, 0.075;
  geometry.weights = ContactVector::Constant(8, 0.01);
  return geometry;
}

}  // namespace ftsense::biped::bench
