// The daemon with [gps] source = "gpsd": against a real gpsd (Debian's) reading the demo
// capture's NMEA from a pty, compared with the serial source reading the same bytes; and
// against a misbehaving peer (a small TCP server here) that sends garbage, closes mid-line
// and goes away for a while.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "daemon_test_support.hpp"
#include "headingd/core/angles.hpp"
#include "lcm_collector.hpp"
#include "pty_fixture.hpp"
#include "status_lookup.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using namespace test;

using core::kDegPerRad;

std::optional<headingd::source_status_t> lastSource(const LcmCollector& lcm, const std::string& kind) {
  const auto s = lcm.status();
  const auto* src = s.empty() ? nullptr : findSource(s.back().message, kind);
  if (src == nullptr) return std::nullopt;
  return *src;
}

// A port for this test run (the namespace is private where permitted; else distinct per pid).
int testPort(int offset) { return 30000 + (getpid() % 10000) * 2 + offset; }

std::string daemonConfig(const std::string& url, const std::string& gps_table) {
  // The TPVs' dates are 2026-06-01: the GPS dates are checked against that day, not the
  // system clock's (gps_date_seed).
  return "[daemon]\nstatus_period_s = 0.25\ngps_date_seed = 2026.41\nwmm = "
         "\"" HEADINGD_CONFIG_DIR "/wmm/WMM2025.COF\"\n[lcm]\nurl = \"" +
         url + "\"\n[recorder]\nenabled = false\n[imu_csv]\nenabled = true\npath = \"" + kDemoImuCsv +
         "\"\ntime_axis = \"monotonic\"\n[gps]\n" + gps_table;
}

// The first `epochs` epochs of the capture, each its sentences (GGA, RMC, VTG: a GGA starts one).
std::vector<std::string> captureEpochs(std::size_t epochs) {
  std::ifstream in(kDemoNmea);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (line.compare(3, 3, "GGA") == 0) {
      if (out.size() == epochs) break;
      out.emplace_back();
    }
    if (!out.empty()) out.back() += line + "\r\n";
  }
  return out;
}

