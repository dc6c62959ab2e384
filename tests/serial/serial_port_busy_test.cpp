// The serial port is ours alone: while another program holds the GPS port (a child process
// standing in for gpsd, reading what the receiver sends), the reader reads nothing, says who
// holds it by name and pid, counts it, and keeps retrying; once the holder lets go it opens
// the port and delivers the parser's fixes, bit for bit.
//
// How the holder takes the port is the parameter: TIOCEXCL alone (what gpsd does), flock
// alone (picocom), both. With CAP_SYS_ADMIN (root), open() ignores TIOCEXCL and the reader
// sees gpsd's mode with TIOCGEXCL; without it, open() fails with EBUSY. CTest runs this file
// both ways (serial.busy_port_unprivileged drops every capability with setpriv), so both
// paths are exercised.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <string>

#include "headingd/nmea/serial_gps_reader.hpp"
#include "headingd/nmea/serial_port_open.hpp"
#include "port_holder.hpp"
#include "pty_fixture.hpp"
#include "serial_reader_harness.hpp"
#include "serial_test_support.hpp"
#include "test_data.hpp"

namespace headingd::test {
namespace {

using nmea::SerialGpsState;

// Whether this process may open a tty in exclusive mode (bit 21 of CapEff, CAP_SYS_ADMIN).
bool hasCapSysAdmin() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("CapEff:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> 21) & 1u;
  }
  return false;
}

class SerialPortBusy : public ::testing::TestWithParam<HoldWith> {};

TEST_P(SerialPortBusy, HolderIsNamedCountedAndNotReadFromThenThePortIsOurs) {
  std::printf("running as uid %d, %s\n", static_cast<int>(::geteuid()),
              hasCapSysAdmin() ? "with CAP_SYS_ADMIN" : "without CAP_SYS_ADMIN");
  const auto wire = readWireBytes(test_data::file(test_data::kGpsdLogs, "mt3339.log"));
  nmea::Counters want_counters;
  const auto want = referenceEpochs(wire, &want_counters);
  ASSERT_GE(want.size(), 5u);

  PtyPair pty;
  // Behind a udev-style symlink, as /dev/gps0: the holder is found by the device's real path.
  TempDir dir;
  const auto link = dir.path() / "gps0";
  pointSymlink(link, pty.slavePath());
  PortHolder holder(pty.slavePath(), GetParam(), "gps-holder");
  const pid_t holder_pid = holder.pid();

  Harness h(testConfig(link.string()));
  ASSERT_TRUE(h.waitState(SerialGpsState::kBusy)) << h.counters().last_error;
  // The receiver talks meanwhile; everything it says goes to the holder, nothing to us.
  const auto first = std::span(wire).first(wire.size() / 2);
  pty.writePaced(first, lineBytesPerSecond(115200));
  ASSERT_TRUE(waitFor([&] { return holder.bytesRead() == first.size(); }, std::chrono::seconds(5)))
      << holder.bytesRead() << " of " << first.size();
  ASSERT_TRUE(waitFor([&] { return h.counters().port_busy >= 3; }, std::chrono::seconds(5)));

  auto c = h.counters();
  EXPECT_EQ(c.state, SerialGpsState::kBusy);
  const std::string named = "busy, held by gps-holder (pid " + std::to_string(holder_pid) + ")";
  EXPECT_NE(c.last_error.find(named), std::string::npos) << c.last_error;
  EXPECT_NE(c.last_error.find(link.string()), std::string::npos) << c.last_error;
  EXPECT_EQ(c.port_busy, c.open_attempts) << "every attempt found the port held";
  EXPECT_EQ(c.reads, 0u);
  EXPECT_EQ(c.parser.framing.bytes, 0u);
  EXPECT_EQ(h.received.fixCount(), 0u);
  EXPECT_EQ(holder.bytesRead(), first.size());

  holder.release();
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen)) << h.counters().last_error;
  const std::uint64_t busy_when_opened = h.counters().port_busy;
  pty.writePaced(wire, lineBytesPerSecond(115200));
  ASSERT_TRUE(h.waitBytes(wire.size()));
  ASSERT_TRUE(waitFor([&] { return h.received.fixCount() >= want.size(); }, std::chrono::seconds(3)));
  expectSameFixes(h.received.fixesCopy(), want);
  c = h.counters();
  expectCountersEqual(c.parser, want_counters);
  EXPECT_EQ(c.port_busy, busy_when_opened) << "no busy attempt once the port is ours";
  EXPECT_EQ(c.reopens, 0u) << "the first successful open is not a reopen";
  EXPECT_NE(c.last_error.find(named), std::string::npos) << "kept after recovery: " << c.last_error;
}

