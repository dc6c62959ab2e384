#include "headingd/gpsd/gpsd_client.hpp"

#include <time.h>

#include <algorithm>
#include <utility>
#include <variant>

#include <spdlog/spdlog.h>
#include <boost/asio/connect.hpp>
#include <boost/asio/error.hpp>
#include <boost/asio/write.hpp>

namespace headingd::gpsd {
namespace {

std::int64_t monotonicNowNs() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::chrono::nanoseconds toNs(double seconds) {
  return std::chrono::nanoseconds(static_cast<std::int64_t>(seconds * 1e9));
}

// A line in a log message: at most 120 characters of it.
std::string excerpt(std::string_view line) {
  constexpr std::size_t kMax = 120;
  std::string s(line.substr(0, kMax));
  if (line.size() > kMax) s += "...";
  return s;
}

}  // namespace

const char* gpsdStateName(GpsdState s) {
  switch (s) {
    case GpsdState::kStopped: return "stopped";
    case GpsdState::kConnecting: return "connecting";
    case GpsdState::kConnected: return "connected";
    case GpsdState::kWaiting: return "waiting";
  }
  return "?";
}

GpsdClient::GpsdClient(boost::asio::io_context& io, GpsdConfig config, EpochHandler on_epoch, ProblemHandler on_problem)
    : config_(std::move(config)),
      on_problem_(std::move(on_problem)),
      merger_(std::move(on_epoch)),
      framer_(config_.max_line_bytes),
      resolver_(io),
      socket_(io),
      reconnect_timer_(io),
      idle_timer_(io),
      backoff_(config_.reopen_backoff_initial_s, config_.reopen_backoff_max_s) {}

GpsdClient::~GpsdClient() {
  alive_.reset();
  closeSocket();
}

void GpsdClient::start() {
  if (running_) return;
  running_ = true;
  backoff_.reset();
  scheduleConnect(std::chrono::nanoseconds(0));
}

void GpsdClient::stop() {
  if (!running_) return;
  running_ = false;
  reconnect_timer_.cancel();
  resolver_.cancel();
  closeSocket();
  endStream();
  counters_.state = GpsdState::kStopped;
}

GpsdCounters GpsdClient::counters() const {
  GpsdCounters c = counters_;
  c.lines = framer_.counters();
  c.epochs = merger_.epochs();
  c.late_reports = merger_.lateReports();
  return c;
}

std::string GpsdClient::where() const { return "gpsd at " + config_.host + ":" + std::to_string(config_.port); }

void GpsdClient::setError(GpsdState state, const std::string& message) {
  // Logged when it changes, so a gpsd that stays away is reported once, not per retry.
  if (message != counters_.last_error || state != counters_.state) spdlog::warn("gps: {}", message);
  counters_.state = state;
  counters_.last_error = message;
}

void GpsdClient::scheduleConnect(std::chrono::nanoseconds delay) {
  reconnect_timer_.expires_after(delay);
  reconnect_timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired() || ec || !running_) return;
    connect();
  });
}

void GpsdClient::connect() {
  ++counters_.connect_attempts;
  if (counters_.state != GpsdState::kWaiting) counters_.state = GpsdState::kConnecting;
  resolver_.async_resolve(
      config_.host, std::to_string(config_.port),
      [this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec,
                                                 const boost::asio::ip::tcp::resolver::results_type& results) {
        if (alive.expired() || !running_) return;
        if (ec) {
          failConnect("cannot resolve " + config_.host + ": " + ec.message());
          return;
        }
        boost::asio::async_connect(
            socket_, results,
            [this, alive](const boost::system::error_code& cec, const boost::asio::ip::tcp::endpoint&) {
              if (alive.expired() || !running_) return;
              if (cec) {
                closeSocket();
                failConnect(where() + ": " + cec.message());
                return;
              }
              onConnected();
            });
      });
}

void GpsdClient::failConnect(const std::string& why) {
  ++counters_.connect_failures;
  setError(GpsdState::kWaiting, why + "; retrying");
  scheduleConnect(backoff_.afterFailure());
}

