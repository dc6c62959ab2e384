// The SocketCAN receiver against a real vcan interface (in the VM of tools/scripts/vm-run.sh,
// or natively where the kernel has vcan): decoding of frames sent through a second raw socket,
// kernel filters (ids, J1939 PGNs), error frames, a flood at the bus's full rate without loss,
// and the interface going down/up and disappearing/coming back.
// Usage: headingd-can-vcan-tests [gtest flags] --vcan=vcan0 --vcan-spare=vcan1
#include <gtest/gtest.h>

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "headingd/can/epoch_assembler.hpp"
#include "headingd/can/j1939.hpp"
#include "headingd/can/socketcan_receiver.hpp"

namespace {

std::string g_vcan = "vcan0";
std::string g_spare = "vcan1";

using namespace headingd::can;
using namespace std::chrono_literals;

// Sends raw frames on an interface, as another node on the bus would.
class Sender {
 public:
  explicit Sender(const std::string& interface) {
    fd_ = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (fd_ < 0) return;
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = static_cast<int>(::if_nametoindex(interface.c_str()));
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  }
  ~Sender() {
    if (fd_ >= 0) ::close(fd_);
  }
  bool ok() const { return fd_ >= 0; }
  bool send(const CanFrame& f) {
    can_frame k{};
    k.can_id = f.error_frame ? (f.id | CAN_ERR_FLAG) : f.extended ? (f.id | CAN_EFF_FLAG) : f.id;
    if (f.remote) k.can_id |= CAN_RTR_FLAG;
    k.len = f.len;
    std::memcpy(k.data, f.data.data(), 8);
    for (int attempt = 0; attempt < 1000; ++attempt) {
      if (::write(fd_, &k, sizeof k) == static_cast<ssize_t>(sizeof k)) return true;
      if (errno != ENOBUFS && errno != EAGAIN) return false;
      std::this_thread::sleep_for(100us);  // the tx queue is full: a real node would wait too
    }
    return false;
  }

 private:
  int fd_ = -1;
};

// The receiver on its own io thread; frames collected for the test to inspect.
class RunningReceiver {
 public:
  RunningReceiver(ReceiverSettings settings) : work_(boost::asio::make_work_guard(io_)) {
    // Each frame kept on the kernel's clock (its receive timestamp, CLOCK_REALTIME).
    receiver_ = std::make_unique<SocketCanReceiver>(io_, std::move(settings),
                                                    [this](const CanFrame& f, std::int64_t kernel_realtime_ns) {
                                                      std::lock_guard lock(mutex_);
                                                      frames_.push_back(f);
                                                      frames_.back().t_ns = kernel_realtime_ns;
                                                    });
    receiver_->start();
    thread_ = std::thread([this] { io_.run(); });
  }
  ~RunningReceiver() {
    boost::asio::post(io_, [this] { receiver_->stop(); });
    work_.reset();
    io_.stop();
    thread_.join();
    receiver_.reset();
  }
  ReceiverStatus status() const { return receiver_->status(); }
  std::vector<CanFrame> frames() const {
    std::lock_guard lock(mutex_);
    return frames_;
  }
  std::size_t count() const {
    std::lock_guard lock(mutex_);
    return frames_.size();
  }
  void clear() {
    std::lock_guard lock(mutex_);
    frames_.clear();
  }
  template <class Pred>
  bool waitFor(Pred pred, std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (pred()) return true;
      std::this_thread::sleep_for(2ms);
    }
    return pred();
  }
  bool waitUp(std::chrono::milliseconds timeout = 5000ms) const {
    return waitFor([&] { return status().state == LinkState::up; }, timeout);
  }

 private:
  boost::asio::io_context io_;
  boost::asio::executor_work_guard<boost::asio::io_context::executor_type> work_;
  std::unique_ptr<SocketCanReceiver> receiver_;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::vector<CanFrame> frames_;
};

std::string ipCommand() {
  for (const char* p : {"/usr/sbin/ip", "/sbin/ip", "/usr/bin/ip", "/bin/ip"}) {
    if (::access(p, X_OK) == 0) return p;
  }
  return "ip";
}

int ip(const std::string& args) { return std::system((ipCommand() + " " + args).c_str()); }

