// [nmea_out]: the table's checks (file:line and key in every error), which THS mode an
// estimate gets, and which sentences go out for it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "config_errors.hpp"
#include "daemon_test_support.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/daemon/config/config.hpp"
#include "headingd/daemon/outputs/nmea_out_sentences.hpp"
#include "headingd/nmea/framer.hpp"
#include "headingd/nmea/sentences.hpp"

namespace headingd::daemon {
namespace {

using test::TempDir;

class NmeaOutConfigTest : public test::ConfigErrors {
 protected:
  NmeaOutConfigTest() : ConfigErrors("nmea.toml") {}
  void expectError(const std::string& text, const std::string& expected) {
    const std::string e = errorOf(text);
    EXPECT_NE(e.find(expected), std::string::npos) << "got: " << e << "\nexpected: " << expected;
  }
};

TEST_F(NmeaOutConfigTest, DefaultsAreOffOnLoopbackAtTenHertz) {
  const DaemonConfig c = loadDaemonConfig(dir.write("ok.toml", "[daemon]\nrate_hz = 100\n"));
  EXPECT_FALSE(c.nmea_out.enabled);
  EXPECT_TRUE(c.nmea_out.tcp);
  EXPECT_FALSE(c.nmea_out.udp);
  EXPECT_EQ(c.nmea_out.tcp_address, "127.0.0.1");
  EXPECT_EQ(c.nmea_out.udp_address, "127.0.0.1");
  EXPECT_EQ(c.nmea_out.tcp_port, 10110);
  EXPECT_EQ(c.nmea_out.rate_hz, 10.0);
  EXPECT_EQ(c.nmea_out.talker, "HE");
  EXPECT_TRUE(c.nmea_out.hdt && c.nmea_out.ths && !c.nmea_out.hdg);
}

TEST(NmeaOutConfigShipped, HeadingdTomlStatesTheCompiledDefaults) {
  const NmeaOutConfig shipped = loadDaemonConfig(HEADINGD_CONFIG_DIR "/headingd.toml").nmea_out;
  const NmeaOutConfig d;
  EXPECT_EQ(shipped.enabled, d.enabled);
  EXPECT_EQ(shipped.tcp, d.tcp);
  EXPECT_EQ(shipped.tcp_address, d.tcp_address);
  EXPECT_EQ(shipped.tcp_port, d.tcp_port);
  EXPECT_EQ(shipped.udp, d.udp);
  EXPECT_EQ(shipped.udp_address, d.udp_address);
  EXPECT_EQ(shipped.udp_port, d.udp_port);
  EXPECT_EQ(shipped.rate_hz, d.rate_hz);
  EXPECT_EQ(shipped.talker, d.talker);
  EXPECT_EQ(shipped.hdt, d.hdt);
  EXPECT_EQ(shipped.ths, d.ths);
  EXPECT_EQ(shipped.hdg, d.hdg);
  EXPECT_EQ(shipped.max_clients, d.max_clients);
  EXPECT_EQ(shipped.client_queue, d.client_queue);
}

TEST_F(NmeaOutConfigTest, EveryKeyIsRead) {
  const DaemonConfig c = loadDaemonConfig(dir.write(
      "ok.toml",
      "[daemon]\nrate_hz = 50\n[nmea_out]\nenabled = true\ntcp = false\ntcp_address = \"::1\"\ntcp_port = 2000\n"
      "udp = true\nudp_address = \"192.168.1.255\"\nudp_port = 2001\nrate_hz = 50\ntalker = \"II\"\n"
      "sentences = [\"HDG\", \"HDT\"]\nmax_clients = 3\nclient_queue = 5\n"));
  const NmeaOutConfig& n = c.nmea_out;
  EXPECT_TRUE(n.enabled && !n.tcp && n.udp);
  EXPECT_EQ(n.tcp_address, "::1");
  EXPECT_EQ(n.tcp_port, 2000);
  EXPECT_EQ(n.udp_address, "192.168.1.255");
  EXPECT_EQ(n.udp_port, 2001);
  EXPECT_EQ(n.rate_hz, 50.0);
  EXPECT_EQ(n.talker, "II");
  EXPECT_TRUE(n.hdt && !n.ths && n.hdg);
  EXPECT_EQ(n.max_clients, 3u);
  EXPECT_EQ(n.client_queue, 5u);
}

TEST_F(NmeaOutConfigTest, BadValuesNameFileLineAndKey) {
  expectError("[nmea_out]\ntcp_port = 0\n", at(2) + "[nmea_out] tcp_port: 0 is out of range");
  expectError("[nmea_out]\nudp_port = 65536\n", at(2) + "[nmea_out] udp_port: 65536 is out of range");
  expectError("[nmea_out]\ntcp_address = \"localhost\"\n",
              at(2) + "[nmea_out] tcp_address: 'localhost' is not an IPv4 or IPv6 address");
  expectError("[nmea_out]\n\nudp_address = \"10.0.0.300\"\n",
              at(3) + "[nmea_out] udp_address: '10.0.0.300' is not an IPv4 or IPv6 address");
  expectError("[nmea_out]\nrate_hz = 0\n", at(2) + "[nmea_out] rate_hz: 0 is out of range");
  expectError("[nmea_out]\nrate_hz = -1\n", at(2) + "[nmea_out] rate_hz: -1 is out of range");
  expectError("[daemon]\nrate_hz = 50\n[nmea_out]\nrate_hz = 100\n",
              at(4) + "[nmea_out] rate_hz: 100.000000 Hz is above the estimator's [daemon] rate_hz (50.000000 Hz)");
  expectError("[nmea_out]\ntalker = \"he\"\n", at(2) + "[nmea_out] talker: 'he': expected two upper-case letters");
  expectError("[nmea_out]\ntalker = \"HEX\"\n", at(2) + "[nmea_out] talker: 'HEX': expected two upper-case letters");
  expectError("[nmea_out]\nsentences = [\"HDT\", \"RMC\"]\n",
              at(2) + "[nmea_out] sentences: 'RMC': expected \"HDT\", \"THS\" or \"HDG\"");
  expectError("[nmea_out]\nsentences = [\"HDT\", \"HDT\"]\n", at(2) + "[nmea_out] sentences: 'HDT' is listed twice");
  expectError("[nmea_out]\nsentences = []\n", at(2) + "[nmea_out] sentences: expected a non-empty array");
  expectError("[nmea_out]\nenabled = true\ntcp = false\nudp = false\n", "tcp and udp are both false");
  expectError("[nmea_out]\nport = 10110\n", at(2) + "[nmea_out] port");
  expectError("[nmea_out]\nmax_clients = 0\n", at(2) + "[nmea_out] max_clients: 0 is out of range");
}

core::HeadingOutput estimate(double true_deg, unsigned declination_sources, bool disturbed, bool mag_used) {
  core::HeadingOutput h;
  h.attitude.valid = true;
  h.attitude.mag_disturbed = disturbed;
  h.attitude.mag_used = mag_used;
  h.heading_true_rad = true_deg * core::kRadPerDeg;
  h.declination_rad = 3.0 * core::kRadPerDeg;
  h.mount_yaw_rad = 1.0 * core::kRadPerDeg;
  h.heading_mag_rad = h.heading_true_rad + h.mount_yaw_rad - h.declination_rad;
  h.declination_sources = declination_sources;
  return h;
}

TEST(NmeaOutSentences, ThsModeFollowsFreshnessDisturbanceAndSource) {
  using nmea::ThsMode;
  const auto good = estimate(10.0, core::kDeclWmm, false, true);
  EXPECT_EQ(thsMode(good, Validity::kFresh, false), ThsMode::kAutonomous);
  EXPECT_EQ(thsMode(good, Validity::kFresh, true), ThsMode::kSimulator);
  EXPECT_EQ(thsMode(estimate(10.0, core::kDeclWmm, true, false), Validity::kFresh, false), ThsMode::kEstimated);
  EXPECT_EQ(thsMode(estimate(10.0, core::kDeclGps, false, false), Validity::kFresh, false), ThsMode::kEstimated);
  EXPECT_EQ(thsMode(good, Validity::kStale, false), ThsMode::kInvalid);
  EXPECT_EQ(thsMode(good, Validity::kNone, false), ThsMode::kInvalid);
  EXPECT_EQ(thsMode(estimate(10.0, core::kDeclNone, false, true), Validity::kFresh, false), ThsMode::kInvalid);
  EXPECT_EQ(thsMode(estimate(10.0, core::kDeclNone, false, true), Validity::kFresh, true), ThsMode::kInvalid);
}

std::string textOf(const NmeaOutConfig& c, const core::HeadingOutput& h, Validity v, bool from_files) {
  NmeaOutBatch batch;
  formatNmeaOut(c, h, v, from_files, batch);
  return std::string(batch.view());
}

TEST(NmeaOutSentences, WhatGoesOutForEachState) {
  NmeaOutConfig c;
  c.hdg = true;
  const auto good = estimate(123.44, core::kDeclWmm, false, true);
  const std::string fresh = textOf(c, good, Validity::kFresh, false);
  EXPECT_EQ(fresh.substr(0, 17), "$HEHDT,123.4,T*2B");
  EXPECT_NE(fresh.find("$HETHS,123.4,A*"), std::string::npos);
  // Magnetic heading of the body (123.44 - 3.0), deviation 0, variation 3.0 E.
  EXPECT_NE(fresh.find("$HEHDG,120.4,0.0,E,3.0,E*"), std::string::npos);
  // Stale: no HDT, no HDG, THS with the last heading and V.
  EXPECT_EQ(textOf(c, good, Validity::kStale, false).substr(0, 17), "$HETHS,123.4,V*3E");
  EXPECT_EQ(textOf(c, good, Validity::kStale, false).find("HDT"), std::string::npos);
  // No estimate: an empty THS.
  EXPECT_EQ(textOf(c, good, Validity::kNone, false).substr(0, 12), "$HETHS,,V*14");
  // No declination: no true heading; HDG still has the magnetic heading, without variation.
  const std::string magnetic = textOf(c, estimate(123.44, core::kDeclNone, false, true), Validity::kFresh, false);
  EXPECT_EQ(magnetic.substr(0, 12), "$HETHS,,V*14");
  EXPECT_NE(magnetic.find("$HEHDG,120.4,0.0,E,,*"), std::string::npos);
  // Only the sentences asked for, talker as configured.
  c.hdt = false;
  c.hdg = false;
  c.talker = "II";
  EXPECT_EQ(textOf(c, good, Validity::kFresh, true).substr(0, 15), "$IITHS,123.4,S*");
}

TEST(NmeaOutSentences, EveryBatchFramesIntoGoodSentences) {
  NmeaOutConfig c;
  c.hdg = true;
  nmea::Framer framer;
  std::size_t lines = 0, batches_sentences = 0;
  for (double deg = -400.0; deg < 400.0; deg += 0.77) {
    NmeaOutBatch batch;
    formatNmeaOut(c, estimate(deg, core::kDeclGps, deg > 0, true), Validity::kFresh, false, batch);
    batches_sentences += batch.sentences;
    for (const char ch : batch.view()) {
      if (framer.push(static_cast<std::uint8_t>(ch))) ++lines;
    }
  }
  EXPECT_EQ(lines, batches_sentences);
  EXPECT_EQ(framer.counters().bad_checksum + framer.counters().garbage_bytes + framer.counters().truncated, 0u);
}

}  // namespace
}  // namespace headingd::daemon
