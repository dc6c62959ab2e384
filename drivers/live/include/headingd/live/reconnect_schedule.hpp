#pragma once
// When a driver that reopens a device or reconnects to a peer makes its next attempt: one
// timer on the driver's io_context, the back-off (ReconnectDelay), whether the driver is
// running, and the guard the driver's other handlers hold. The serial GPS reader, the gpsd
// client and the SocketCAN receiver each own one, so they start, stop and retry alike; what
// an attempt does, and what a failure is called, stays theirs.
//
// Threading: as its owner: every call, and the attempt, on the io_context's thread.
#include <chrono>
#include <functional>
#include <memory>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "headingd/live/reconnect_delay.hpp"

namespace headingd::live {

class ReconnectSchedule {
 public:
  // `attempt` opens or connects; it is called on the io_context, and only while running.
  ReconnectSchedule(boost::asio::io_context& io, ReconnectDelay backoff, std::function<void()> attempt);
  ReconnectSchedule(const ReconnectSchedule&) = delete;
  ReconnectSchedule& operator=(const ReconnectSchedule&) = delete;

  // Running from now on, the back-off at its initial wait, the first attempt as soon as the
  // io_context runs. False (and nothing done) if it was running already.
  bool start();
  // No more attempts: the pending one is cancelled. False if it was not running.
  bool stop();
  bool running() const { return running_; }

  // An attempt failed: the next one after the back-off's wait, which doubles for the one
  // after (up to the maximum). Returns the wait.
  std::chrono::nanoseconds retryAfterFailure();
  // A link that worked was lost: the next attempt after the initial wait.
  std::chrono::nanoseconds retryAfterLoss();
  // An attempt succeeded: the next failure waits the initial wait again.
  void succeeded() { backoff_.reset(); }

  // For the owner's handlers (reads, other timers): expired once this schedule, a member of
  // its owner, is gone, so that a handler that completes after its owner does nothing.
  std::weak_ptr<void> guard() const { return alive_; }

 private:
  void attemptAfter(std::chrono::nanoseconds delay);

  boost::asio::steady_timer timer_;
  ReconnectDelay backoff_;
  std::function<void()> attempt_;
  bool running_ = false;
  std::shared_ptr<int> alive_ = std::make_shared<int>(0);
};

}  // namespace headingd::live
