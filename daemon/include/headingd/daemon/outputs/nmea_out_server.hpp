#pragma once
// [nmea_out]'s network side: a TCP server (any number of clients up to max_clients) and/or
// UDP datagrams, on a Boost.Asio thread of its own. The estimator thread hands each send over
// with offer(): a copy into a lock-free single-producer ring, nothing more (no system call, no
// wake-up), so it never waits for the network and never allocates; the network thread looks
// into the ring on a timer (twice per send, every 1 to 10 ms). The network thread gives every client its
// own bounded queue; a client that reads too slowly (or not at all) gets its newest sends
// dropped and counted, and never holds up the others. Whatever a client sends is read,
// discarded and counted (headingd only speaks). daemon/README.md, "NMEA heading out".
#include <atomic>
#include <cstdint>
#include <memory>
#include <string_view>
#include <thread>

#include "headingd/daemon/outputs/nmea_out_config.hpp"
#include "headingd/daemon/outputs/nmea_out_sentences.hpp"

namespace headingd::daemon {

// For STATUS (cumulative but `clients`).
struct NmeaOutCounters {
  std::uint64_t clients = 0;            // TCP clients connected now
  std::uint64_t connections = 0;        // TCP connections accepted
  std::uint64_t clients_refused = 0;    // closed at once: max_clients were connected
  std::uint64_t sentences_sent = 0;     // written to a TCP client or sent as a datagram (per client)
  std::uint64_t sentences_dropped = 0;  // not sent to a client: its queue was full, or the handoff ring was
  std::uint64_t client_errors = 0;      // connections ended by an error (reset, broken pipe), failed datagrams
  std::uint64_t bytes_received = 0;     // sent to us by clients: read and discarded
};

// Calls fn(name, value) for each counter, in STATUS order ("nmea_out_clients", ...).
template <class Fn>
void forEachNmeaOutCounter(const NmeaOutCounters& c, Fn&& fn) {
  fn("nmea_out_clients", c.clients);
  fn("nmea_out_connections", c.connections);
  fn("nmea_out_clients_refused", c.clients_refused);
  fn("nmea_out_sentences_sent", c.sentences_sent);
  fn("nmea_out_sentences_dropped", c.sentences_dropped);
  fn("nmea_out_client_errors", c.client_errors);
  fn("nmea_out_bytes_received", c.bytes_received);
}

class NmeaOutServer {
 public:
  // Opens nothing (the configuration is checked by parseNmeaOutTable).
  NmeaOutServer(const NmeaOutConfig& config, int repeat_burst, double repeat_interval_s);
  ~NmeaOutServer();
  NmeaOutServer(const NmeaOutServer&) = delete;
  NmeaOutServer& operator=(const NmeaOutServer&) = delete;

  // Binds and listens (TCP), opens the UDP socket, starts the thread. Throws std::runtime_error
  // naming the key and address when it cannot (the port is taken, the address is not here).
  void start();
  // Closes every socket and joins the thread. Idempotent.
  void stop();

  // Estimator thread only: never blocks, never allocates, no system call. False when the
  // handoff ring was full (the network thread is stuck; counted as dropped).
  bool offer(const NmeaOutBatch& batch);

  // Any thread; relaxed reads of the counters.
  NmeaOutCounters counters() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace headingd::daemon
