// [nmea_out] end to end: the headingd binary on the demo capture (file sources: THS mode S),
// its TCP server on loopback in a private network namespace (in-private-net.sh), real TCP
// clients, a real gpsd and gpspipe, and a real LCM subscriber to compare with HEADING.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "daemon_test_support.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/nmea/checksum.hpp"
#include "headingd/nmea/framer.hpp"
#include "headingd/nmea/sentences.hpp"
#include "lcm_collector.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using namespace test;

constexpr int kNmeaPort = 10110;
using core::kDegPerRad;

double steadyNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The demo configuration with absolute paths, an LCM URL of this test's own, the given play
// speed and estimator rate, and `nmea_out` as the [nmea_out] table.
std::string demoConfig(const TempDir& dir, const std::string& url, double speed, double rate_hz,
                       const std::string& nmea_out) {
  std::string demo = test::readFile(HEADINGD_CONFIG_DIR "/demo.toml");
  for (const std::string key : {"wmm = \"", "path = \"", "can_config = \""}) {
    for (std::size_t at = demo.find(key); at != std::string::npos; at = demo.find(key, at + 1)) {
      demo.insert(at + key.size(), HEADINGD_CONFIG_DIR "/");
    }
  }
  const auto replace = [&demo](const std::string& from, const std::string& to) {
    const std::size_t at = demo.find(from);
    if (at == std::string::npos) throw std::runtime_error("demo.toml has no '" + from + "'");
    demo.replace(at, from.size(), to);
  };
  replace("udpm://239.255.76.67:7667?ttl=0", url);
  replace("speed = 1.0", "speed = " + std::to_string(speed));
  replace("rate_hz = 100.0", "rate_hz = " + std::to_string(rate_hz));
  replace("console_status = true", "console_status = false");
  return dir.write("demo.toml",
                   demo + "\n[nmea_out]\nenabled = true\ntcp_port = " + std::to_string(kNmeaPort) + "\n" + nmea_out);
}

// A TCP client of the daemon's server: connects (retrying until the server listens), then
// reads lines on a thread of its own and stamps them, or, with read = false, never reads.
class NmeaClient {
 public:
  explicit NmeaClient(bool read = true, int receive_buffer = 0) {
    const auto until = std::chrono::steady_clock::now() + 10s;
    for (;;) {
      fd_ = socket(AF_INET, SOCK_STREAM, 0);
      if (receive_buffer > 0) setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
      sockaddr_in at{};
      at.sin_family = AF_INET;
      at.sin_port = htons(kNmeaPort);
      at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      if (connect(fd_, reinterpret_cast<sockaddr*>(&at), sizeof at) == 0) break;
      close(fd_);
      fd_ = -1;
      if (std::chrono::steady_clock::now() > until) throw std::runtime_error("cannot connect to the NMEA server");
      std::this_thread::sleep_for(20ms);
    }
    if (read) thread_ = std::thread([this] { readLines(); });
  }
  ~NmeaClient() { disconnect(); }
  void disconnect() {
    if (fd_ >= 0) shutdown(fd_, SHUT_RDWR);
    if (thread_.joinable()) thread_.join();
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
  }
  void send(const std::string& bytes) const {
    ASSERT_EQ(::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL), static_cast<ssize_t>(bytes.size()));
  }

  struct Line {
    std::string text;  // as framed: '$' through "*hh"
    double receive_s = 0;
  };
  std::vector<Line> lines() const {
    std::lock_guard lock(mutex_);
    return lines_;
  }
  std::uint64_t badChecksums() const { return bad_checksums_.load(); }
  std::uint64_t garbageBytes() const { return garbage_.load(); }

 private:
  void readLines() {
    nmea::Framer framer;  // this project's own framer and checksum check
    char buffer[4096];
    for (;;) {
      const ssize_t n = recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      const double now = steadyNow();
      for (ssize_t i = 0; i < n; ++i) {
        if (const auto line = framer.push(static_cast<std::uint8_t>(buffer[i]))) {
          std::lock_guard lock(mutex_);
          lines_.push_back({std::string(*line), now});
        }
      }
      bad_checksums_ = framer.counters().bad_checksum + framer.counters().missing_checksum;
      garbage_ = framer.counters().garbage_bytes + framer.counters().truncated;
    }
  }

  int fd_ = -1;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::vector<Line> lines_;
  std::atomic<std::uint64_t> bad_checksums_{0}, garbage_{0};
};

