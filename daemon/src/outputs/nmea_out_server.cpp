#include "headingd/daemon/outputs/nmea_out_server.hpp"

#include <spdlog/spdlog.h>
#include <algorithm>
#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>
#include <boost/lockfree/spsc_queue.hpp>
#include <chrono>
#include <deque>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "headingd/daemon/system/repeat_limiter.hpp"
#include "headingd/live/clocks.hpp"

namespace headingd::daemon {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using asio::ip::udp;

// Sends the estimator can hand over while the network thread is busy: seconds at any rate.
constexpr std::size_t kHandoffCapacity = 256;
// How often the network thread looks into the handoff ring: twice per send, at most every
// 10 ms (a sentence leaves at most 10 ms after its tick), at least every 1 ms. Polling, as the
// recorder's writer does, rather than a wake-up from the estimator: the estimator thread then
// makes no system call and wakes no thread (docs/real-time.md, "NMEA out and the estimator thread", has
// what was measured both ways).
std::chrono::nanoseconds pollInterval(double rate_hz) {
  const double s = std::clamp(0.5 / rate_hz, 0.001, 0.010);
  return std::chrono::nanoseconds(static_cast<std::int64_t>(s * 1e9));
}
// Per client, in the kernel: a cap instead of autotuning, so a client that does not read
// ties up a bounded amount of memory and its queue (client_queue) fills in bounded time.
constexpr int kSocketSendBuffer = 8 * 1024;  // the kernel doubles it: 16 KiB, 15 s of sends at 10 Hz

// One send, shared by every client queue it is in.
struct Chunk {
  std::string bytes;
  std::size_t sentences = 0;
};

std::string endpointText(const tcp::socket& s) {
  boost::system::error_code ec;
  const tcp::endpoint e = s.remote_endpoint(ec);
  if (ec) return "(unknown peer)";
  return e.address().to_string() + ":" + std::to_string(e.port());
}

}  // namespace

class NmeaOutServer::Impl {
 public:
  Impl(const NmeaOutConfig& config, int burst, double interval_s)
      : config_(config),
        poll_(io_),
        poll_interval_(pollInterval(config.rate_hz)),
        connect_log_(burst, interval_s),
        garbage_log_(burst, interval_s),
        error_log_(burst, interval_s) {}

  ~Impl() { stop(); }

  void start() {
    if (config_.tcp) openTcp();
    if (config_.udp) openUdp();
    poll_.expires_after(poll_interval_);
    waitForPoll();
    if (acceptor_) accept();
    thread_ = std::thread([this] { io_.run(); });
  }

  void stop() {
    if (thread_.joinable()) {
      io_.stop();
      thread_.join();
    }
    clients_.clear();
    boost::system::error_code ec;
    if (acceptor_) acceptor_->close(ec);
    if (udp_) udp_->close(ec);
  }

  bool offer(const NmeaOutBatch& batch) {
    if (batch.sentences == 0) return true;
    if (handoff_.push(batch)) return true;
    dropped_.fetch_add(batch.sentences, std::memory_order_relaxed);
    return false;
  }

  NmeaOutCounters counters() const {
    NmeaOutCounters c;
    c.clients = clients_now_.load(std::memory_order_relaxed);
    c.connections = connections_.load(std::memory_order_relaxed);
    c.clients_refused = refused_.load(std::memory_order_relaxed);
    c.sentences_sent = sent_.load(std::memory_order_relaxed);
    c.sentences_dropped = dropped_.load(std::memory_order_relaxed);
    c.client_errors = errors_.load(std::memory_order_relaxed);
    c.bytes_received = received_.load(std::memory_order_relaxed);
    return c;
  }

 private:
  struct Client : std::enable_shared_from_this<Client> {
    explicit Client(tcp::socket s) : socket(std::move(s)), peer(endpointText(socket)) {}
    tcp::socket socket;
    std::string peer;
    std::deque<std::shared_ptr<const Chunk>> queue;
    bool writing = false;
    bool closed = false;
    std::array<char, 512> inbox{};
  };

