// Gait schedule: footprints, contact phases, planned ZMP and swing-foot trajectories.
#include <gtest/gtest.h>

#include <cmath>

#include "ftsense/sim/gait_plan.hpp"

using namespace ftsense::sim;

namespace {
GaitParams params(double L, double T, int n) {
  GaitParams p;
  p.step_length_m = L;
  p.step_time_s = T;
  p.double_support_ratio = 0.2;
  p.num_steps = n;
  p.initial_stand_s = 1.5;
  return p;
}
}  // namespace

TEST(GaitPlan, FootprintsAdvanceByStepLengthAndEndSideBySide) {
  const GaitPlan plan(params(0.15, 1.0, 6), 30.0);
  const auto& fp = plan.footprints();
  ASSERT_EQ(fp.size(), 8u);
  EXPECT_DOUBLE_EQ(fp[0].y(), -0.1);  // right
  EXPECT_DOUBLE_EQ(fp[1].y(), 0.1);   // left
  for (std::size_t i = 2; i + 1 < fp.size(); ++i) EXPECT_NEAR(fp[i].x() - fp[i - 1].x(), 0.15, 1e-12);
  EXPECT_DOUBLE_EQ(fp[6].x(), fp[7].x());
  EXPECT_NEAR(plan.walk_end_s(), 1.5 + 6.2, 1e-12);
}

TEST(GaitPlan, NumberOfStepsFillsTheDuration) {
  GaitParams p = params(0.15, 1.0, -1);
  const GaitPlan plan(p, 35.0);
  EXPECT_EQ(plan.num_steps(), 32);  // floor(35 - 1.5 - 0.2 - 1)
  EXPECT_LE(plan.walk_end_s() + 1.0, 35.0);
}

TEST(GaitPlan, ContactScheduleAndZmp) {
  const GaitPlan plan(params(0.15, 1.0, 4), 20.0);
  // Standing: both feet down, ZMP between them.
  auto s = plan.sample(1.0);
  EXPECT_TRUE(s.contact[0] && s.contact[1]);
  EXPECT_NEAR(s.zmp.y(), 0.0, 1e-12);
  // Step 0 single support (t in [1.7, 2.5)): right swings, ZMP on the left sole.
  s = plan.sample(2.0);
  EXPECT_TRUE(s.contact[0]);
  EXPECT_FALSE(s.contact[1]);
  EXPECT_NEAR(s.zmp.x(), 0.0, 1e-12);
  EXPECT_NEAR(s.zmp.y(), 0.1, 1e-12);
  // Step 1 double support (t in [2.5, 2.7)): ZMP halfway from left to right sole.
  s = plan.sample(2.6);
  EXPECT_TRUE(s.contact[0] && s.contact[1]);
  EXPECT_NEAR(s.zmp.y(), 0.0, 1e-9);
  EXPECT_NEAR(s.zmp.x(), 0.075, 1e-9);
  // After the walk: standing side by side, ZMP midway.
  s = plan.sample(15.0);
  EXPECT_TRUE(s.contact[0] && s.contact[1]);
  EXPECT_NEAR(s.zmp.y(), 0.0, 1e-12);
  EXPECT_NEAR(s.sole[0].x(), s.sole[1].x(), 1e-12);
  EXPECT_NEAR(s.zmp.x(), s.sole[0].x(), 1e-12);
}

TEST(GaitPlan, SwingFootLiftsAndLandsWithZeroVelocity) {
  const GaitPlan plan(params(0.2, 0.8, 4), 20.0);
  const double ss0 = 1.5 + 0.16, ss1 = 1.5 + 0.8;  // first single support
  const double h = 1e-4;
  for (double t : {ss0 + 1e-6, ss1 - 1e-6}) {
    const auto a = plan.sample(t - h), b = plan.sample(t + h);
    const Eigen::Vector3d v = (b.sole[1] - a.sole[1]) / (2 * h);
    EXPECT_LT(v.norm(), 1e-3) << "t = " << t;
  }
  const auto mid = plan.sample(0.5 * (ss0 + ss1));
  EXPECT_NEAR(mid.sole[1].z(), plan.params().step_height_m, 1e-12);
  EXPECT_NEAR(plan.sample(ss1 - 1e-9).sole[1].x(), 0.2, 1e-6);  // landed on F2
  // The stance foot never moves during single support.
  for (double t = ss0; t < ss1; t += 0.01) EXPECT_EQ(plan.sample(t).sole[0], Eigen::Vector3d(0, 0.1, 0));
}

TEST(GaitPlan, FootTrajectoriesAreContinuous) {
  const GaitPlan plan(params(0.2, 0.8, 8), 20.0);
  auto prev = plan.sample(0.0);
  for (double t = 0.001; t < 12.0; t += 0.001) {
    const auto s = plan.sample(t);
    for (int f = 0; f < 2; ++f) ASSERT_LT((s.sole[f] - prev.sole[f]).norm(), 2e-3) << "t = " << t;
    ASSERT_LT((s.zmp - prev.zmp).norm(), 2e-3) << "t = " << t;
    prev = s;
  }
}
