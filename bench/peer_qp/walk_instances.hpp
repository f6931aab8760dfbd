#pragma once
// The contact-force QP instances the pipeline solves on a simulated walk (bench/peer_qp).
//
// A SURALP walk (MuJoCo, configs/scenarios/clean.json, the given length and seed) runs through
// configs/suralp.json. At every tick where a foot's distribution stage (vfs_l, vfs_r) answered
// with status optimal, the normal force F_z [N] and CoP r [m] that stage received, and the forces
// it output, make one instance of that foot; zero-load ticks (swing) and the ticks before the
// virtual sensor is ready are left out. The solver keeps its warm-start state across them, so
// the instances of one foot, in time order, are exactly the sequence its solver saw.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ftsense/biped/contact_force_qp.hpp"

namespace ftsense::peer_qp {

struct FootInstance {
  double fz = 0.0;                                ///< [N]
  Eigen::Vector2d cop = Eigen::Vector2d::Zero();  ///< [m], foot frame
};

struct WalkInstances {
  std::size_t ticks = 0;
  biped::ContactGeometry geometry;                ///< the config's foot (both feet alike)
  std::array<std::vector<FootInstance>, 2> feet;  ///< left, right
  /// Per foot, what the pipeline output: n forces [N] per instance, one instance after another.
  std::array<std::vector<double>, 2> pipeline_forces;
};

// Throws std::runtime_error if the config's two distribution stages differ in geometry.
WalkInstances record_walk_instances(const std::string& source_dir, double seconds, std::uint64_t seed);

}  // namespace ftsense::peer_qp
