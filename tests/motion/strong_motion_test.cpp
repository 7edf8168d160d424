// The strong-motion window against a motion whose exceedances are placed by hand.
#include <gtest/gtest.h>

#include "rigid/core/types.hpp"
#include "rigid/motion/strong_motion.hpp"

using namespace rigid;

namespace {
// 20 s at 100 Hz, quiet (0.01 g) but for two samples of 0.3 g at 5.00 s and 12.50 s
motion::GroundMotion two_spikes() {
  motion::GroundMotion m;
  m.dt = 0.01;
  m.x.assign(2001, 0.01 * kGravity);
  m.x[500] = 0.3 * kGravity;
  m.x[1250] = -0.3 * kGravity;
  return m;
}
}  // namespace

TEST(StrongMotionWindow, SpansTheExceedancesWithOneSecondEachSide) {
  const motion::TimeWindow w = motion::strong_motion_window(two_spikes(), 0.1);
  EXPECT_NEAR(w.start_s, 4.0, 1e-12);
  EXPECT_NEAR(w.end_s, 13.5, 1e-12);
}

TEST(StrongMotionWindow, ClipsToTheMotionAndKeepsTwoSecondsOfAQuietOne) {
  motion::GroundMotion m = two_spikes();
  m.x[0] = 0.5 * kGravity;
  m.x[2000] = 0.5 * kGravity;
  const motion::TimeWindow whole = motion::strong_motion_window(m, 0.4);
  EXPECT_EQ(whole.start_s, 0.0);
  EXPECT_NEAR(whole.end_s, 20.0, 1e-12);
  const motion::TimeWindow quiet = motion::strong_motion_window(two_spikes(), 1.0);
  EXPECT_EQ(quiet.start_s, 0.0);
  EXPECT_EQ(quiet.end_s, 2.0);
  const motion::TimeWindow all = motion::strong_motion_window(two_spikes(), 0.0);
  EXPECT_EQ(all.start_s, 0.0);
  EXPECT_NEAR(all.end_s, 20.0, 1e-12);
}