std::int64_t realtimeNs() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

CanSetup setupOf(const char* name) { return loadCanSetup(std::string(HEADINGD_CONFIG_DIR) + "/" + name); }

ReceiverSettings fastSettings(const std::string& interface, std::vector<IdFilter> filters) {
  ReceiverSettings s;
  s.interface = interface;
  s.filters = std::move(filters);
  s.reconnect_initial = 20ms;
  s.reconnect_max = 200ms;
  s.receive_buffer_bytes = 4 << 20;
  return s;
}

class Vcan : public ::testing::Test {
 protected:
  void SetUp() override {
    const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
    ASSERT_GE(fd, 0) << "socket(PF_CAN) failed (" << std::strerror(errno)
                     << "): run this in tools/scripts/vm-run.sh or on a kernel with CAN";
    ::close(fd);
    ASSERT_NE(::if_nametoindex(g_vcan.c_str()), 0u) << "no interface " << g_vcan;
  }
};

TEST_F(Vcan, DecodesImuFramesWithKernelTimestamps) {
  const CanSetup setup = setupOf("can-headingd.toml");
  const ImuFrameCodec codec(setup.config, setup.dbc);
  RunningReceiver rx(fastSettings(g_vcan, codec.kernelFilters()));
  ASSERT_TRUE(rx.waitUp()) << rx.status().last_error;
  Sender tx(g_vcan);
  ASSERT_TRUE(tx.ok());
  std::vector<headingd::core::ImuSample> sent;
  const std::int64_t before = realtimeNs();
  for (int k = 0; k < 50; ++k) {
    headingd::core::ImuSample s;
    s.gyro_rad_s = {0.001 * k, -1.5, 2.0};
    s.accel_m_s2 = {0.5, -0.25, 9.8};
    s.mag_uT = {21.0, -4.0, 40.0 + k};
    std::vector<CanFrame> frames;
    codec.encode(s, static_cast<std::uint64_t>(k), true, frames);
    for (const auto& f : frames) ASSERT_TRUE(tx.send(f));
    sent.push_back(s);
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_TRUE(rx.waitFor([&] { return rx.count() == 150; }, 5000ms)) << rx.count();
  const std::int64_t after = realtimeNs();
  EpochAssembler assembler(codec, epochSettingsFrom(setup.config));
  std::vector<headingd::core::ImuSample> got;
  for (const auto& f : rx.frames()) {
    EXPECT_GE(f.t_ns, before);
    EXPECT_LE(f.t_ns, after);
    const auto out = assembler.push(f);
    for (int i = 0; i < out.count; ++i) got.push_back(out.samples[static_cast<std::size_t>(i)]);
  }
  ASSERT_EQ(got.size(), sent.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_LT((got[i].gyro_rad_s - sent[i].gyro_rad_s).cwiseAbs().maxCoeff(), 0.51e-4);
    EXPECT_LT((got[i].mag_uT - sent[i].mag_uT).cwiseAbs().maxCoeff(), 1.01e-3);
    EXPECT_TRUE(got[i].has_mag);
  }
  EXPECT_EQ(assembler.counters().sequence_gaps, 0u);
  EXPECT_EQ(rx.status().kernel_drops, 0u);
}

TEST_F(Vcan, KernelFiltersPassOnlyConfiguredIds) {
  const CanSetup setup = setupOf("can-headingd.toml");
  const ImuFrameCodec codec(setup.config, setup.dbc);
  RunningReceiver rx(fastSettings(g_vcan, codec.kernelFilters()));
  ASSERT_TRUE(rx.waitUp()) << rx.status().last_error;
  Sender tx(g_vcan);
  CanFrame f;
  f.len = 8;
  for (std::uint32_t id : {0x100u, 0x123u, 0x7FFu}) {  // other standard ids
    f.id = id;
    ASSERT_TRUE(tx.send(f));
  }
  f.id = 0x120;
  f.extended = true;  // the right number as an extended id
  ASSERT_TRUE(tx.send(f));
  f.extended = false;
  f.remote = true;  // remote request with our id
  f.len = 0;
  ASSERT_TRUE(tx.send(f));
  f.remote = false;
  f.len = 8;
  f.data[0] = 0xAB;  // and one that passes
  ASSERT_TRUE(tx.send(f));
  ASSERT_TRUE(rx.waitFor([&] { return rx.count() >= 1; }, 2000ms));
  std::this_thread::sleep_for(100ms);
  const auto frames = rx.frames();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].id, 0x120u);
  EXPECT_EQ(frames[0].data[0], 0xAB);
}

