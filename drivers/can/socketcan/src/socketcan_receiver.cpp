#include "headingd/can/socketcan_receiver.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "headingd/live/clocks.hpp"

namespace headingd::can {
namespace {

std::string errnoText(int err) { return std::strerror(err); }

}  // namespace

const char* linkStateName(LinkState s) {
  switch (s) {
    case LinkState::waiting: return "waiting";
    case LinkState::down: return "down";
    case LinkState::up: return "up";
  }
  return "?";
}

ReceiverSettings receiverSettingsFrom(const CanConfig& config, const ImuFrameCodec& codec) {
  ReceiverSettings s;
  s.interface = config.interface;
  s.filters = codec.kernelFilters();
  s.reconnect_initial = live::secondsToNs(config.reconnect_initial_s);
  s.reconnect_max = live::secondsToNs(config.reconnect_max_s);
  s.receive_buffer_bytes = config.receive_buffer_bytes;
  return s;
}

SocketCanReceiver::SocketCanReceiver(boost::asio::io_context& io, ReceiverSettings settings, FrameHandler on_frame)
    : settings_(std::move(settings)),
      on_frame_(std::move(on_frame)),
      socket_(io),
      reopen_(io, live::ReconnectDelay(settings_.reconnect_initial, settings_.reconnect_max), [this] { tryOpen(); }) {}

SocketCanReceiver::~SocketCanReceiver() { stop(); }

void SocketCanReceiver::start() { reopen_.start(); }

void SocketCanReceiver::stop() {
  reopen_.stop();
  boost::system::error_code ignored;
  socket_.close(ignored);
}

ReceiverStatus SocketCanReceiver::status() const {
  std::lock_guard lock(mutex_);
  ReceiverStatus s = rare_;
  s.state = state_.load(std::memory_order_relaxed);
  s.frames = frames_.load(std::memory_order_relaxed);
  s.kernel_drops = kernel_drops_.load(std::memory_order_relaxed);
  return s;
}

void SocketCanReceiver::setError(LinkState next, int err, const std::string& what) {
  std::lock_guard lock(mutex_);
  rare_.last_errno = err;
  rare_.last_error = what;
  state_.store(next, std::memory_order_relaxed);
}

void SocketCanReceiver::lose(LinkState next, int err, const std::string& what) {
  boost::system::error_code ignored;
  socket_.close(ignored);
  {
    std::lock_guard lock(mutex_);
    if (state_.load(std::memory_order_relaxed) == LinkState::up) ++rare_.times_lost;
  }
  setError(next, err, what);
  scheduleRetry();
}

void SocketCanReceiver::scheduleRetry() {
  if (!reopen_.running()) return;
  const auto delay = reopen_.retryAfterFailure();  // bounded exponential back-off
  std::lock_guard lock(mutex_);
  rare_.next_retry_delay_ns = delay.count();
}

void SocketCanReceiver::tryOpen() {
  if (!reopen_.running()) return;
  {
    std::lock_guard lock(mutex_);
    ++rare_.open_attempts;
  }
  const std::string& name = settings_.interface;
  auto fail = [&](LinkState next, int err, const std::string& what, int fd) {
    if (fd >= 0) ::close(fd);
    {
      std::lock_guard lock(mutex_);
      ++rare_.open_failures;
    }
    setError(next, err, what);
    scheduleRetry();
  };

  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    const int err = errno;
    const bool no_can = err == EAFNOSUPPORT || err == EPROTONOSUPPORT;
    fail(LinkState::waiting, err,
         no_can ? "the kernel has no CAN support (socket(PF_CAN, SOCK_RAW, CAN_RAW): " + errnoText(err) +
                      "); load can and can-raw, waiting"
                : "socket(PF_CAN) failed: " + errnoText(err),
         -1);
    return;
  }
  const unsigned ifindex = ::if_nametoindex(name.c_str());
  if (ifindex == 0) {
    const int err = errno;
    fail(LinkState::waiting, err, "no interface " + name + " (" + errnoText(err) + "), waiting for it", fd);
    return;
  }
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, name.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd, SIOCGIFFLAGS, &ifr) == 0 && (ifr.ifr_flags & IFF_UP) == 0) {
    fail(LinkState::down, ENETDOWN, "interface " + name + " is down, waiting for it to come up", fd);
    return;
  }

  std::vector<can_filter> filters;
  for (const auto& f : settings_.filters) {
    can_filter k{};
    // RTR is in the mask so remote requests with a matching id stay out.
    if (f.extended) {
      k.can_id = (f.id & CAN_EFF_MASK) | CAN_EFF_FLAG;
      k.can_mask = (f.mask & CAN_EFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG;
    } else {
      k.can_id = f.id & CAN_SFF_MASK;
      k.can_mask = (f.mask & CAN_SFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG;
    }
    filters.push_back(k);
  }
  const int one = 1;
  const can_err_mask_t err_mask = settings_.error_frames ? CAN_ERR_MASK : 0;
  const int rcvbuf = settings_.receive_buffer_bytes;
  if ((!filters.empty() && ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                                        static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0) ||
      ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) != 0 ||
      ::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof one) != 0 ||
      ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one) != 0) {
    const int err = errno;
    fail(LinkState::waiting, err, "setsockopt on the CAN socket failed: " + errnoText(err), fd);
    return;
  }
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);  // best effort; granted size reported
  int granted = 0;
  socklen_t granted_len = sizeof granted;
  ::getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &granted, &granted_len);

  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(ifindex);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    fail(err == ENODEV ? LinkState::waiting : LinkState::down, err, "bind to " + name + " failed: " + errnoText(err),
         fd);
    return;
  }
  boost::system::error_code ec;
  socket_.assign(fd, ec);
  if (ec) {
    fail(LinkState::waiting, ec.value(), "asio assign failed: " + ec.message(), fd);
    return;
  }
  reopen_.succeeded();
  {
    std::lock_guard lock(mutex_);
    ++rare_.times_up;
    rare_.receive_buffer_bytes = granted;
    rare_.next_retry_delay_ns = 0;
    rare_.last_error.clear();
    rare_.last_errno = 0;
  }
  state_.store(LinkState::up, std::memory_order_relaxed);
  waitReadable();
}

