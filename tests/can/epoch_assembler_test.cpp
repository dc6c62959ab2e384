// Epoch assembly: complete epochs, a slower magnetometer, lost and repeated frames, counter
// gaps, malformed frames; with counters (headingd frame set) and by time (OpenIMU, J1939).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "can_test_support.hpp"
#include "headingd/can/epoch_assembler.hpp"
#include "headingd/can/j1939.hpp"

namespace headingd::can {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;  // 100 Hz
constexpr std::int64_t kSpacingNs = 200'000;

core::ImuSample sampleAt(int k) {
  core::ImuSample s;
  s.t_ns = 1'000'000'000 + k * kPeriodNs;
  s.gyro_rad_s = {0.01 * k, -0.5, 1.25};
  s.accel_m_s2 = {0.1, -0.2, 9.81 + 0.001 * k};
  s.mag_uT = {20.0 + k, -3.5, 42.0};
  return s;
}

class Fixture {
 public:
  explicit Fixture(const char* config, bool wait_for_mag = true)
      : setup_(loadCanSetup(test::configPath(config))), codec_(setup_.config, setup_.dbc) {
    settings_ = epochSettingsFrom(setup_.config);
    settings_.wait_for_mag = wait_for_mag;
  }
  const ImuFrameCodec& codec() const { return codec_; }
  EpochSettings settings() const { return settings_; }

  // Frames of epoch k in DBC order (gyro, accel, mag), timestamped from the sample time.
  std::vector<CanFrame> epoch(int k, bool with_mag = true) const {
    std::vector<CanFrame> frames;
    codec_.encode(sampleAt(k), static_cast<std::uint64_t>(k), with_mag, frames);
    std::int64_t t = sampleAt(k).t_ns;
    for (auto& f : frames) {
      f.t_ns = t;
      t += kSpacingNs;
    }
    return frames;
  }

