// ZMP preview control: Riccati solution, tracking of a step and of a walking-like reference.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include "ftsense/sim/preview_control.hpp"

using namespace ftsense::sim;

TEST(PreviewControl, RiccatiSolutionSatisfiesTheEquationAndIsStabilising) {
  const ZmpPreviewController pc(0.001, 0.7, 9.806, 1.6);
  const Eigen::Matrix3d& P = pc.riccati_solution();
  EXPECT_LT(pc.riccati_residual(), 1e-9 * std::max(1.0, P.cwiseAbs().maxCoeff()));
  EXPECT_LT((P - P.transpose()).cwiseAbs().maxCoeff(), 1e-12 * P.cwiseAbs().maxCoeff());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(P);
  EXPECT_GE(es.eigenvalues().minCoeff(), 0.0);
  const Eigen::Matrix3d Ac = pc.A() - pc.B() * pc.state_gain();
  const auto ev = Ac.eigenvalues();
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(ev[i]), 1.0);
  // Preview gains decay (the far future matters little); the last gain carries the tail, so
  // that the gains sum to the position gain and a constant reference has no steady-state error.
  const auto& f = pc.preview_gains();
  ASSERT_EQ(f.size(), 1600u);
  EXPECT_LT(std::abs(f[f.size() - 2]), 1e-2 * std::abs(f.front()));
  double fsum = 0.0;
  for (double fj : f) fsum += fj;
  const Eigen::RowVector3d& K = pc.state_gain();
  // At rest at c: u = -K0 c + sum(f) p, with p = c  =>  sum(f) = K0.
  EXPECT_NEAR(fsum, K[0], 1e-6 * K[0]);
}

TEST(PreviewControl, TracksAStepOfTheReferenceAndEndsAtRest) {
  const double dt = 0.001;
  const ZmpPreviewController pc(dt, 0.7, 9.806, 1.6);
  std::vector<double> ref(6000, 0.0);
  for (std::size_t k = 2000; k < ref.size(); ++k) ref[k] = 0.1;
  const auto x = pc.track(ref, Eigen::Vector3d::Zero());
  const Eigen::Vector3d& end = x.back();
  EXPECT_NEAR(end[0], 0.1, 1e-4);
  EXPECT_NEAR(end[1], 0.0, 1e-4);
  // Cart-table ZMP follows the reference except around the step.
  for (std::size_t k = 0; k < ref.size(); ++k) {
    const double p = pc.C() * x[k];
    if (k < 1000 || k > 3500) {
      EXPECT_NEAR(p, ref[k], 2e-3) << k;
    }
  }
}

TEST(PreviewControl, WalkingReferenceIsTrackedWithinMillimetres) {
  // Lateral ZMP alternating +-0.1 m each 1 s with 0.2 s ramps (the gait generator's shape).
  const double dt = 0.001;
  const ZmpPreviewController pc(dt, 0.7, 9.806, 1.6);
  std::vector<double> ref(12000);
  for (std::size_t k = 0; k < ref.size(); ++k) {
    const double t = static_cast<double>(k) * dt;
    if (t < 2.0 || t >= 10.0) {
      ref[k] = 0.0;
      continue;
    }
    const double ph = std::fmod(t - 2.0, 1.0);
    const int step = static_cast<int>((t - 2.0) / 1.0);
    const double target = (step % 2 == 0) ? 0.1 : -0.1;
    const double prev = step == 0 ? 0.0 : -target;
    ref[k] = ph < 0.2 ? prev + (target - prev) * ph / 0.2 : target;
  }
  const auto x = pc.track(ref, Eigen::Vector3d::Zero());
  double max_err = 0.0;
  for (std::size_t k = 0; k < ref.size(); ++k) max_err = std::max(max_err, std::abs(pc.C() * x[k] - ref[k]));
  std::printf("max cart-table ZMP error %.4f m\n", max_err);
  EXPECT_LT(max_err, 0.003);
}
