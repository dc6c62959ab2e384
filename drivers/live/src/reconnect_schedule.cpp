#include "headingd/live/reconnect_schedule.hpp"

#include <utility>

namespace headingd::live {

ReconnectSchedule::ReconnectSchedule(boost::asio::io_context& io, ReconnectDelay backoff, std::function<void()> attempt)
    : timer_(io), backoff_(backoff), attempt_(std::move(attempt)) {}

bool ReconnectSchedule::start() {
  if (running_) return false;
  running_ = true;
  backoff_.reset();
  attemptAfter(std::chrono::nanoseconds(0));
  return true;
}

bool ReconnectSchedule::stop() {
  if (!running_) return false;
  running_ = false;
  timer_.cancel();
  return true;
}

std::chrono::nanoseconds ReconnectSchedule::retryAfterFailure() {
  const std::chrono::nanoseconds wait = backoff_.afterFailure();
  attemptAfter(wait);
  return wait;
}

std::chrono::nanoseconds ReconnectSchedule::retryAfterLoss() {
  const std::chrono::nanoseconds wait = backoff_.reset();
  attemptAfter(wait);
  return wait;
}

void ReconnectSchedule::attemptAfter(std::chrono::nanoseconds delay) {
  timer_.expires_after(delay);
  timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired() || ec || !running_) return;
    attempt_();
  });
}

}  // namespace headingd::live
