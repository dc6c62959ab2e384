#pragma once
// Ends a GPS reader's epoch in progress once its input has been quiet for epoch_idle_s, so
// that a fix goes out at the end of its burst instead of when the next epoch starts. One
// timer per quiet period: input that arrives while it runs pushes the deadline instead of
// re-arming the timer on every read.
//
// Threading: as its owner: every call, and the callbacks, on the io_context's thread.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

namespace headingd::live {

class EpochIdleTimer {
 public:
  // idle_s <= 0: never (an epoch ends when the next one starts). `epoch_pending` says whether
  // an epoch is in progress; `end_epoch` ends it.
  EpochIdleTimer(boost::asio::io_context& io, double idle_s, std::function<bool()> epoch_pending,
                 std::function<void()> end_epoch);
  EpochIdleTimer(const EpochIdleTimer&) = delete;
  EpochIdleTimer& operator=(const EpochIdleTimer&) = delete;

  // Input received at `receive_ns` (monotonicNs()) was fed to the epoch: the quiet period
  // starts again, and the timer runs if an epoch is pending and it does not run already.
  void fed(std::int64_t receive_ns);
  // The input closed: the timer stops without ending the epoch (its owner ends the stream).
  void cancel() { timer_.cancel(); }

 private:
  void waitFor(std::chrono::nanoseconds wait);
  void onTimer();

  boost::asio::steady_timer timer_;
  double idle_s_;
  std::function<bool()> epoch_pending_;
  std::function<void()> end_epoch_;
  std::int64_t last_receive_ns_ = 0;
  bool armed_ = false;
  // The handler holds a weak_ptr to this: once the timer is gone, it does nothing.
  std::shared_ptr<int> alive_ = std::make_shared<int>(0);
};

}  // namespace headingd::live