// Datagrams to 127.0.0.1:port, received on a thread of its own.
class UdpReceiver {
 public:
  explicit UdpReceiver(int port) {
    fd_ = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in at{};
    at.sin_family = AF_INET;
    at.sin_port = htons(static_cast<std::uint16_t>(port));
    at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(fd_, reinterpret_cast<sockaddr*>(&at), sizeof at) != 0) throw std::runtime_error("UDP bind failed");
    timeval timeout{0, 100'000};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    thread_ = std::thread([this] {
      char buffer[2048];
      while (!stop_) {
        const ssize_t n = recv(fd_, buffer, sizeof buffer, 0);
        if (n <= 0) continue;
        std::lock_guard lock(mutex_);
        datagrams_.emplace_back(buffer, static_cast<std::size_t>(n));
      }
    });
  }
  ~UdpReceiver() {
    stop_ = true;
    thread_.join();
    close(fd_);
  }
  std::vector<std::string> datagrams() const {
    std::lock_guard lock(mutex_);
    return datagrams_;
  }

 private:
  int fd_ = -1;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::vector<std::string> datagrams_;
  std::thread thread_;
};

std::int64_t counter(const headingd::status_t& s, const std::string& name) {
  for (const auto& c : s.counters) {
    if (c.name == name) return c.value;
  }
  return -1;
}

