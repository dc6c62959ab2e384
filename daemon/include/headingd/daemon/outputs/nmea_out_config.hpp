#pragma once
// The [nmea_out] table: the heading as NMEA 0183 sentences over TCP and/or UDP, for gpsd,
// chart plotters (OpenCPN) and anything else that reads HDT/THS/HDG. Off by default, on the
// loopback interface by default. Every key is documented in config/headingd.toml.
#include <toml++/toml.h>
#include <cstddef>
#include <cstdint>
#include <string>

namespace headingd::daemon {

struct NmeaOutConfig {
  bool enabled = false;
  bool tcp = true;  // a TCP server, any number of clients (up to max_clients)
  std::string tcp_address = "127.0.0.1";
  std::uint16_t tcp_port = 10110;  // IANA's nmea-0183 port
  bool udp = false;                // datagrams to udp_address:udp_port, one sentence each
  std::string udp_address = "127.0.0.1";
  std::uint16_t udp_port = 10110;
  double rate_hz = 10.0;                     // at most [daemon] rate_hz; sent every round(rate/this) ticks
  std::string talker = "HE";                 // two upper-case letters
  bool hdt = true, ths = true, hdg = false;  // which sentences (key `sentences`)
  std::size_t max_clients = 16;              // TCP clients beyond this are closed at once (counted)
  std::size_t client_queue = 64;             // sends held per client before new ones are dropped for it
};

// Parses [nmea_out] (null: absent, off). `daemon_rate_hz` bounds rate_hz. Unknown keys, wrong
// types, a port out of 1..65535, an address that is not an IPv4/IPv6 address, a rate <= 0 or
// above the estimator's, a talker that is not two upper-case letters, an unknown sentence:
// core::ConfigError naming file:line and the key.
NmeaOutConfig parseNmeaOutTable(const toml::table* table, const std::string& source, double daemon_rate_hz);

}  // namespace headingd::daemon
