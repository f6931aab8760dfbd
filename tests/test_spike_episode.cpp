// spike_episode: the hold after the last spike is ln(1 / p_gap) / lambda^, lambda^ = (n - 1) / D,
// clamped to [min_hold, first_hold]; the first spike holds first_hold; an episode ends once its
// quiet time reaches the hold, and the next spike starts a new one. Exact values, in ticks.

#include <cmath>

#include <gtest/gtest.h>

#include "ftsense/generic/spike_episode.hpp"

namespace ftsense::generic {
namespace {

const SpikeHoldRule kRule{800.0, 10.0, std::log(100.0)};  // p_gap = 0.01

TEST(SpikeEpisode, TheFirstSpikeHoldsFirstHold) {
  SpikeEpisode e;
  EXPECT_FALSE(e.running());
  e.spike(kRule);
  EXPECT_TRUE(e.running());
  EXPECT_EQ(e.count, 1.0);
  EXPECT_EQ(e.hold, 800.0);
  for (int k = 0; k < 799; ++k) e.see(1.0);
  EXPECT_TRUE(e.running());
  e.see(1.0);
  EXPECT_FALSE(e.running()) << "quiet 800 = hold";
  e.spike(kRule);  // on the tick the hold is reached: a new episode, not a second spike of the old
  EXPECT_EQ(e.count, 1.0);
  EXPECT_EQ(e.hold, 800.0);
}

TEST(SpikeEpisode, LaterSpikesHoldTheGapTheirRateLeavesWithProbabilityPGap) {
  SpikeEpisode e;
  e.spike(kRule);
  for (int k = 0; k < 100; ++k) e.see(1.0);
  e.spike(kRule);  // n = 2 over D = 100 ticks: h = ln(100) * 100 / 1
  EXPECT_EQ(e.count, 2.0);
  EXPECT_DOUBLE_EQ(e.hold, std::log(100.0) * 100.0);  // 460.5 ticks
  for (int k = 0; k < 460; ++k) e.see(1.0);
  EXPECT_TRUE(e.running());
  e.see(1.0);
  EXPECT_FALSE(e.running()) << "quiet 461 > 460.5";
  e.spike(kRule);  // a new episode: rate unknown again
  EXPECT_EQ(e.count, 1.0);
  EXPECT_EQ(e.hold, 800.0);
  EXPECT_EQ(e.seen, 0.0);
}

TEST(SpikeEpisode, TheHoldIsClampedToItsBounds) {
  SpikeEpisode fast;
  fast.spike(kRule);
  fast.see(1.0);
  fast.spike(kRule);  // a spike every tick: ln(100) * 1 = 4.6 ticks, below min_hold
  EXPECT_EQ(fast.hold, 10.0);
  SpikeEpisode slow;
  slow.spike(kRule);
  for (int k = 0; k < 700; ++k) slow.see(1.0);
  slow.spike(kRule);  // ln(100) * 700 = 3224 ticks, above first_hold
  EXPECT_EQ(slow.hold, 800.0);
}

TEST(SpikeEpisode, EndStopsTheEpisodeAtOnce) {
  SpikeEpisode e;
  e.spike(kRule);
  e.end();
  EXPECT_FALSE(e.running());
  e.spike(kRule);
  EXPECT_EQ(e.count, 1.0);
}

}  // namespace
}  // namespace ftsense::generic