double circularDiff(double a, double b) {
  double d = std::fmod(std::fabs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

// True when some fresh HEADING received within `window_s` of `when_s` has a true heading
// within `tolerance_deg` of `deg`.
bool matchesHeading(const std::vector<test::Received<headingd::heading_t>>& heading, double deg, double when_s,
                    double window_s, double tolerance_deg) {
  for (const auto& h : heading) {
    if (h.message.validity != headingd::heading_t::VALIDITY_FRESH) continue;
    if (std::fabs(h.receive_s - when_s) > window_s) continue;
    if (circularDiff(h.message.heading_true_rad * kDegPerRad, deg) <= tolerance_deg) return true;
  }
  return false;
}

template <class T>
std::optional<T> decodeLine(std::optional<T> (*decoder)(const nmea::FieldList&, int&), const std::string& line) {
  const auto fields = nmea::FieldList::split(line);
  if (!fields) return std::nullopt;
  int invalid = 0;
  auto decoded = decoder(*fields, invalid);
  if (invalid != 0) return std::nullopt;
  return decoded;
}

// (a) Raw TCP clients and UDP datagrams: the sentences carry HEADING's true heading to their resolution, THS says
// S (files), HDG adds up; clients come and go, one sends garbage: all counted on STATUS.
TEST(DaemonNmeaOut, TcpClientsAndUdpGetTheHeadingOfLcmWithinTheSentenceResolution) {
  TempDir dir;
  const std::string url = lcmUrl(40);
  const std::string config = demoConfig(dir, url, 10.0, 100.0,
                                        "rate_hz = 10\nsentences = [\"HDT\", \"THS\", \"HDG\"]\n"
                                        "udp = true\nudp_port = 10111\n");
  UdpReceiver udp(10111);
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  NmeaClient reader;
  NmeaClient garbage;
  const std::string junk = "hello headingd\r\n$GPGGA,not,a,request*00\r\n" + std::string(1000, '\x7f');
  garbage.send(junk);
  // Clients that connect and go at will.
  for (int i = 0; i < 20; ++i) {
    NmeaClient fleeting(i % 2 == 0);
    std::this_thread::sleep_for(20ms);
  }
  std::this_thread::sleep_for(2500ms);
  const std::vector<NmeaClient::Line> lines = reader.lines();
  ASSERT_TRUE(waitUntil(
      [&] {
        return !lcm.status().empty() && counter(lcm.status().back().message, "nmea_out_bytes_received") >=
                                            static_cast<std::int64_t>(junk.size());
      },
      3s))
      << test::readFile(dir.file("err"));
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(5s), 0) << test::readFile(dir.file("err"));
  lcm.stop();
  reader.disconnect();

  EXPECT_EQ(reader.badChecksums(), 0u);
  EXPECT_EQ(reader.garbageBytes(), 0u);
  const auto heading = lcm.heading();
  std::size_t hdt = 0, ths_s = 0, hdg = 0, unmatched = 0;
  std::optional<double> last_hdt;
  for (const auto& line : lines) {
    const std::string type = line.text.substr(3, 3);
    ASSERT_EQ(line.text.substr(0, 3), "$HE") << line.text;
    if (type == "HDT") {
      const auto d = decodeLine(nmea::decodeHdt, line.text);
      ASSERT_TRUE(d && d->heading_deg) << line.text;
      ++hdt;
      last_hdt = *d->heading_deg;
      // The value of a HEADING sent at the same tick, to 0.05 deg (half the resolution).
      if (!matchesHeading(heading, *d->heading_deg, line.receive_s, 0.5, 0.05 + 1e-9)) {
        ++unmatched;
        ADD_FAILURE() << line.text << " matches no HEADING within 0.5 s";
      }
    } else if (type == "THS") {
      const auto d = decodeLine(nmea::decodeThs, line.text);
      ASSERT_TRUE(d && d->mode) << line.text;
      if (*d->mode == 'S') {
        ++ths_s;
        ASSERT_TRUE(last_hdt.has_value());
        EXPECT_EQ(d->heading_deg, last_hdt) << line.text;  // the same estimate as the HDT before it
      } else {
        EXPECT_EQ(*d->mode, 'V') << line.text;  // before the first declination
      }
    } else if (type == "HDG") {
      const auto d = decodeLine(nmea::decodeHdg, line.text);
      ASSERT_TRUE(d && d->heading_deg && d->deviation_deg) << line.text;
      if (!d->variation_deg) continue;  // no declination yet: no HDT either
      ASSERT_TRUE(last_hdt.has_value()) << line.text;
      ++hdg;
      // magnetic + deviation + variation = true, each rounded to 0.1.
      EXPECT_LE(circularDiff(*d->heading_deg + *d->deviation_deg + *d->variation_deg, *last_hdt), 0.1 + 1e-9)
          << line.text;
    } else {
      ADD_FAILURE() << "unexpected sentence " << line.text;
    }
  }
  // 2.5 s and more at 10 Hz, less the start (the first GPS epoch brings the declination).
  EXPECT_GE(hdt, 20u);
  EXPECT_EQ(ths_s, hdt);
  EXPECT_EQ(hdg, hdt);
  EXPECT_EQ(unmatched, 0u);

  // UDP: one sentence a datagram, the same sentences as over TCP.
  const std::vector<std::string> datagrams = udp.datagrams();
  std::size_t udp_hdt = 0;
  for (const std::string& d : datagrams) {
    ASSERT_GE(d.size(), 6u);
    EXPECT_EQ(d.substr(d.size() - 2), "\r\n");
    EXPECT_EQ(d.find('$', 1), std::string::npos) << d;  // one sentence
    EXPECT_EQ(nmea::verifyChecksum(d.substr(0, d.size() - 2)), nmea::ChecksumVerdict::kOk) << d;
    udp_hdt += d.substr(3, 3) == "HDT";
  }
  EXPECT_GE(udp_hdt, hdt);  // UDP began before the TCP reader connected

  const headingd::status_t status = lcm.status().back().message;
  EXPECT_EQ(counter(status, "nmea_out_clients"), 2);
  EXPECT_EQ(counter(status, "nmea_out_connections"), 22);
  EXPECT_EQ(counter(status, "nmea_out_clients_refused"), 0);
  EXPECT_EQ(counter(status, "nmea_out_bytes_received"), static_cast<std::int64_t>(junk.size()));
  // Every sentence received was counted, but those of the last second (after the last STATUS:
  // 30 a second to each of the two).
  EXPECT_GE(counter(status, "nmea_out_sentences_sent"),
            static_cast<std::int64_t>(lines.size() + datagrams.size()) - 60);
  EXPECT_EQ(counter(status, "nmea_out_sentences_dropped"), 0);
  const std::string err = test::readFile(dir.file("err"));
  EXPECT_NE(err.find("nmea_out: serving HEHDT, HETHS, HEHDG at 10 Hz to TCP clients on 127.0.0.1 port 10110"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("bytes; ignored (headingd only sends)"), std::string::npos) << err;
}

// Lines appended to a file by another process, stamped when this process saw them.
class FileTail {
 public:
  explicit FileTail(std::string path) : path_(std::move(path)), thread_([this] { run(); }) {}
  ~FileTail() {
    stop_ = true;
    thread_.join();
  }
  std::vector<NmeaClient::Line> lines() const {
    std::lock_guard lock(mutex_);
    return lines_;
  }

 private:
  void run() {
    std::string pending;
    std::size_t offset = 0;
    while (!stop_) {
      std::ifstream in(path_, std::ios::binary);
      in.seekg(static_cast<std::streamoff>(offset));
      std::string chunk((std::istreambuf_iterator<char>(in)), {});
      offset += chunk.size();
      pending += chunk;
      const double now = steadyNow();
      for (std::size_t nl; (nl = pending.find('\n')) != std::string::npos;) {
        std::lock_guard lock(mutex_);
        lines_.push_back({pending.substr(0, nl), now});
        pending.erase(0, nl + 1);
      }
      std::this_thread::sleep_for(5ms);
    }
  }
  std::string path_;
  mutable std::mutex mutex_;
  std::vector<NmeaClient::Line> lines_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// True when this process's network namespace has the loopback interface only: a private one
// (in-private-net.sh), not the host's. (/proc/1/ns/net, to compare with, is not readable in
// every container.)
bool inPrivateNetworkNamespace() {
  std::ifstream dev("/proc/self/net/dev");
  std::string line;
  std::size_t interfaces = 0;
  bool loopback = false;
  while (std::getline(dev, line)) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;  // the two header lines
    std::string name = line.substr(0, colon);
    name.erase(0, name.find_first_not_of(' '));
    ++interfaces;
    loopback = loopback || name == "lo";
  }
  return interfaces == 1 && loopback;
}

// (b) A real gpsd reads headingd's TCP server as a device and reports the heading as ATT to
// its clients (gpspipe). Debian 12's gpsd (3.22) takes HDT only, and only from the talkers
// its lexer knows (HC, II, GP, ...; not HE): hence talker = "II".
TEST(DaemonNmeaOut, GpsdReadsTheHeadingAndReportsItAsAtt) {
  // gpsd listens on a TCP port and talks to the system bus: run only where in-private-net.sh
  // gave the test a network of its own (CTest does), never on the shared machine's network.
  // Without the gpsd package (a machine set up without install-deps.sh) there is nothing to run.
  if (!inPrivateNetworkNamespace()) GTEST_SKIP() << "gpsd runs only in a private network namespace";
  if (access("/usr/sbin/gpsd", X_OK) != 0 || access("/usr/bin/gpspipe", X_OK) != 0) {
    GTEST_SKIP() << "gpsd or gpspipe missing (tools/scripts/install-deps.sh installs them)";
  }
  TempDir dir;
  chmod(dir.path().c_str(), 0755);  // gpsd drops root for its own user
  const std::string url = lcmUrl(42);
  const std::string config = demoConfig(dir, url, 10.0, 100.0, "rate_hz = 10\ntalker = \"II\"\n");
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  ASSERT_NO_THROW(NmeaClient probe(false));  // the server listens
  // Its own IPC namespace (gpsd puts its fix and NTP time into System V shared memory) and no
  // system bus (gpsd announces fixes on D-Bus): nothing of the host is touched.
  const std::string gpsd_port = "29470";
  ChildProcess gpsd(
      {"/usr/bin/unshare", "-i", "/usr/bin/env", "DBUS_SYSTEM_BUS_ADDRESS=unix:path=/nonexistent", "/usr/sbin/gpsd",
       "-N", "-n", "-b", "-F", dir.file("gpsd.sock"), "-S", gpsd_port, "tcp://127.0.0.1:" + std::to_string(kNmeaPort)},
      dir.file("gpsd.out"), dir.file("gpsd.err"));
  std::this_thread::sleep_for(500ms);  // gpsd listens
  FileTail tail(dir.file("gpspipe.out"));
  ChildProcess gpspipe({"/usr/bin/gpspipe", "-w", "-n", "40", "127.0.0.1:" + gpsd_port}, dir.file("gpspipe.out"),
                       dir.file("gpspipe.err"));
  const int gpspipe_status = gpspipe.waitFor(15s);
  std::this_thread::sleep_for(100ms);
  gpsd.signal(SIGTERM);
  gpsd.waitFor(3s);
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(5s), 0) << test::readFile(dir.file("err"));
  lcm.stop();
  ASSERT_EQ(gpspipe_status, 0) << test::readFile(dir.file("gpspipe.err")) << test::readFile(dir.file("gpsd.err"));

  const auto heading = lcm.heading();
  std::size_t att = 0;
  for (const auto& line : tail.lines()) {
    if (line.text.find("\"class\":\"ATT\"") == std::string::npos) continue;
    const std::size_t at = line.text.find("\"heading\":");
    ASSERT_NE(at, std::string::npos) << line.text;
    const double deg = std::strtod(line.text.c_str() + at + 10, nullptr);
    ++att;
    EXPECT_TRUE(matchesHeading(heading, deg, line.receive_s, 0.5, 0.05 + 1e-9))
        << line.text << " matches no HEADING within 0.5 s";
  }
  std::fprintf(
      stderr,
      "gpspipe: %zu ATT reports, each within 0.05 deg (HDT's resolution) of a fresh HEADING received within 0.5 s\n",
      att);
  EXPECT_GE(att, 30u) << test::readFile(dir.file("gpspipe.out"));
  EXPECT_NE(test::readFile(dir.file("gpspipe.out")).find("\"driver\":\"NMEA0183\""), std::string::npos);
}

// (c) A client that never reads: its queue fills and its sends are dropped and counted, while
// a reading client gets every send and the estimator keeps its rate; a third client, beyond
// max_clients, is closed at once.
TEST(DaemonNmeaOut, AClientThatNeverReadsStallsNeitherTheOthersNorTheEstimator) {
  TempDir dir;
  const std::string url = lcmUrl(44);
  constexpr double kRate = 200.0;
  const std::string config = demoConfig(dir, url, 1.0, kRate,
                                        "rate_hz = 200\nsentences = [\"HDT\", \"THS\", \"HDG\"]\nclient_queue = 16\n"
                                        "max_clients = 2\n");
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  NmeaClient dead(false, 1024);
  NmeaClient reader;
  {
    NmeaClient third;  // beyond max_clients: closed at once, and reads nothing
    std::this_thread::sleep_for(200ms);
    EXPECT_TRUE(third.lines().empty());
  }
  const bool dropping = waitUntil(
      [&] {
        const auto s = lcm.status();
        return !s.empty() && counter(s.back().message, "nmea_out_sentences_dropped") > 0;
      },
      8s);
  ASSERT_TRUE(dropping) << test::readFile(dir.file("err"));
  const auto before = lcm.status().back();
  const std::size_t lines_before = reader.lines().size();
  const double t0 = steadyNow();
  std::this_thread::sleep_for(1500ms);
  const double t1 = steadyNow();
  const std::size_t lines_after = reader.lines().size();
  const auto after = lcm.status().back();
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(5s), 0) << test::readFile(dir.file("err"));
  lcm.stop();

  EXPECT_GT(counter(after.message, "nmea_out_sentences_dropped"),
            counter(before.message, "nmea_out_sentences_dropped"));
  EXPECT_EQ(counter(after.message, "nmea_out_clients"), 2);
  EXPECT_EQ(counter(after.message, "nmea_out_clients_refused"), 1);
  // The reader: three sentences a tick at 200 Hz, at least half of them (the machine is shared).
  const double reader_rate = static_cast<double>(lines_after - lines_before) / (t1 - t0);
  EXPECT_GE(reader_rate, 0.5 * 3 * kRate) << "sentences/s to the reading client";
  EXPECT_EQ(reader.badChecksums(), 0u);
  // The estimator: HEADING at its rate, at least half of it, in the last status period.
  EXPECT_GE(after.message.heading_rate_hz, 0.5 * kRate);
  std::size_t heading_in_window = 0;
  for (const auto& h : lcm.heading()) heading_in_window += h.receive_s >= t0 && h.receive_s <= t1;
  EXPECT_GE(static_cast<double>(heading_in_window), 0.5 * kRate * (t1 - t0));
}

}  // namespace
}  // namespace headingd::daemon
