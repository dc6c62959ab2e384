#include "headingd/gpsd/gpsd_client.hpp"

#include <algorithm>
#include <utility>
#include <variant>

#include <spdlog/spdlog.h>
#include <boost/asio/connect.hpp>
#include <boost/asio/error.hpp>
#include <boost/asio/write.hpp>

#include "headingd/live/clocks.hpp"
#include "headingd/live/link_error.hpp"

namespace headingd::gpsd {
namespace {

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
      epoch_idle_(
          io, config_.epoch_idle_s, [this] { return merger_.epochPending(); }, [this] { merger_.completeEpoch(); }),
      reconnect_(io, {config_.reopen_backoff_initial_s, config_.reopen_backoff_max_s}, [this] { connect(); }) {}

GpsdClient::~GpsdClient() { closeSocket(); }

void GpsdClient::start() { reconnect_.start(); }

void GpsdClient::stop() {
  if (!reconnect_.stop()) return;
  resolver_.cancel();
  closeSocket();
  endStream();
  counters_.state = GpsdState::kStopped;
}

std::string GpsdClient::where() const { return "gpsd at " + config_.host + ":" + std::to_string(config_.port); }

void GpsdClient::setError(GpsdState state, const std::string& message) {
  live::setLinkError(counters_.state, counters_.last_error, state, message, "gps");
}

void GpsdClient::connect() {
  ++counters_.connect_attempts;
  if (counters_.state != GpsdState::kWaiting) counters_.state = GpsdState::kConnecting;
  resolver_.async_resolve(
      config_.host, std::to_string(config_.port),
      [this, alive = reconnect_.guard()](const boost::system::error_code& ec,
                                         const boost::asio::ip::tcp::resolver::results_type& results) {
        if (alive.expired() || !reconnect_.running()) return;
        if (ec) {
          failConnect("cannot resolve " + config_.host + ": " + ec.message());
          return;
        }
        boost::asio::async_connect(
            socket_, results,
            [this, alive](const boost::system::error_code& cec, const boost::asio::ip::tcp::endpoint&) {
              if (alive.expired() || !reconnect_.running()) return;
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
  reconnect_.retryAfterFailure();
}

void GpsdClient::onConnected() {
  ++counters_.connects;
  counters_.state = GpsdState::kConnected;
  reconnect_.succeeded();
  spdlog::info("gps: connected to {}, watching", where());
  boost::asio::async_write(socket_, boost::asio::buffer(kWatchCommand.data(), kWatchCommand.size()),
                           [this, alive = reconnect_.guard()](const boost::system::error_code& ec, std::size_t) {
                             if (alive.expired() || ec == boost::asio::error::operation_aborted) return;
                             if (ec && socket_.is_open()) lose("sending WATCH failed: " + ec.message());
                           });
  startRead();
}

void GpsdClient::startRead() {
  socket_.async_read_some(boost::asio::buffer(buffer_), [this, alive = reconnect_.guard()](
                                                            const boost::system::error_code& ec, std::size_t n) {
    if (alive.expired() || ec == boost::asio::error::operation_aborted || !socket_.is_open()) return;
    if (n > 0) {
      const std::int64_t receive_ns = live::monotonicNs();
      framer_.feed(std::span<const std::uint8_t>(buffer_.data(), n),
                   [&](std::string_view line) { onLine(line, receive_ns); });
      const auto oversized = framer_.counters().oversized;
      if (oversized != counters_.lines.oversized) {
        counters_.lines.oversized = oversized;
        if (on_problem_) {
          on_problem_("oversized", "a line longer than " + std::to_string(config_.max_line_bytes) + " bytes, skipped");
        }
      }
      epoch_idle_.fed(receive_ns);
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
      // gpsd always sends the mode: a TPV without one does not say whether it is a fix at all.
      const bool usable = tpv->missing != "mode";
      if (on_problem_) {
        on_problem_("missing_fields",
                    "TPV without " + tpv->missing + (usable ? "" : " (not used)") + ": " + excerpt(line));
      }
      if (!usable) return;
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

void GpsdClient::lose(const std::string& why) {
  ++counters_.disconnects;
  closeSocket();
  endStream();
  setError(GpsdState::kWaiting, where() + ": " + why + "; reconnecting");
  reconnect_.retryAfterLoss();
}

void GpsdClient::endStream() {
  if (framer_.endOfStream() && on_problem_) on_problem_("cut", "the connection ended in the middle of a line");
  merger_.completeEpoch();
}

void GpsdClient::closeSocket() {
  epoch_idle_.cancel();
  boost::system::error_code ignored;
  socket_.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

GpsdCounters GpsdClient::counters() const {
  GpsdCounters c = counters_;
  c.lines = framer_.counters();
  c.epochs = merger_.epochs();
  c.late_reports = merger_.lateReports();
  return c;
}

}  // namespace headingd::gpsd