 private:
  CanSetup setup_;
  ImuFrameCodec codec_;
  EpochSettings settings_;
};

struct Collector {
  std::vector<core::ImuSample> samples;
  void take(const AssembledSamples& out) {
    for (int i = 0; i < out.count; ++i) samples.push_back(out.samples[static_cast<std::size_t>(i)]);
  }
};

// An assembler on a configuration's frame set, and the samples it released.
struct Assembly {
  explicit Assembly(const char* config, bool wait_for_mag = true)
      : fx(config, wait_for_mag), a(fx.codec(), fx.settings()) {}
  Fixture fx;
  EpochAssembler a;
  Collector c;
};

void expectSampleNear(const core::ImuSample& got, const core::ImuSample& want, bool with_mag) {
  EXPECT_EQ(got.t_ns, want.t_ns);
  EXPECT_LT((got.gyro_rad_s - want.gyro_rad_s).cwiseAbs().maxCoeff(), 0.51e-4);
  EXPECT_LT((got.accel_m_s2 - want.accel_m_s2).cwiseAbs().maxCoeff(), 1.01e-4);
  EXPECT_EQ(got.has_mag, with_mag);
  if (with_mag) {
    EXPECT_LT((got.mag_uT - want.mag_uT).cwiseAbs().maxCoeff(), 1.01e-3);
  }
}

TEST(EpochAssembler, CompleteEpochsBecomeSamplesAtTheFirstFrameTime) {
  Assembly assembly("can-headingd.toml");
  auto& [fx, a, c] = assembly;
  for (int k = 0; k < 40; ++k) {
    for (const auto& f : fx.epoch(k)) {
      const AssembledSamples out = a.push(f);
      c.take(out);
    }
    ASSERT_EQ(c.samples.size(), static_cast<std::size_t>(k + 1)) << "released as soon as complete";
  }
  for (int k = 0; k < 40; ++k) expectSampleNear(c.samples[static_cast<std::size_t>(k)], sampleAt(k), true);
  EXPECT_EQ(a.counters().samples, 40u);
  EXPECT_EQ(a.counters().incomplete_epochs, 0u);
  EXPECT_EQ(a.counters().sequence_gaps, 0u);  // the 4-bit counter wrapped twice
  c.take(a.finish());
  EXPECT_EQ(c.samples.size(), 40u);
}

TEST(EpochAssembler, FramesInAnyOrder) {
  Assembly assembly("can-headingd.toml");
  auto& [fx, a, c] = assembly;
  for (int k = 0; k < 6; ++k) {
    auto frames = fx.epoch(k);
    std::swap(frames[0], frames[2]);  // mag, accel, gyro
    for (std::size_t i = 0; i < frames.size(); ++i) {
      frames[i].t_ns = sampleAt(k).t_ns + static_cast<std::int64_t>(i) * kSpacingNs;
      c.take(a.push(frames[i]));
    }
  }
  ASSERT_EQ(c.samples.size(), 6u);
  EXPECT_EQ(c.samples[3].t_ns, sampleAt(3).t_ns);  // t of the earliest arriving frame
  EXPECT_TRUE(c.samples[3].has_mag);
}

TEST(EpochAssembler, SlowerMagnetometerWaitingForIt) {
  Assembly assembly("can-headingd.toml", /*wait_for_mag=*/true);
  auto& [fx, a, c] = assembly;
  for (int k = 0; k < 20; ++k) {
    for (const auto& f : fx.epoch(k, k % 4 == 0)) c.take(a.push(f));
  }
  c.take(a.finish());
  ASSERT_EQ(c.samples.size(), 20u);
  for (int k = 0; k < 20; ++k) expectSampleNear(c.samples[static_cast<std::size_t>(k)], sampleAt(k), k % 4 == 0);
  EXPECT_EQ(a.counters().samples_with_mag, 5u);
  EXPECT_EQ(a.counters().incomplete_epochs, 0u);
}

TEST(EpochAssembler, FlushReleasesAnEpochWithoutMagAfterTheWindow) {
  Assembly assembly("can-headingd.toml", true);
  auto& [fx, a, c] = assembly;
  for (const auto& f : fx.epoch(0, false)) c.take(a.push(f));
  EXPECT_TRUE(c.samples.empty());
  c.take(a.flush(sampleAt(0).t_ns + 1'000'000));  // within the 2 ms window: keep waiting
  EXPECT_TRUE(c.samples.empty());
  c.take(a.flush(sampleAt(0).t_ns + 2'500'000));
  ASSERT_EQ(c.samples.size(), 1u);
  EXPECT_FALSE(c.samples[0].has_mag);
}

TEST(EpochAssembler, LateMagnetometerGoesToTheNextSample) {
  Assembly assembly("can-headingd.toml", /*wait_for_mag=*/false);
  auto& [fx, a, c] = assembly;
  for (int k = 0; k < 3; ++k) {
    for (const auto& f : fx.epoch(k)) c.take(a.push(f));  // gyro, accel (released), then mag
  }
  ASSERT_EQ(c.samples.size(), 3u);
  EXPECT_FALSE(c.samples[0].has_mag);
  EXPECT_TRUE(c.samples[1].has_mag);
  EXPECT_NEAR(c.samples[1].mag_uT.x(), sampleAt(0).mag_uT.x(), 1.01e-3);  // epoch 0's field
  EXPECT_EQ(a.counters().late_mag_frames, 3u);
}

TEST(EpochAssembler, LostFramesAreCountedNotInvented) {
  Assembly assembly("can-headingd.toml");
  auto& [fx, a, c] = assembly;
  for (int k = 0; k < 10; ++k) {
    auto frames = fx.epoch(k);
    if (k == 4) frames.erase(frames.begin());      // gyro frame lost
    if (k == 7) frames.erase(frames.begin() + 1);  // accel frame lost
    for (const auto& f : frames) c.take(a.push(f));
  }
  c.take(a.finish());
  EXPECT_EQ(c.samples.size(), 8u);
  EXPECT_EQ(a.counters().incomplete_epochs, 2u);
  for (const auto& s : c.samples) {
    EXPECT_NE(s.t_ns, sampleAt(4).t_ns);
    EXPECT_NE(s.t_ns, sampleAt(7).t_ns);
  }
}

TEST(EpochAssembler, CounterGapsAndDuplicates) {
  Assembly assembly("can-headingd.toml");
  auto& [fx, a, c] = assembly;
  for (int k : {0, 1, 2, 6, 7}) {  // epochs 3, 4, 5 lost entirely
    for (const auto& f : fx.epoch(k)) c.take(a.push(f));
  }
  const auto again = fx.epoch(7);
  c.take(a.push(again[0]));  // gyro of epoch 7 repeated
  EXPECT_EQ(c.samples.size(), 5u);
  EXPECT_EQ(a.counters().sequence_gaps, 1u);
  EXPECT_EQ(a.counters().missing_epochs, 3u);
  EXPECT_EQ(a.counters().duplicate_frames, 1u);
}

// A log played again (the daemon's [playback] at_end = "loop"): its first epoch may carry the
// counter of the last one (60,001 epochs of a 4-bit counter end on 0, as they began). After
// restartStream it is a new epoch, not three repeated frames.
TEST(EpochAssembler, RestartedStreamIsNotTakenForRepeatedFrames) {
  Fixture fx("can-headingd.toml");
  for (const bool restart : {false, true}) {
    EpochAssembler a(fx.codec(), fx.settings());
    Collector c;
    for (int k : {0, 1, 2}) {
      for (const auto& f : fx.epoch(k)) c.take(a.push(f));
    }
    if (restart) c.take(a.restartStream());
    for (auto f : fx.epoch(2)) {  // counter 2 again, a second later
      f.t_ns += 1'000'000'000;
      c.take(a.push(f));
    }
    c.take(a.finish());
    EXPECT_EQ(c.samples.size(), restart ? 4u : 3u) << "restart " << restart;
    EXPECT_EQ(a.counters().duplicate_frames, restart ? 0u : 3u) << "restart " << restart;
    if (restart) {
      EXPECT_EQ(c.samples.back().t_ns, sampleAt(2).t_ns + 1'000'000'000);
    }
  }
}

// The assembler's counters after every frame of the epochs `order`, in that order.
AssemblerCounters countersAfter(const std::vector<int>& order) {
  Fixture fx("can-headingd.toml");
  EpochAssembler a(fx.codec(), fx.settings());
  for (const int k : order) {
    for (const auto& f : fx.epoch(k)) a.push(f);
  }
  return a.counters();
}

TEST(EpochAssembler, SwappedEpochPairsAreReorderedNotMissing) {
  // 100 pairs of consecutive epochs swapped (0, 2, 1, 3, 4, 6, 5, 7, ...): each late epoch is
  // one reordered epoch, not a skip of nearly the whole 4-bit counter range (15 + 1 "missing").
  std::vector<int> order;
  for (int k = 0; k < 400; ++k) order.push_back(k % 4 == 1 ? k + 1 : (k % 4 == 2 ? k - 1 : k));
  const AssemblerCounters c = countersAfter(order);
  EXPECT_EQ(c.samples, 400u);
  EXPECT_EQ(c.reordered_epochs, 100u);
  EXPECT_EQ(c.missing_epochs, 0u);
  EXPECT_EQ(c.sequence_gaps, 0u);
}

TEST(EpochAssembler, ALateEpochInsideAGapIsNoLongerMissing) {
  // 3, 4, 5 skipped, then 4 arrives late: 3 and 5 stay missing, in two gaps.
  AssemblerCounters c = countersAfter({0, 1, 2, 6, 4, 7});
  EXPECT_EQ(c.reordered_epochs, 1u);
  EXPECT_EQ(c.missing_epochs, 2u);
  EXPECT_EQ(c.sequence_gaps, 2u);
  c = countersAfter({0, 1, 2, 6, 4, 7, 3, 5});  // then 3 and 5 too: nothing missing
  EXPECT_EQ(c.reordered_epochs, 3u);
  EXPECT_EQ(c.missing_epochs, 0u);
  EXPECT_EQ(c.sequence_gaps, 0u);
  // Further back than a quarter of the counter range (4 of 16) is a skip ahead, as before:
  // 15 after 10 is 11 behind (mod 16) or 5 ahead: 4 missing.
  c = countersAfter({8, 9, 10, 15});
  EXPECT_EQ(c.missing_epochs, 4u);
  EXPECT_EQ(c.reordered_epochs, 0u);
}

TEST(EpochAssembler, MalformedFramesAreCounted) {
  Fixture fx("can-headingd.toml");
  EpochAssembler a(fx.codec(), fx.settings());
  auto frames = fx.epoch(0);
  CanFrame short_frame = frames[0];
  short_frame.len = 6;
  CanFrame unknown = frames[0];
  unknown.id = 0x7FF;
  CanFrame extended_same_id = frames[0];
  extended_same_id.extended = true;
  CanFrame remote = frames[1];
  remote.remote = true;
  remote.len = 0;
  CanFrame error;
  error.error_frame = true;
  error.id = 0x40;
  for (const auto& f : {short_frame, unknown, extended_same_id, remote, error}) {
    EXPECT_EQ(a.push(f).count, 0);
  }
  const auto& n = a.counters();
  EXPECT_EQ(n.wrong_length_frames, 1u);
  EXPECT_EQ(n.unknown_id_frames, 2u);
  EXPECT_EQ(n.remote_frames, 1u);
  EXPECT_EQ(n.error_frames, 1u);
  EXPECT_EQ(n.decoded_frames, 0u);
  EXPECT_EQ(n.frames, 5u);
}

// A gyro pinned at its signal's full scale measured more than it says: counted (STATUS shows
// full_scale_values, the sources warn), the value used as read.
TEST(EpochAssembler, ValuesAtTheirFullScaleAreCountedAndUsedAsRead) {
  Fixture fx("can-headingd.toml");
  EpochAssembler a(fx.codec(), fx.settings());
  Collector c;
  for (const auto& f : fx.epoch(0)) c.take(a.push(f));
  EXPECT_EQ(a.counters().full_scale_values, 0u);
  core::ImuSample spinning = sampleAt(1);
  spinning.gyro_rad_s.z() = 1000.0;  // beyond the signal's ±52.4 rad/s
  spinning.accel_m_s2.x() = -500.0;  // beyond its ±104.9 m/s²
  std::vector<CanFrame> frames;
  EXPECT_EQ(fx.codec().encode(spinning, 1, true, frames), 2);  // written at the signals' ends
  for (auto& f : frames) {
    f.t_ns = spinning.t_ns;
    c.take(a.push(f));
  }
  EXPECT_EQ(a.counters().full_scale_values, 2u);
  ASSERT_EQ(c.samples.size(), 2u);
  EXPECT_NEAR(c.samples[1].gyro_rad_s.z(), 52.4287, 1e-9);
  EXPECT_NEAR(c.samples[1].accel_m_s2.x(), -104.8576, 1e-9);
  // Remote frames and superseded late magnetometer values reach STATUS by name too.
  std::vector<std::string> names;
  forEachCounter(a.counters(), [&](const char* name, std::uint64_t) { names.emplace_back(name); });
  for (const char* name : {"full_scale_values", "remote_frames", "superseded_mag_frames"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
}

TEST(EpochAssembler, J1939ByTimeAnySourceAddressAndPriority) {
  Assembly assembly("can-openimu.toml", /*wait_for_mag=*/true);
  auto& [fx, a, c] = assembly;
  for (int k = 0; k < 10; ++k) {
    auto frames = fx.epoch(k, k % 2 == 0);
    for (auto& f : frames) {
      // Another unit address and priority: still the same PGNs.
      f.id = (f.id & ~0x1C0000FFu) | (3u << 26) | 0x23u;
      c.take(a.push(f));
    }
  }
  c.take(a.finish());
  ASSERT_EQ(c.samples.size(), 10u);
  for (int k = 0; k < 10; ++k) {
    const auto& s = c.samples[static_cast<std::size_t>(k)];
    EXPECT_EQ(s.t_ns, sampleAt(k).t_ns);
    EXPECT_LT((s.gyro_rad_s - sampleAt(k).gyro_rad_s).cwiseAbs().maxCoeff(), 0.5 * (3.14159265 / 180) / 128 + 1e-12);
    EXPECT_LT((s.accel_m_s2 - sampleAt(k).accel_m_s2).cwiseAbs().maxCoeff(), 0.005 + 1e-12);
    EXPECT_EQ(s.has_mag, k % 2 == 0);
    if (s.has_mag) {
      EXPECT_LT((s.mag_uT - sampleAt(k).mag_uT).cwiseAbs().maxCoeff(), 0.0125 + 1e-9);
    }
  }
  EXPECT_EQ(a.counters().incomplete_epochs, 0u);
  // A different PGN with the same source address is not ours.
  CanFrame other = test::frame(j1939Id(6, 61483, 0x80), true, {0, 0, 0, 0, 0, 0, 0, 0}, 5'000'000'000);
  a.push(other);
  EXPECT_EQ(a.counters().unknown_id_frames, 1u);
}

TEST(EpochAssembler, KernelFiltersFollowTheConfiguration) {
  Fixture own("can-headingd.toml");
  for (const auto& f : own.codec().kernelFilters()) {
    EXPECT_FALSE(f.extended);
    EXPECT_EQ(f.mask, 0x7FFu);
  }
  Fixture j("can-openimu.toml");
  const auto filters = j.codec().kernelFilters();
  ASSERT_EQ(filters.size(), 3u);
  for (const auto& f : filters) {
    EXPECT_TRUE(f.extended);
    EXPECT_EQ(f.mask, 0x03FFFF00u);  // PDU2: priority and source address free
  }
}

TEST(EpochAssembler, RandomFrameSoupNeverCrashesAndBalancesCounters) {
  Fixture fx("can-headingd.toml");
  EpochAssembler a(fx.codec(), fx.settings());
  std::uint32_t state = 99;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  std::uint64_t released = 0;
  for (int i = 0; i < 50000; ++i) {
    CanFrame f;
    f.id = 0x120 + next() % 4;
    f.extended = next() % 16 == 0;
    f.len = static_cast<std::uint8_t>(next() % 16 == 0 ? next() % 9 : 8);
    for (auto& b : f.data) b = static_cast<std::uint8_t>(next());
    f.t_ns = i * 1'000'000LL + static_cast<std::int64_t>(next() % 3'000'000);
    released += static_cast<std::uint64_t>(a.push(f).count);
  }
  released += static_cast<std::uint64_t>(a.finish().count);
  const auto& n = a.counters();
  EXPECT_EQ(n.samples, released);
  EXPECT_EQ(n.frames, 50000u);
  EXPECT_EQ(n.frames,
            n.decoded_frames + n.unknown_id_frames + n.wrong_length_frames + n.remote_frames + n.error_frames);
}

}  // namespace
}  // namespace headingd::can