INSTANTIATE_TEST_SUITE_P(HoldWith, SerialPortBusy,
                         ::testing::Values(HoldWith::kExclusiveMode, HoldWith::kFlock, HoldWith::kBoth),
                         [](const auto& info) { return std::string(holdWithName(info.param)); });

// Once the reader has the port, a second opener is turned away: a second reader (another
// headingd on the same device) is busy and reads nothing. On a pty the guard is the flock
// alone: the reader does not put a pty in exclusive mode (a killed reader would leave it so
// while the pty's creator keeps the slave open, refusing the restarted one).
TEST(SerialPortExclusive, ASecondReaderOfTheSamePortIsTurnedAway) {
  PtyPair pty;
  Harness first(testConfig(pty.slavePath()));
  ASSERT_TRUE(first.waitState(SerialGpsState::kOpen));
  auto result = nmea::openSerialDevice(pty.slavePath(), 115200);
  ASSERT_TRUE(std::holds_alternative<nmea::SerialOpenFailure>(result));
  const auto& failure = std::get<nmea::SerialOpenFailure>(result);
  EXPECT_TRUE(failure.busy) << failure.message;
  // The holder is this very process, which the search leaves out (a process does not name
  // itself as the other program).
  EXPECT_NE(failure.message.find("busy, held by an unknown program"), std::string::npos) << failure.message;

  const int probe = ::open(pty.slavePath().c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  ASSERT_GE(probe, 0) << "a pty held by the reader can still be opened: it is not in exclusive mode";
  int exclusive = -1;
  ASSERT_EQ(::ioctl(probe, TIOCGEXCL, &exclusive), 0);
  EXPECT_EQ(exclusive, 0);
  ::close(probe);

  // Once the first reader stops, its lock is gone with its descriptor.
  first.stop();
  result = nmea::openSerialDevice(pty.slavePath(), 115200);
  ASSERT_TRUE(std::holds_alternative<nmea::OpenedSerialDevice>(result))
      << std::get<nmea::SerialOpenFailure>(result).message;
  const int fd = std::get<nmea::OpenedSerialDevice>(result).fd;
  nmea::releaseSerialDevice(fd);
  ::close(fd);
}

// The daemon killed while it has the port (SIGKILL, or the watchdog's SIGABRT): its restart
// opens the port at once. On a pty whose creator keeps the slave open, exclusive mode set by
// the killed reader would outlive it and refuse the restart; its flock dies with it.
TEST(SerialPortExclusive, AReaderKilledWithThePortOpenDoesNotLockOutItsRestart) {
  PtyPair pty;
  int ready[2];
  ASSERT_EQ(::pipe2(ready, O_CLOEXEC), 0);
  const pid_t killed = ::fork();
  ASSERT_GE(killed, 0);
  if (killed == 0) {  // the reader that is killed: opens the port as the reader does, then waits
    auto opened = nmea::openSerialDevice(pty.slavePath(), 115200);
    const char ok = std::holds_alternative<nmea::OpenedSerialDevice>(opened) ? 1 : 0;
    if (::write(ready[1], &ok, 1) != 1) ::_exit(1);
    for (;;) ::pause();
  }
  ::close(ready[1]);
  char ok = 0;
  ASSERT_EQ(::read(ready[0], &ok, 1), 1);
  ::close(ready[0]);
  ASSERT_EQ(ok, 1) << "the first reader could not open the port";
  ::kill(killed, SIGKILL);
  ::waitpid(killed, nullptr, 0);

  Harness restarted(testConfig(pty.slavePath()));
  ASSERT_TRUE(restarted.waitState(SerialGpsState::kOpen)) << restarted.counters().last_error;
  EXPECT_EQ(restarted.counters().port_busy, 0u);
}

}  // namespace
}  // namespace headingd::test