  void openTcp() {
    const tcp::endpoint at(asio::ip::make_address(config_.tcp_address), config_.tcp_port);
    acceptor_.emplace(io_);
    boost::system::error_code ec;
    acceptor_->open(at.protocol(), ec);
    if (!ec) acceptor_->set_option(asio::socket_base::reuse_address(true), ec);
    if (!ec) acceptor_->bind(at, ec);
    if (!ec) acceptor_->listen(asio::socket_base::max_listen_connections, ec);
    if (ec) {
      throw std::runtime_error("[nmea_out] tcp_address, tcp_port: cannot listen on " + config_.tcp_address + " port " +
                               std::to_string(config_.tcp_port) + ": " + ec.message());
    }
    spdlog::info("nmea_out: serving {} to TCP clients on {} port {}", sentenceNames(), config_.tcp_address,
                 config_.tcp_port);
  }

  void openUdp() {
    udp_target_ = udp::endpoint(asio::ip::make_address(config_.udp_address), config_.udp_port);
    udp_.emplace(io_);
    boost::system::error_code ec;
    udp_->open(udp_target_.protocol(), ec);
    if (!ec) udp_->set_option(asio::socket_base::broadcast(true), ec);  // a broadcast address is allowed
    if (!ec) udp_->non_blocking(true, ec);
    if (ec) throw std::runtime_error("[nmea_out] udp_address: cannot open a UDP socket: " + ec.message());
    spdlog::info("nmea_out: sending {} as UDP datagrams to {} port {}", sentenceNames(), config_.udp_address,
                 config_.udp_port);
  }

  std::string sentenceNames() const {
    std::string s;
    const std::pair<bool, const char*> kinds[] = {{config_.hdt, "HDT"}, {config_.ths, "THS"}, {config_.hdg, "HDG"}};
    for (const auto& [on, name] : kinds) {
      if (on) s += (s.empty() ? "" : ", ") + config_.talker + name;
    }
    return s + " at " + fmt::format("{:g}", config_.rate_hz) + " Hz";
  }

  // On absolute deadlines: a late wake-up does not shift the later ones.
  void waitForPoll() {
    poll_.async_wait([this](const boost::system::error_code& ec) {
      if (ec) return;  // cancelled: stopping
      distribute();
      poll_.expires_at(poll_.expiry() + poll_interval_);
      waitForPoll();
    });
  }

  void distribute() {
    NmeaOutBatch batch;
    while (handoff_.pop(batch)) {
      if (udp_) sendDatagrams(batch);
      if (clients_.empty()) continue;
      auto chunk = std::make_shared<Chunk>();
      chunk->bytes.assign(batch.view());
      chunk->sentences = batch.sentences;
      for (const auto& c : clients_) {
        if (c->queue.size() >= config_.client_queue) {
          dropped_.fetch_add(chunk->sentences, std::memory_order_relaxed);
          continue;
        }
        c->queue.push_back(chunk);
        if (!c->writing) write(c);
      }
    }
  }

  // One datagram a sentence: what OpenCPN's and gpsd's UDP inputs expect.
  void sendDatagrams(const NmeaOutBatch& batch) {
    std::string_view rest = batch.view();
    while (!rest.empty()) {
      const std::size_t end = rest.find('\n');
      const std::string_view sentence = rest.substr(0, end == std::string_view::npos ? rest.size() : end + 1);
      rest.remove_prefix(sentence.size());
      boost::system::error_code ec;
      udp_->send_to(asio::buffer(sentence.data(), sentence.size()), udp_target_, 0, ec);
      if (!ec) {
        sent_.fetch_add(1, std::memory_order_relaxed);
        continue;
      }
      errors_.fetch_add(1, std::memory_order_relaxed);
      logLimited(error_log_, spdlog::level::warn, "nmea_out: UDP datagram to {} port {} not sent: {}",
                 config_.udp_address, config_.udp_port, ec.message());
    }
  }

