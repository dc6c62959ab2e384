#pragma once
// SocketCAN receiver: a raw CAN socket (PF_CAN, SOCK_RAW, CAN_RAW) driven by Boost.Asio (no
// polling loop), with kernel-side id filters, error frames, kernel receive timestamps
// (SO_TIMESTAMPNS) and kernel drop counts (SO_RXQ_OVFL). It survives the interface going
// down, disappearing and coming back, and a kernel without CAN support: it closes, reports
// the state and retries with a bounded exponential back-off.
//
// Threading: every handler runs on the io_context's thread; the frame callback too (the
// daemon pushes into a lock-free ring from it). status() may be called from any thread.
// Destroy the receiver before running its io_context again (pending handlers refer to it).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>

#include "headingd/can/can_frame.hpp"
#include "headingd/can/error_frame.hpp"
#include "headingd/can/imu_frame_codec.hpp"
#include "headingd/live/reconnect_schedule.hpp"

namespace headingd::can {

enum class LinkState : std::uint8_t {
  waiting,  // no socket yet: no CAN support in the kernel, or no such interface
  down,     // the interface exists but is not up (or just went down)
  up,       // bound and receiving
};
const char* linkStateName(LinkState s);

struct ReceiverSettings {
  std::string interface = "can0";
  std::vector<IdFilter> filters;  // empty: every frame
  bool error_frames = true;       // CAN_RAW_ERR_FILTER with every error class
  std::chrono::nanoseconds reconnect_initial{std::chrono::milliseconds(100)};
  std::chrono::nanoseconds reconnect_max{std::chrono::seconds(5)};
  int receive_buffer_bytes = 1 << 20;  // SO_RCVBUF request (the kernel caps it at rmem_max)
  int max_frames_per_wakeup = 256;     // then yield to other handlers on the io_context
};
ReceiverSettings receiverSettingsFrom(const CanConfig& config, const ImuFrameCodec& codec);

struct ReceiverStatus {
  LinkState state = LinkState::waiting;
  int last_errno = 0;              // of the last failed open or read
  std::string last_error;          // what failed, with the interface name
  std::uint64_t frames = 0;        // data and error frames delivered to the callback
  std::uint64_t kernel_drops = 0;  // frames the kernel dropped for a full receive queue (SO_RXQ_OVFL)
  std::uint64_t read_errors = 0;
  std::uint64_t truncated_reads = 0;  // recvmsg sizes other than a classic CAN frame
  std::uint64_t open_attempts = 0;
  std::uint64_t open_failures = 0;
  std::uint64_t times_up = 0;    // transitions into `up` (1 + reconnections)
  std::uint64_t times_lost = 0;  // transitions out of `up`
  std::int64_t next_retry_delay_ns = 0;
  int receive_buffer_bytes = 0;  // what the kernel granted
  BusErrorCounters bus;
};

class SocketCanReceiver {
 public:
  // A frame with the kernel's receive timestamp (SO_TIMESTAMPNS: CLOCK_REALTIME; 0 if the
  // kernel gave none). The frame's own t_ns is 0: its stream's axis is the caller's to choose.
  using FrameHandler = std::function<void(const CanFrame&, std::int64_t kernel_realtime_ns)>;

  SocketCanReceiver(boost::asio::io_context& io, ReceiverSettings settings, FrameHandler on_frame);
  ~SocketCanReceiver();
  SocketCanReceiver(const SocketCanReceiver&) = delete;
  SocketCanReceiver& operator=(const SocketCanReceiver&) = delete;

  void start();  // first open attempt now, on the io thread
  void stop();   // closes the socket and cancels the retry timer (call on the io thread)

  ReceiverStatus status() const;
  LinkState state() const { return state_.load(std::memory_order_relaxed); }

 private:
  void tryOpen();
  void scheduleRetry();
  void waitReadable();
  void onReadable(const boost::system::error_code& ec);
  void lose(LinkState next, int err, const std::string& what);
  void setError(LinkState next, int err, const std::string& what);

  ReceiverSettings settings_;
  FrameHandler on_frame_;
  boost::asio::posix::stream_descriptor socket_;
  live::ReconnectSchedule reopen_;  // running or stopped, the next open, the back-off

  // Per-frame counters are atomics; rare events go through the mutex.
  std::atomic<LinkState> state_{LinkState::waiting};
  std::atomic<std::uint64_t> frames_{0};
  std::atomic<std::uint64_t> kernel_drops_{0};
  mutable std::mutex mutex_;
  ReceiverStatus rare_;  // the fields other than the atomics above
};

}  // namespace headingd::can