TEST_F(Vcan, J1939FiltersMatchThePgnFromAnySource) {
  const CanSetup setup = setupOf("can-openimu.toml");
  const ImuFrameCodec codec(setup.config, setup.dbc);
  RunningReceiver rx(fastSettings(g_vcan, codec.kernelFilters()));
  ASSERT_TRUE(rx.waitUp()) << rx.status().last_error;
  Sender tx(g_vcan);
  CanFrame f;
  f.extended = true;
  f.len = 8;
  const std::uint32_t ours[] = {j1939Id(6, 61482, 0x80), j1939Id(3, 61485, 0x23), j1939Id(7, 65386, 0xFE)};
  const std::uint32_t others[] = {j1939Id(6, 61483, 0x80), j1939Id(6, 65387, 0x80), j1939Id(6, 61482 | 0x10000, 0x80)};
  for (std::uint32_t id : others) {
    f.id = id;
    ASSERT_TRUE(tx.send(f));
  }
  for (std::uint32_t id : ours) {
    f.id = id;
    ASSERT_TRUE(tx.send(f));
  }
  ASSERT_TRUE(rx.waitFor([&] { return rx.count() >= 3; }, 2000ms));
  std::this_thread::sleep_for(100ms);
  const auto frames = rx.frames();
  ASSERT_EQ(frames.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(frames[i].id, ours[i]);
}

TEST_F(Vcan, ErrorFramesAreReceivedAndCounted) {
  RunningReceiver rx(fastSettings(g_vcan, {{0x120, 0x7FF, false}}));
  ASSERT_TRUE(rx.waitUp()) << rx.status().last_error;
  Sender tx(g_vcan);
  // vcan has no controller to report errors; a frame sent with CAN_ERR_FLAG travels like a
  // kernel error report and reaches sockets that asked for error frames.
  CanFrame e;
  e.error_frame = true;
  e.len = 8;
  e.id = 0x40;  // CAN_ERR_BUSOFF
  ASSERT_TRUE(tx.send(e));
  e.id = 0x04;       // CAN_ERR_CRTL
  e.data[1] = 0x10;  // CAN_ERR_CRTL_RX_PASSIVE
  ASSERT_TRUE(tx.send(e));
  ASSERT_TRUE(rx.waitFor([&] { return rx.status().bus.error_frames >= 2; }, 2000ms))
      << "error frames received: " << rx.status().bus.error_frames;
  const auto s = rx.status();
  EXPECT_EQ(s.bus.bus_off, 1u);
  EXPECT_EQ(s.bus.controller_problems, 1u);
  EXPECT_EQ(s.bus.error_passive, 1u);
  const auto frames = rx.frames();
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_TRUE(frames[0].error_frame);
}

TEST_F(Vcan, FloodAtFullBusRateWithoutLoss) {
  // 1 Mbit/s classic CAN carries at most ~9000 frames/s (8 data bytes, 11-bit id, 111 bits
  // before stuffing). Send that for two seconds, paced by absolute deadlines.
  constexpr int kFramesPerSecond = 9000;
  constexpr int kSeconds = 2;
  constexpr int kTotal = kFramesPerSecond * kSeconds;
  RunningReceiver rx(fastSettings(g_vcan, {{0x120, 0x7FF, false}}));
  ASSERT_TRUE(rx.waitUp()) << rx.status().last_error;
  Sender tx(g_vcan);
  timespec next{};
  ::clock_gettime(CLOCK_MONOTONIC, &next);
  const auto start = std::chrono::steady_clock::now();
  CanFrame f;
  f.id = 0x120;
  f.len = 8;
  for (int i = 0; i < kTotal; ++i) {
    std::memcpy(f.data.data(), &i, sizeof i);
    ASSERT_TRUE(tx.send(f)) << "send " << i << ": " << std::strerror(errno);
    if (i % 9 == 8) {  // 9 frames per millisecond
      next.tv_nsec += 1'000'000;
      if (next.tv_nsec >= 1'000'000'000) {
        next.tv_nsec -= 1'000'000'000;
        ++next.tv_sec;
      }
      ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    }
  }
  const double send_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(rx.waitFor([&] { return rx.count() >= static_cast<std::size_t>(kTotal); }, 10000ms))
      << "received " << rx.count() << " of " << kTotal << ", kernel drops " << rx.status().kernel_drops;
  const auto frames = rx.frames();
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(kTotal));
  for (int i = 0; i < kTotal; ++i) {
    int got = -1;
    std::memcpy(&got, frames[static_cast<std::size_t>(i)].data.data(), sizeof got);
    ASSERT_EQ(got, i) << "frames lost or reordered";
  }
  EXPECT_EQ(rx.status().kernel_drops, 0u);
  std::printf("flood: %d frames in %.3f s (%.0f frames/s), receive buffer %d bytes\n", kTotal, send_s, kTotal / send_s,
              rx.status().receive_buffer_bytes);
}