void GpsdClient::onConnected() {
  ++counters_.connects;
  counters_.state = GpsdState::kConnected;
  backoff_.reset();
  spdlog::info("gps: connected to {}, watching", where());
  boost::asio::async_write(
      socket_, boost::asio::buffer(kWatchCommand.data(), kWatchCommand.size()),
      [this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec, std::size_t) {
        if (alive.expired() || ec == boost::asio::error::operation_aborted) return;
        if (ec && socket_.is_open()) lose("sending WATCH failed: " + ec.message());
      });
  startRead();
}

void GpsdClient::startRead() {
  socket_.async_read_some(boost::asio::buffer(buffer_), [this, alive = std::weak_ptr<int>(alive_)](
                                                            const boost::system::error_code& ec, std::size_t n) {
    if (alive.expired() || ec == boost::asio::error::operation_aborted || !socket_.is_open()) return;
    if (n > 0) {
      last_receive_ns_ = monotonicNowNs();
      framer_.feed(std::span<const std::uint8_t>(buffer_.data(), n),
                   [&](std::string_view line) { onLine(line, last_receive_ns_); });
      const auto oversized = framer_.counters().oversized;
      if (oversized != counters_.lines.oversized) {
        counters_.lines.oversized = oversized;
        if (on_problem_) {
          on_problem_("oversized", "a line longer than " + std::to_string(config_.max_line_bytes) + " bytes, skipped");
        }
      }
      armIdleTimer();
    }
    if (ec) {
      lose(ec == boost::asio::error::eof ? "gpsd closed the connection" : "read failed: " + ec.message());
      return;
    }
    startRead();
  });
}

void GpsdClient::onLine(std::string_view line, std::int64_t receive_ns) {
  if (line.empty()) return;
  const GpsdReport report = parseGpsdReport(line);
  if (const auto* tpv = std::get_if<TpvReport>(&report)) {
    ++counters_.tpv_reports;
    if (!tpv->missing.empty()) {
      ++counters_.missing_fields;
      if (on_problem_) on_problem_("missing_fields", "TPV without " + tpv->missing + ": " + excerpt(line));
    }
    merger_.addTpv(tpv->fix, receive_ns);
  } else if (const auto* sky = std::get_if<SkyReport>(&report)) {
    ++counters_.sky_reports;
    merger_.addSky(*sky);
  } else if (const auto* bad = std::get_if<MalformedReport>(&report)) {
    ++counters_.malformed;
    if (on_problem_) on_problem_("malformed", bad->why + ": " + excerpt(line));
  } else {
    ++counters_.other_reports;
  }
}

void GpsdClient::armIdleTimer() {
  if (config_.epoch_idle_s <= 0.0 || idle_timer_armed_ || !merger_.epochPending()) return;
  idle_timer_armed_ = true;
  idle_timer_.expires_after(toNs(config_.epoch_idle_s));
  idle_timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired()) return;
    idle_timer_armed_ = false;
    if (!ec) onIdleTimer();
  });
}

void GpsdClient::onIdleTimer() {
  // One timer per quiet period: reports since it was armed push the deadline.
  const auto quiet_for = std::chrono::nanoseconds(monotonicNowNs() - last_receive_ns_);
  const auto idle = toNs(config_.epoch_idle_s);
  if (quiet_for >= idle) {
    merger_.completeEpoch();
    return;
  }
  idle_timer_armed_ = true;
  idle_timer_.expires_after(idle - quiet_for);
  idle_timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired()) return;
    idle_timer_armed_ = false;
    if (!ec) onIdleTimer();
  });
}

void GpsdClient::lose(const std::string& why) {
  ++counters_.disconnects;
  closeSocket();
  endStream();
  setError(GpsdState::kWaiting, where() + ": " + why + "; reconnecting");
  scheduleConnect(backoff_.reset());
}

void GpsdClient::endStream() {
  if (framer_.endOfStream() && on_problem_) on_problem_("cut", "the connection ended in the middle of a line");
  merger_.completeEpoch();
}

void GpsdClient::closeSocket() {
  idle_timer_.cancel();
  boost::system::error_code ignored;
  socket_.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

}  // namespace headingd::gpsd
