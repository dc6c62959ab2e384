#pragma once
// The skeleton every Asio-driven source shares: an io_context run by a thread of the
// source's own, the start and stop sequence, a periodic timer on that thread (the driver's
// counters live there, so they are copied into a mutex-protected snapshot that report()
// reads from any thread), and the counts of what went into the source's ring.
//
// A source derives from AsioSource<Counters> and fills in the hooks, all called on the io
// thread: onStart (start the driver), onStop (stop it; live sources only), onTick (periodic
// work besides the snapshot) and currentCounters (the driver's counters for the snapshot).
// Its destructor must call stop(), so that the io thread ends before its members go.
#include <atomic>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/sources/source.hpp"

namespace headingd::daemon {

class AsioSourceBase : public Source {
 public:
  // How long the io thread runs.
  enum class Lifetime {
    kUntilStopped,  // a device: kept running until stop(), which runs onStop on the io thread
    kUntilPlayed,   // a file: ends when the io_context runs out of work (played); stop() interrupts it
  };

  const std::string& name() const final { return name_; }
  // Posts onStart (then the first tick) and starts the io thread; a second call does nothing.
  void start() final;
  // kUntilStopped: onStop and the timer's end on the io thread (waited for up to 0.5 s), then
  // the thread is joined; kUntilPlayed: the io_context is stopped and the thread joined.
  void stop() final;

 protected:
  // `snapshot_period` 0: no periodic timer (the source snapshots when it wants to).
  AsioSourceBase(std::string name, std::uint16_t source_index, Lifetime lifetime,
                 std::chrono::milliseconds snapshot_period);

  boost::asio::io_context& io() { return io_; }

  virtual void onStart() = 0;
  virtual void onStop() {}
  virtual void onTick() {}
  // Copies the driver's counters into the snapshot (AsioSource<Counters>).
  virtual void takeSnapshot() = 0;
  // No further ticks (a file played to the end, so that the io_context runs out of work).
  void stopTicks();

  // Pushes `entry`, stamped with this source's index, into `ring` and counts the outcome;
  // false: the ring was full and the entry is dropped.
  template <class Entry>
  bool push(SampleRing<Entry>& ring, Entry entry) {
    entry.source_index = source_index_;
    const bool pushed = ring.push(entry);
    (pushed ? pushed_ : dropped_).fetch_add(1, std::memory_order_relaxed);
    return pushed;
  }
  // The same for a file source that can wait: false leaves the entry for a later try and
  // counts nothing.
  template <class Entry>
  bool tryPush(SampleRing<Entry>& ring, Entry entry) {
    entry.source_index = source_index_;
    if (!ring.push(entry)) return false;
    pushed_.fetch_add(1, std::memory_order_relaxed);
    return true;
  }
  std::uint64_t pushed() const { return pushed_.load(std::memory_order_relaxed); }
  std::uint64_t ringFullDrops() const { return dropped_.load(std::memory_order_relaxed); }
  // A report's first two counters: `pushed_name` ("samples_pushed", "epochs_pushed") and
  // "ring_full_drops". Returns the index of the next counter.
  std::size_t reportPushes(SourceReport& out, std::string_view pushed_name) const {
    out.set(0, pushed_name, pushed());
    out.set(1, "ring_full_drops", ringFullDrops());
    return 2;
  }

 private:
  void tick();

  std::string name_;
  std::uint16_t source_index_;
  Lifetime lifetime_;
  std::chrono::milliseconds snapshot_period_;
  boost::asio::io_context io_;
  std::optional<boost::asio::executor_work_guard<boost::asio::io_context::executor_type>> work_;
  boost::asio::steady_timer tick_timer_;
  bool ticking_ = false;  // io thread only
  std::thread thread_;
  std::atomic<std::uint64_t> pushed_{0}, dropped_{0};
};

template <class Counters>
class AsioSource : public AsioSourceBase {
 protected:
  using AsioSourceBase::AsioSourceBase;

  // The driver's counters now (io thread).
  virtual Counters currentCounters() const = 0;
  void takeSnapshot() override {
    std::lock_guard lock(snapshot_mutex_);
    snapshot_ = currentCounters();
  }
  // Any thread: `read(const Counters&)` under the snapshot's lock.
  template <class Read>
  void withSnapshot(Read&& read) const {
    std::lock_guard lock(snapshot_mutex_);
    read(snapshot_);
  }

 private:
  mutable std::mutex snapshot_mutex_;
  Counters snapshot_{};
};

}  // namespace headingd::daemon