  void accept() {
    acceptor_->async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
      if (ec == asio::error::operation_aborted) return;
      if (ec) {
        logLimited(error_log_, spdlog::level::warn, "nmea_out: accept failed: {}", ec.message());
      } else {
        admit(std::move(socket));
      }
      accept();
    });
  }

  void admit(tcp::socket socket) {
    if (clients_.size() >= config_.max_clients) {
      refused_.fetch_add(1, std::memory_order_relaxed);
      logLimited(connect_log_, spdlog::level::warn, "nmea_out: client {} refused: max_clients ({}) are connected",
                 endpointText(socket), config_.max_clients);
      boost::system::error_code ec;
      socket.close(ec);
      return;
    }
    boost::system::error_code ec;
    socket.set_option(tcp::no_delay(true), ec);  // a sentence goes out when it is there
    socket.set_option(asio::socket_base::send_buffer_size(kSocketSendBuffer), ec);
    auto client = std::make_shared<Client>(std::move(socket));
    clients_.push_back(client);
    connections_.fetch_add(1, std::memory_order_relaxed);
    clients_now_.store(clients_.size(), std::memory_order_relaxed);
    logLimited(connect_log_, spdlog::level::info, "nmea_out: client {} connected ({} now)", client->peer,
               clients_.size());
    read(client);
  }

  // Clients have nothing to say to us: whatever comes is counted and dropped. The read also
  // notices a client that closed the connection.
  void read(const std::shared_ptr<Client>& c) {
    c->socket.async_read_some(asio::buffer(c->inbox), [this, c](const boost::system::error_code& ec, std::size_t n) {
      if (c->closed) return;
      if (ec == asio::error::eof) {
        close(c, nullptr);
        return;
      }
      if (ec) {
        close(c, &ec);
        return;
      }
      received_.fetch_add(n, std::memory_order_relaxed);
      logLimited(garbage_log_, spdlog::level::warn, "nmea_out: client {} sent {} bytes; ignored (headingd only sends)",
                 c->peer, n);
      read(c);
    });
  }

  void write(const std::shared_ptr<Client>& c) {
    c->writing = true;
    const std::shared_ptr<const Chunk> chunk = c->queue.front();
    asio::async_write(c->socket, asio::buffer(chunk->bytes),
                      [this, c, chunk](const boost::system::error_code& ec, std::size_t) {
                        c->writing = false;
                        if (c->closed) return;
                        if (ec) {
                          close(c, &ec);
                          return;
                        }
                        sent_.fetch_add(chunk->sentences, std::memory_order_relaxed);
                        c->queue.pop_front();
                        if (!c->queue.empty()) write(c);
                      });
  }

  // `error`: why, or null for a client that closed the connection itself.
  void close(const std::shared_ptr<Client>& c, const boost::system::error_code* error) {
    c->closed = true;
    boost::system::error_code ignored;
    c->socket.close(ignored);
    std::erase(clients_, c);
    clients_now_.store(clients_.size(), std::memory_order_relaxed);
    if (error != nullptr) {
      errors_.fetch_add(1, std::memory_order_relaxed);
      logLimited(error_log_, spdlog::level::warn, "nmea_out: client {} dropped: {} ({} now)", c->peer, error->message(),
                 clients_.size());
    } else {
      logLimited(connect_log_, spdlog::level::info, "nmea_out: client {} disconnected ({} now)", c->peer,
                 clients_.size());
    }
  }

  template <class... Args>
  void logLimited(RepeatLimiter& limiter, spdlog::level::level_enum level, fmt::format_string<Args...> format,
                  Args&&... args) {
    std::uint64_t suppressed = 0;
    if (!limiter.allow(live::monotonicNs(), &suppressed)) return;
    std::string text = fmt::format(format, std::forward<Args>(args)...);
    if (suppressed != 0) text += fmt::format(" ({} such messages suppressed)", suppressed);
    spdlog::log(level, "{}", text);
  }

  const NmeaOutConfig config_;
  asio::io_context io_;
  asio::steady_timer poll_;
  const std::chrono::nanoseconds poll_interval_;
  std::optional<tcp::acceptor> acceptor_;
  std::optional<udp::socket> udp_;
  udp::endpoint udp_target_;
  std::vector<std::shared_ptr<Client>> clients_;  // network thread only
  boost::lockfree::spsc_queue<NmeaOutBatch, boost::lockfree::capacity<kHandoffCapacity>> handoff_;
  std::thread thread_;
  RepeatLimiter connect_log_, garbage_log_, error_log_;
  std::atomic<std::uint64_t> clients_now_{0}, connections_{0}, refused_{0}, sent_{0}, dropped_{0}, errors_{0},
      received_{0};
};

NmeaOutServer::NmeaOutServer(const NmeaOutConfig& config, int repeat_burst, double repeat_interval_s)
    : impl_(std::make_unique<Impl>(config, repeat_burst, repeat_interval_s)) {}
NmeaOutServer::~NmeaOutServer() = default;
void NmeaOutServer::start() { impl_->start(); }
void NmeaOutServer::stop() { impl_->stop(); }
bool NmeaOutServer::offer(const NmeaOutBatch& batch) { return impl_->offer(batch); }
NmeaOutCounters NmeaOutServer::counters() const { return impl_->counters(); }

}  // namespace headingd::daemon
