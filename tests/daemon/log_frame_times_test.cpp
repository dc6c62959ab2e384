// Which frames of a log are played and when (log_frame_times.hpp): one bad timestamp, at the
// start, inside or at the end of a log, is skipped; a step of the log's clock is played at
// once; swapped frames and gaps are played as they are.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "headingd/daemon/sources/log_frame_times.hpp"

namespace headingd::daemon {
namespace {

constexpr std::int64_t kS = 1'000'000'000;
constexpr std::int64_t kT0 = 1'780'315'200 * kS;  // the demo log's start
constexpr std::int64_t kYear = 365 * 86'400 * kS;

// n frames 10 ms apart from kT0.
std::vector<std::int64_t> steady(std::size_t n) {
  std::vector<std::int64_t> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = kT0 + static_cast<std::int64_t>(i) * 10'000'000;
  return t;
}

std::vector<std::size_t> skippedIndices(const LogFrameTimes& r) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < r.skipped.size(); ++i) {
    if (r.skipped[i]) out.push_back(i);
  }
  return out;
}

TEST(LogFrameTimes, AWellFormedLogIsPlayedOnItsOwnTimes) {
  const auto t = steady(100);
  const LogFrameTimes r = placeLogFrames(t);
  EXPECT_EQ(r.outlier_frames, 0u);
  EXPECT_EQ(r.time_steps, 0u);
  EXPECT_EQ(r.play_ns, t);
}

TEST(LogFrameTimes, AFirstFrameAtZeroIsSkipped) {
  auto t = steady(100);
  t[0] = 0;  // (0.000000)
  const LogFrameTimes r = placeLogFrames(t);
  EXPECT_EQ(skippedIndices(r), std::vector<std::size_t>{0});
  EXPECT_EQ(r.first_outlier_index, 0);
  EXPECT_EQ(r.time_steps, 0u);
  EXPECT_EQ(r.play_ns[1], t[1]);
}

TEST(LogFrameTimes, OneFrameAYearAheadInsideOrAtTheEndIsSkipped) {
  for (const std::size_t at : {std::size_t{1}, std::size_t{50}, std::size_t{99}}) {
    auto t = steady(100);
    t[at] += kYear;
    const LogFrameTimes r = placeLogFrames(t);
    EXPECT_EQ(skippedIndices(r), std::vector<std::size_t>{at}) << at;
    EXPECT_EQ(r.time_steps, 0u) << at;
  }
}

TEST(LogFrameTimes, AnEpochOfThreeFramesBackAtZeroIsSkipped) {
  auto t = steady(100);
  t[30] = t[31] = t[32] = 0;
  const LogFrameTimes r = placeLogFrames(t);
  EXPECT_EQ(skippedIndices(r), (std::vector<std::size_t>{30, 31, 32}));
  EXPECT_EQ(r.play_ns[33], t[33]);
}

TEST(LogFrameTimes, SwappedFramesAndAGapArePlayedAsTheyAre) {
  auto t = steady(100);
  std::swap(t[10], t[11]);                                      // 10 ms back, then on
  for (std::size_t i = 60; i < t.size(); ++i) t[i] += 30 * kS;  // 30 s without frames
  const LogFrameTimes r = placeLogFrames(t);
  EXPECT_EQ(r.outlier_frames, 0u);
  EXPECT_EQ(r.time_steps, 0u);
  EXPECT_EQ(r.play_ns, t);
}

TEST(LogFrameTimes, AStepOfTheLogsClockIsPlayedAtOnce) {
  for (const std::int64_t step : {-3600 * kS, kYear}) {
    auto t = steady(100);
    for (std::size_t i = 40; i < t.size(); ++i) t[i] += step;
    const LogFrameTimes r = placeLogFrames(t);
    EXPECT_EQ(r.outlier_frames, 0u);
    EXPECT_EQ(r.time_steps, 1u);
    EXPECT_EQ(r.first_step_index, 40);
    EXPECT_EQ(r.play_ns[40], r.play_ns[39]);                  // no wait, no jump back
    EXPECT_EQ(r.play_ns[99] - r.play_ns[40], t[99] - t[40]);  // then the log's own spacing
  }
}

TEST(LogFrameTimes, ASlowLogIsNotTakenForOutliers) {
  std::vector<std::int64_t> t;
  for (int i = 0; i < 20; ++i) t.push_back(kT0 + i * 5 * kS);  // a frame every 5 s
  const LogFrameTimes r = placeLogFrames(t);
  EXPECT_EQ(r.outlier_frames, 0u);
  EXPECT_EQ(r.time_steps, 0u);
}

TEST(LogFrameTimes, ExtremeTimesNeitherOverflowNorStall) {
  auto t = steady(50);
  t[20] = INT64_MAX;
  t[0] = INT64_MIN;
  t[49] = INT64_MAX;
  const LogFrameTimes r = placeLogFrames(t);
  EXPECT_EQ(skippedIndices(r), (std::vector<std::size_t>{0, 20, 49}));
  for (std::size_t i = 1; i < 49; ++i) {
    if (!r.skipped[i]) {
      EXPECT_EQ(r.play_ns[i], t[i]);
    }
  }
}

}  // namespace
}  // namespace headingd::daemon
