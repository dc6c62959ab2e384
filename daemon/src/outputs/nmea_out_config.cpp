#include "headingd/daemon/outputs/nmea_out_config.hpp"

#include <boost/asio/ip/address.hpp>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/nmea/heading_sentences.hpp"

namespace headingd::daemon {
namespace {

using core::TomlTableReader;

void checkAddress(TomlTableReader& r, std::string_view key, const std::string& address) {
  boost::system::error_code ec;
  boost::asio::ip::make_address(address, ec);
  if (ec) r.fail(key, "'" + address + "' is not an IPv4 or IPv6 address (e.g. \"127.0.0.1\", \"0.0.0.0\", \"::1\")");
}

// sentences = ["HDT", "THS", "HDG"]: any of the three, each once, at least one.
void readSentences(TomlTableReader& r, NmeaOutConfig& c) {
  const toml::node* node = r.node("sentences");
  if (node == nullptr) return;
  const toml::array* list = node->as_array();
  if (list == nullptr || list->empty()) r.fail("sentences", "expected a non-empty array of \"HDT\", \"THS\", \"HDG\"");
  c.hdt = c.ths = c.hdg = false;
  for (const toml::node& item : *list) {
    const std::optional<std::string> name = item.value<std::string>();
    bool* flag = nullptr;
    if (name == "HDT") flag = &c.hdt;
    if (name == "THS") flag = &c.ths;
    if (name == "HDG") flag = &c.hdg;
    if (flag == nullptr) {
      r.fail("sentences", "'" + name.value_or("(not a string)") + "': expected \"HDT\", \"THS\" or \"HDG\"");
    }
    if (*flag) r.fail("sentences", "'" + *name + "' is listed twice");
    *flag = true;
  }
}

}  // namespace

NmeaOutConfig parseNmeaOutTable(const toml::table* table, const std::string& source, double daemon_rate_hz) {
  NmeaOutConfig c;
  TomlTableReader r(table, source, "nmea_out");
  c.enabled = r.boolean("enabled", c.enabled);
  c.tcp = r.boolean("tcp", c.tcp);
  c.tcp_address = r.string("tcp_address", c.tcp_address);
  checkAddress(r, "tcp_address", c.tcp_address);
  c.tcp_port = static_cast<std::uint16_t>(r.integer("tcp_port", c.tcp_port, 1, 65535));
  c.udp = r.boolean("udp", c.udp);
  c.udp_address = r.string("udp_address", c.udp_address);
  checkAddress(r, "udp_address", c.udp_address);
  c.udp_port = static_cast<std::uint16_t>(r.integer("udp_port", c.udp_port, 1, 65535));
  c.rate_hz = r.number("rate_hz", c.rate_hz, 0.01, 2000.0, "Hz");
  if (c.rate_hz > daemon_rate_hz) {
    r.fail("rate_hz", std::to_string(c.rate_hz) + " Hz is above the estimator's [daemon] rate_hz (" +
                          std::to_string(daemon_rate_hz) + " Hz); expected at most that");
  }
  c.talker = r.string("talker", c.talker);
  if (!nmea::isTalkerId(c.talker)) r.fail("talker", "'" + c.talker + "': expected two upper-case letters, e.g. \"HE\"");
  readSentences(r, c);
  c.max_clients = static_cast<std::size_t>(r.integer("max_clients", static_cast<std::int64_t>(c.max_clients), 1, 1024));
  c.client_queue =
      static_cast<std::size_t>(r.integer("client_queue", static_cast<std::int64_t>(c.client_queue), 1, 65536));
  r.rejectUnknownKeys();
  if (c.enabled && !c.tcp && !c.udp) r.failBetween("tcp", "udp", "tcp and udp are both false: nothing to send on");
  return c;
}

}  // namespace headingd::daemon