void SocketCanReceiver::waitReadable() {
  socket_.async_wait(boost::asio::posix::stream_descriptor::wait_read,
                     [this](const boost::system::error_code& ec) { onReadable(ec); });
}

void SocketCanReceiver::onReadable(const boost::system::error_code& ec) {
  if (!reopen_.running() || ec == boost::asio::error::operation_aborted) return;
  if (ec) {
    {
      std::lock_guard lock(mutex_);
      ++rare_.read_errors;
    }
    lose(LinkState::down, ec.value(), "waiting on " + settings_.interface + " failed: " + ec.message());
    return;
  }
  const int fd = socket_.native_handle();
  can_frame kf{};
  iovec iov{&kf, sizeof kf};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(std::uint32_t))];
  for (int n = 0; n < settings_.max_frames_per_wakeup; ++n) {
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t got = ::recvmsg(fd, &msg, MSG_DONTWAIT);
    if (got < 0) {
      const int err = errno;
      if (err == EAGAIN || err == EWOULDBLOCK) break;
      if (err == EINTR) continue;
      {
        std::lock_guard lock(mutex_);
        ++rare_.read_errors;
      }
      // ENETDOWN: the interface went down; ENODEV: it was removed. Both: reopen later.
      lose(err == ENODEV ? LinkState::waiting : LinkState::down, err,
           "reading " + settings_.interface + " failed: " + errnoText(err));
      return;
    }
    if (static_cast<std::size_t>(got) != sizeof(can_frame)) {
      std::lock_guard lock(mutex_);
      ++rare_.truncated_reads;
      continue;
    }
    CanFrame f;
    std::int64_t kernel_realtime_ns = 0;
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SO_TIMESTAMPNS) {
        timespec ts{};
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        kernel_realtime_ns = static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
      } else if (c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t dropped = 0;  // the socket's running total
        std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
        kernel_drops_.store(dropped, std::memory_order_relaxed);
      }
    }
    f.error_frame = (kf.can_id & CAN_ERR_FLAG) != 0;
    f.extended = !f.error_frame && (kf.can_id & CAN_EFF_FLAG) != 0;
    f.remote = !f.error_frame && (kf.can_id & CAN_RTR_FLAG) != 0;
    f.id = f.error_frame ? (kf.can_id & CAN_ERR_MASK)
           : f.extended  ? (kf.can_id & CAN_EFF_MASK)
                         : (kf.can_id & CAN_SFF_MASK);
    f.len = kf.len > kClassicMaxLen ? kClassicMaxLen : kf.len;
    std::memcpy(f.data.data(), kf.data, kClassicMaxLen);
    if (f.error_frame) {
      std::lock_guard lock(mutex_);
      countErrorFrame(f, rare_.bus);
    }
    frames_.fetch_add(1, std::memory_order_relaxed);
    on_frame_(f, kernel_realtime_ns);
    if (!reopen_.running()) return;  // the callback may stop us
  }
  waitReadable();
}

}  // namespace headingd::can