std::span<const std::uint8_t> bytesOf(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Both sources on the same 45 epochs (fix lost for 11 s, then a walk): gpsd decodes the
// sentences itself, the serial source with headingd's parser; every fix gpsd passes on must
// be one of the serial source's, with the same course, speed, variation, height and date
// within the sentences' resolution.
TEST(DaemonGpsdSource, RealGpsdGivesTheSameFixesAsTheSerialSource) {
  test::TempDir dir;
  headingd::test::PtyPair serial_pty, gpsd_pty;
  // gpsd drops root for its own user before it opens the device.
  ASSERT_EQ(::chmod(gpsd_pty.slavePath().c_str(), 0666), 0);
  const int gpsd_port = testPort(1);
  ChildProcess gpsd({HEADINGD_GPSD_BIN, "-N", "-n", "-F", dir.file("gpsd.sock"), "-S", std::to_string(gpsd_port),
                     gpsd_pty.slavePath()},
                    dir.file("gpsd.out"), dir.file("gpsd.err"));
  const std::string url_serial = lcmUrl(20), url_gpsd = lcmUrl(22);
  const std::string serial_config = dir.write(
      "serial.toml", daemonConfig(url_serial, "device = \"" + serial_pty.slavePath() + "\"\nepoch_idle_s = 0.1\n"));
  const std::string gpsd_config =
      dir.write("gpsd.toml",
                daemonConfig(url_gpsd, "source = \"gpsd\"\nhost = \"127.0.0.1\"\nport = " + std::to_string(gpsd_port) +
                                           "\nepoch_idle_s = 0.1\nreopen_backoff_initial_s = 0.05\n"));
  LcmCollector lcm_serial(url_serial), lcm_gpsd(url_gpsd);
  ChildProcess serial_daemon({HEADINGD_BIN, "--config", serial_config}, dir.file("serial.out"), dir.file("serial.err"));
  ChildProcess gpsd_daemon({HEADINGD_BIN, "--config", gpsd_config}, dir.file("gpsd-daemon.out"),
                           dir.file("gpsd-daemon.err"));
  ASSERT_TRUE(waitUntil(
      [&] {
        const auto s = lastSource(lcm_serial, "gps_serial");
        const auto g = lastSource(lcm_gpsd, "gps_gpsd");
        return s && s->state == "running" && g && g->state == "running";
      },
      8s))
      << test::readFile(dir.file("gpsd-daemon.err")) << test::readFile(dir.file("gpsd.err"));

  const auto epochs = captureEpochs(45);
  for (const std::string& epoch : epochs) {
    serial_pty.write(bytesOf(epoch));
    gpsd_pty.write(bytesOf(epoch));
    std::this_thread::sleep_for(250ms);  // a receiver's burst, then quiet (4x real time)
  }
  std::this_thread::sleep_for(1000ms);
  serial_daemon.signal(SIGTERM);
  gpsd_daemon.signal(SIGTERM);
  EXPECT_EQ(serial_daemon.waitFor(2s), 0);
  EXPECT_EQ(gpsd_daemon.waitFor(2s), 0) << test::readFile(dir.file("gpsd-daemon.err"));
  gpsd.signal(SIGTERM);
  gpsd.waitFor(2s);
  lcm_serial.stop();
  lcm_gpsd.stop();

  const auto serial = lcm_serial.gps();
  const auto from_gpsd = lcm_gpsd.gps();
  std::size_t serial_with_position = 0, gpsd_with_position = 0, matched = 0, hdop_compared = 0, without_date = 0;
  for (const auto& s : serial) serial_with_position += s.message.has_position ? 1 : 0;
  for (const auto& g : from_gpsd) {
    const auto& m = g.message;
    EXPECT_EQ(m.source, "gps");
    if (!m.has_position) {
      EXPECT_FALSE(m.fix_ok);
      continue;
    }
    ++gpsd_with_position;
    const headingd::gps_t* twin = nullptr;
    for (const auto& s : serial) {
      // gpsd prints degrees to 9 decimals; the sentences carry 1e-5 minutes (1.7e-7 degrees).
      if (s.message.has_position && std::abs(s.message.latitude_deg - m.latitude_deg) < 1e-8 &&
          std::abs(s.message.longitude_deg - m.longitude_deg) < 1e-8) {
        twin = &s.message;
      }
    }
    ASSERT_NE(twin, nullptr) << "gpsd's fix at " << m.latitude_deg << ", " << m.longitude_deg
                             << " is not the serial source's";
    ++matched;
    EXPECT_EQ(m.fix_ok, twin->fix_ok);
    if (std::isnan(m.decimal_year)) {
      // gpsd's first fix, while it still identifies the receiver: from the GGA alone (it
      // passes on no RMC of that epoch, so no date, course or speed of the receiver's).
      ++without_date;
      continue;
    }
    EXPECT_NEAR(m.height_m, twin->height_m, 0.01);
    EXPECT_NEAR(m.decimal_year, twin->decimal_year, 1e-9);
    ASSERT_EQ(m.has_course, twin->has_course) << m.latitude_deg;
    if (m.has_course) {
      EXPECT_NEAR(m.course_rad * kDegPerRad, twin->course_rad * kDegPerRad, 0.006);  // 0.01 deg in RMC
    }
    ASSERT_EQ(m.has_speed, twin->has_speed);
    if (m.has_speed) {
      EXPECT_NEAR(m.speed_mps, twin->speed_mps, 0.0006);  // gpsd prints mm/s
    }
    ASSERT_EQ(m.has_magvar, twin->has_magvar);
    if (m.has_magvar) {
      EXPECT_NEAR(m.magvar_rad, twin->magvar_rad, 1e-9);
    }
    if (m.has_hdop && twin->has_hdop) {
      ++hdop_compared;
      EXPECT_NEAR(m.hdop, twin->hdop, 0.005);
    }
  }
  // gpsd needs an epoch or two to recognise the receiver before it reports.
  EXPECT_GE(matched + 2, serial_with_position);
  EXPECT_EQ(matched, gpsd_with_position);
  EXPECT_LE(without_date, 2u);
  const auto status = lcm_gpsd.status();
  ASSERT_FALSE(status.empty());
  const auto* source = findSource(status.back().message, "gps_gpsd");
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(counter(*source, "epochs_pushed"), static_cast<std::int64_t>(from_gpsd.size()));
  EXPECT_EQ(counter(*source, "malformed"), 0);
  EXPECT_EQ(counter(*source, "disconnects"), 0);
  std::fprintf(
      stderr,
      "serial source: %zu fixes (%zu with a position); gpsd source: %zu fixes (%zu with a position, %zu equal to "
      "the serial source's, %zu of them without a date, %zu with HDOP compared); gpsd TPV reports %lld, late %lld\n",
      serial.size(), serial_with_position, from_gpsd.size(), gpsd_with_position, matched, without_date, hdop_compared,
      static_cast<long long>(counter(*source, "tpv_reports")),
      static_cast<long long>(counter(*source, "late_reports")));
}

// A listening TCP socket on 127.0.0.1:port (SO_REUSEADDR, so it can come back at once).
int listenOn(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 4) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

void sendAll(int fd, const std::string& s) {
  std::size_t sent = 0;
  while (sent < s.size()) {
    const ssize_t n = ::send(fd, s.data() + sent, s.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

std::string readCommand(int fd) {
  std::string got;
  char buf[256];
  while (got.find('\n') == std::string::npos) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    got.append(buf, static_cast<std::size_t>(n));
  }
  return got;
}

std::string tpvAt(int second, double lat) {
  char line[256];
  std::snprintf(
      line, sizeof line,
      R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:%02d.000Z","lat":%.9f,"lon":18.07,"track":45.0,"speed":1.2})"
      "\r\n",
      second, lat);
  return line;
}

// The peer: malformed JSON, a fix without a position, an endless line, a cut line and a close;
// then nothing listening for a while (gpsd restarting); then a good gpsd. The daemon counts
// each, logs them (bounded), reconnects, keeps publishing estimates throughout, and stops on
// SIGTERM as usual.
TEST(DaemonGpsdSource, MisbehavingPeerIsCountedLoggedAndReconnectedWithoutAStall) {
  test::TempDir dir;
  const int port = testPort(3);
  int listener = listenOn(port);
  ASSERT_GE(listener, 0);
  const std::string url = lcmUrl(24);
  const std::string config = dir.write(
      "gpsd.toml",
      daemonConfig(url, "source = \"gpsd\"\nport = " + std::to_string(port) +
                            "\nepoch_idle_s = 0.1\nreopen_backoff_initial_s = 0.1\nreopen_backoff_max_s = 0.4\n"));
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));

  int peer = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
  ASSERT_GE(peer, 0);
  EXPECT_EQ(readCommand(peer), "?WATCH={\"enable\":true,\"json\":true};\n");
  sendAll(peer, R"({"class":"VERSION","release":"3.22","proto_major":3,"proto_minor":14})"
                "\r\n");
  sendAll(peer, tpvAt(1, 59.33));
  std::this_thread::sleep_for(300ms);
  sendAll(peer, "{\"class\":\"TPV\",\"mode\":3,\"lat\":\n");  // malformed
  sendAll(peer, "\x01\x02 binary garbage\n");                 // malformed
  sendAll(peer, R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:02.000Z"})"
                "\n");  // no lat/lon
  sendAll(peer, R"({"class":"TPV","time":"2026-06-01T12:00:03.000Z","lat":59.33,"lon":18.07})"
                "\n");  // no mode: not a fix, no epoch
  // 1024 weeks before 2026-06-01 (a receiver after a week-number rollover): the epoch is
  // delivered, but the World Magnetic Model is not evaluated on its date.
  sendAll(peer, R"({"class":"TPV","mode":3,"time":"2006-10-16T12:00:04.000Z","lat":59.33,"lon":18.07})"
                "\n");
  sendAll(peer, std::string(100000, 'x') + "\n");                                     // oversized
  sendAll(peer, R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:03.000Z","la)");  // cut
  std::this_thread::sleep_for(200ms);
  ::close(peer);
  ::close(listener);  // gpsd gone: connects fail for a while

  const auto headings_before = lcm.heading().size();
  std::this_thread::sleep_for(1500ms);
  const auto while_away = lastSource(lcm, "gps_gpsd");
  ASSERT_TRUE(while_away);
  EXPECT_EQ(while_away->state, "waiting");
  EXPECT_NE(while_away->last_error.find("gpsd at 127.0.0.1:" + std::to_string(port)), std::string::npos)
      << while_away->last_error;
  EXPECT_GT(lcm.heading().size(), headings_before + 50);  // the estimator goes on (100 Hz)

  listener = listenOn(port);
  ASSERT_GE(listener, 0);
  peer = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
  ASSERT_GE(peer, 0);
  EXPECT_EQ(readCommand(peer), "?WATCH={\"enable\":true,\"json\":true};\n");
  for (int s = 10; s < 15; ++s) {
    sendAll(peer, tpvAt(s, 59.34 + s * 1e-5));
    std::this_thread::sleep_for(200ms);
  }
  ASSERT_TRUE(waitUntil(
      [&] {
        const auto g = lastSource(lcm, "gps_gpsd");
        return g && g->state == "running" && counter(*g, "epochs") >= 8;
      },
      3s));
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(1s), 0);
  ::close(peer);
  ::close(listener);
  lcm.stop();

  const auto g = *lastSource(lcm, "gps_gpsd");
  EXPECT_EQ(counter(g, "malformed"), 2);
  EXPECT_EQ(counter(g, "missing_fields"), 2);
  EXPECT_EQ(counter(g, "oversized_lines"), 1);
  EXPECT_EQ(counter(g, "cut_lines"), 1);
  EXPECT_EQ(counter(g, "connects"), 2);
  EXPECT_GE(counter(g, "connect_failures"), 2);
  EXPECT_EQ(counter(g, "disconnects"), 1);
  EXPECT_EQ(counter(g, "epochs"), 8);  // 12:00:01, 12:00:02 (no position), the 2006 one, 12:00:10 .. 14
  EXPECT_EQ(statusCounter(lcm.status().back().message, "gps_dates_not_believed"), 1);
  const auto gps = lcm.gps();
  ASSERT_EQ(gps.size(), 8u);
  EXPECT_TRUE(gps[0].message.fix_ok);
  EXPECT_FALSE(gps[1].message.fix_ok);
  EXPECT_NEAR(gps.back().message.latitude_deg, 59.34 + 14e-5, 1e-9);
  EXPECT_NEAR(gps.back().message.course_rad * kDegPerRad, 45.0, 1e-9);
  const std::string log = test::readFile(dir.file("err"));
  for (const char* kind : {"gpsd line malformed: not JSON", "gpsd line missing_fields: TPV without lat/lon",
                           "gpsd line missing_fields: TPV without mode (not used)", "gpsd line oversized",
                           "gpsd line cut", "gpsd closed the connection", "connected to gpsd at 127.0.0.1"}) {
    EXPECT_NE(log.find(kind), std::string::npos) << kind << "\n" << log;
  }
  std::fprintf(stderr, "gpsd source after the misbehaving peer: %s\n", g.last_error.c_str());
}

}  // namespace
}  // namespace headingd::daemon