TEST_F(Vcan, InterfaceDownAndUpIsSurvived) {
  RunningReceiver rx(fastSettings(g_vcan, {{0x120, 0x7FF, false}}));
  ASSERT_TRUE(rx.waitUp()) << rx.status().last_error;
  ASSERT_EQ(ip("link set " + g_vcan + " down"), 0);
  const bool went_down = rx.waitFor([&] { return rx.status().state != LinkState::up; }, 3000ms);
  const auto down = rx.status();
  ASSERT_EQ(ip("link set " + g_vcan + " up"), 0);
  ASSERT_TRUE(went_down) << "state stayed up";
  EXPECT_EQ(down.state, LinkState::down) << down.last_error;
  EXPECT_EQ(down.times_lost, 1u);
  EXPECT_FALSE(down.last_error.empty());
  ASSERT_TRUE(rx.waitUp(3000ms)) << rx.status().last_error;
  Sender tx(g_vcan);
  CanFrame f;
  f.id = 0x120;
  f.len = 8;
  ASSERT_TRUE(tx.send(f));
  ASSERT_TRUE(rx.waitFor([&] { return rx.count() >= 1; }, 2000ms)) << "no frame after coming back";
  EXPECT_EQ(rx.status().times_up, 2u);
}

TEST_F(Vcan, InterfaceRemovedAndAddedIsSurvived) {
  ASSERT_NE(::if_nametoindex(g_spare.c_str()), 0u) << "no interface " << g_spare;
  RunningReceiver rx(fastSettings(g_spare, {{0x120, 0x7FF, false}}));
  ASSERT_TRUE(rx.waitUp()) << rx.status().last_error;
  ASSERT_EQ(ip("link del " + g_spare), 0);
  const bool lost = rx.waitFor([&] { return rx.status().state == LinkState::waiting; }, 3000ms);
  const auto gone = rx.status();
  std::this_thread::sleep_for(300ms);  // a few retries against a missing interface
  const auto retrying = rx.status();
  ASSERT_EQ(ip("link add dev " + g_spare + " type vcan"), 0);
  ASSERT_EQ(ip("link set " + g_spare + " up"), 0);
  ASSERT_TRUE(lost) << "state " << linkStateName(gone.state) << ": " << gone.last_error;
  EXPECT_GT(retrying.open_attempts, gone.open_attempts);
  EXPECT_LE(retrying.next_retry_delay_ns, 200'000'000);
  ASSERT_TRUE(rx.waitUp(3000ms)) << rx.status().last_error;
  Sender tx(g_spare);
  CanFrame f;
  f.id = 0x120;
  f.len = 8;
  ASSERT_TRUE(tx.send(f));
  ASSERT_TRUE(rx.waitFor([&] { return rx.count() >= 1; }, 2000ms)) << "no frame after the interface came back";
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--vcan=", 0) == 0)
      g_vcan = arg.substr(7);
    else if (arg.rfind("--vcan-spare=", 0) == 0)
      g_spare = arg.substr(13);
  }
  return RUN_ALL_TESTS();
}
