// The overlay's rolling GPU/CPU medians.
#include <gtest/gtest.h>

#include "game/play_stats.hpp"

using bounce::game::RollingTimings;
using bounce::gpu::TimingResult;

TEST(RollingTimings, MedianOfTheWindowPerPass) {
  RollingTimings r(3);
  r.addGpuFrame({{"shadow", 0, 1.0}, {"lighting", 0, 10.0}, {"inner", 1, 99.0}}, 1);
  r.addGpuFrame({{"shadow", 0, 3.0}, {"lighting", 0, 30.0}}, 2);
  r.addGpuFrame({{"shadow", 0, 3.0}, {"lighting", 0, 30.0}}, 2);  // same frame again: ignored
  r.addGpuFrame({{"shadow", 0, 2.0}, {"lighting", 0, 20.0}}, 3);
  EXPECT_EQ(r.gpuFrames(), 3u);
  const auto m = r.passMedians();
  ASSERT_EQ(m.size(), 2u);  // nested scopes are not rows
  EXPECT_EQ(m[0].first, "shadow");
  EXPECT_DOUBLE_EQ(m[0].second, 2.0);
  EXPECT_EQ(m[1].first, "lighting");
  EXPECT_DOUBLE_EQ(m[1].second, 20.0);
  EXPECT_DOUBLE_EQ(r.gpuTotalMedianMs(), 22.0);  // totals 11, 33, 22

  // Frame 1 leaves the window; a pass that just appeared has its own samples only.
  r.addGpuFrame({{"overlay", 0, 0.5}, {"lighting", 0, 40.0}}, 4);
  const auto n = r.passMedians();
  ASSERT_EQ(n.size(), 2u);
  EXPECT_EQ(n[0].first, "overlay");
  EXPECT_DOUBLE_EQ(n[0].second, 0.5);
  EXPECT_DOUBLE_EQ(n[1].second, 30.0);  // 30, 20, 40
}

TEST(RollingTimings, EmptyAndCpuFrames) {
  RollingTimings r(2);
  EXPECT_TRUE(r.passMedians().empty());
  EXPECT_DOUBLE_EQ(r.gpuTotalMedianMs(), 0.0);
  EXPECT_DOUBLE_EQ(r.cpuFrameMedianMs(), 0.0);
  r.addGpuFrame({}, 1);  // a frame without timestamps (unsupported queue) records nothing
  r.addGpuFrame({{"x", 0, 1.0}}, 0);  // frame number 0: nothing resolved yet
  EXPECT_EQ(r.gpuFrames(), 0u);
  r.addCpuFrameMs(100.0);
  r.addCpuFrameMs(16.0);
  r.addCpuFrameMs(17.0);  // window 2: 16, 17 → nearest-rank median 16
  EXPECT_DOUBLE_EQ(r.cpuFrameMedianMs(), 16.0);
}
