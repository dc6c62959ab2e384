// Parts of the receiver that run on any host: error-frame decoding, and a real socket open
// on this machine. Without CAN in the kernel (or without the interface) the receiver must
// say so, keep retrying with a bounded back-off, and never crash or spin.
#include <gtest/gtest.h>

#include <linux/can/error.h>

#include <boost/asio/io_context.hpp>
#include <chrono>

#include "can_test_support.hpp"
#include "headingd/can/error_frame.hpp"
#include "headingd/can/socketcan_receiver.hpp"

namespace headingd::can {
namespace {

CanFrame errorFrame(std::uint32_t cls, std::initializer_list<std::pair<int, std::uint8_t>> bytes) {
  CanFrame f;
  f.error_frame = true;
  f.id = cls;
  f.len = 8;
  for (const auto& [i, v] : bytes) f.data[static_cast<std::size_t>(i)] = v;
  return f;
}

TEST(ErrorFrames, ClassesAndControllerDetailsAreCounted) {
  BusErrorCounters c;
  countErrorFrame(errorFrame(CAN_ERR_BUSOFF, {}), c);
  countErrorFrame(errorFrame(CAN_ERR_CRTL, {{1, CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_PASSIVE}}), c);
  countErrorFrame(errorFrame(CAN_ERR_CRTL, {{1, CAN_ERR_CRTL_RX_WARNING}}), c);
  countErrorFrame(errorFrame(CAN_ERR_PROT | CAN_ERR_BUSERROR, {{2, CAN_ERR_PROT_STUFF}}), c);
  countErrorFrame(errorFrame(CAN_ERR_ACK | CAN_ERR_RESTARTED, {}), c);
  countErrorFrame(errorFrame(CAN_ERR_CNT, {{6, 97}, {7, 130}}), c);
  countErrorFrame(test::frame(0x40, false, {0}), c);  // a data frame is not an error frame
  EXPECT_EQ(c.error_frames, 6u);
  EXPECT_EQ(c.bus_off, 1u);
  EXPECT_EQ(c.controller_problems, 2u);
  EXPECT_EQ(c.controller_rx_overflow, 1u);
  EXPECT_EQ(c.error_passive, 1u);
  EXPECT_EQ(c.error_warning, 1u);
  EXPECT_EQ(c.protocol_violations, 1u);
  EXPECT_EQ(c.bus_errors, 1u);
  EXPECT_EQ(c.no_ack, 1u);
  EXPECT_EQ(c.controller_restarted, 1u);
  EXPECT_EQ(c.last_tx_error_count, 97);
  EXPECT_EQ(c.last_rx_error_count, 130);
  char text[128];
  EXPECT_STREQ(errorClassSummary(CAN_ERR_BUSOFF | CAN_ERR_CRTL, text, sizeof text), "controller, bus-off");
}

TEST(SocketCanReceiverHost, MissingCanOrInterfaceIsReportedAndRetried) {
  boost::asio::io_context io;
  ReceiverSettings settings;
  settings.interface = "hdgnone0";  // never exists
  settings.reconnect_initial = std::chrono::milliseconds(10);
  settings.reconnect_max = std::chrono::milliseconds(40);
  int frames = 0;
  SocketCanReceiver receiver(io, settings, [&](const CanFrame&, std::int64_t) { ++frames; });
  receiver.start();
  io.run_for(std::chrono::milliseconds(400));
  const ReceiverStatus s = receiver.status();
  EXPECT_EQ(s.state, LinkState::waiting);
  EXPECT_EQ(frames, 0);
  // 10 + 20 + 40 + 40 ... ms: about 10 attempts in 400 ms, never a busy loop.
  EXPECT_GE(s.open_attempts, 5u);
  EXPECT_LE(s.open_attempts, 15u);
  EXPECT_EQ(s.open_failures, s.open_attempts);
  EXPECT_EQ(s.next_retry_delay_ns, 40'000'000);
  EXPECT_TRUE(s.last_errno == EAFNOSUPPORT || s.last_errno == ENODEV) << s.last_errno << " " << s.last_error;
  if (s.last_errno == EAFNOSUPPORT) {
    EXPECT_NE(s.last_error.find("the kernel has no CAN support"), std::string::npos) << s.last_error;
  } else {
    EXPECT_NE(s.last_error.find("no interface hdgnone0"), std::string::npos) << s.last_error;
  }
  receiver.stop();
  io.restart();
  io.run_for(std::chrono::milliseconds(50));
  EXPECT_EQ(receiver.status().open_attempts, s.open_attempts + 0) << "no attempts after stop()";
}

}  // namespace
}  // namespace headingd::can
