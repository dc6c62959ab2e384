#pragma once
// What the two live GPS sources ([gps] source = "serial" and "gpsd") share: a driver on the
// source's own io thread hands over each receiver epoch as a fix with its monotonic receive
// time (the live IMU's time axis), which goes into the source's GPS ring as the estimator's
// observation, through the one conversion every GPS input uses.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/sources/asio_source.hpp"
#include "headingd/nmea/gps_observation_from_fix.hpp"

namespace headingd::daemon {

// `Driver` (nmea::SerialGpsReader, gpsd::GpsdClient) has start(), stop() and counters(); the
// derived source makes it on io() in its constructor, handing it pushFix as the fix callback,
// and calls stop() in its own destructor.
template <class Driver>
class GpsFixSource : public AsioSource<std::invoke_result_t<decltype(&Driver::counters), const Driver&>> {
 public:
  using Counters = std::invoke_result_t<decltype(&Driver::counters), const Driver&>;

  // A receiver's epochs come as it sends them, and their arrival time places them: a driver
  // thread (real-time priority where configured).
  bool readsAtRealTimePace() const override { return true; }

 protected:
  // How often the driver's counters are copied for STATUS (they may only be read on its thread).
  static constexpr std::chrono::milliseconds kSnapshotPeriod{250};

  GpsFixSource(std::string name, std::uint16_t source_index, SampleRing<GpsRingEntry>* gps_ring)
      : AsioSource<Counters>(std::move(name), source_index, AsioSourceBase::Lifetime::kUntilStopped, kSnapshotPeriod),
        ring_(gps_ring) {}

  // io thread: one epoch into the ring (counted as pushed or dropped).
  void pushFix(const nmea::Fix& fix, std::int64_t receive_ns) {
    GpsRingEntry e;
    e.observation = nmea::gpsObservationFromFix(fix, receive_ns);
    e.arrival_mono_ns = receive_ns;
    this->push(*ring_, e);
  }

  std::unique_ptr<Driver> driver_;

 private:
  void onStart() override { driver_->start(); }
  void onStop() override {
    driver_->stop();
    this->takeSnapshot();  // the driver's last word, for a report after stop
  }
  Counters currentCounters() const override { return driver_->counters(); }

  SampleRing<GpsRingEntry>* ring_;
};

}  // namespace headingd::daemon
