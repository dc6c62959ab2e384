// [nmea_out]'s cost on the estimator thread per send: the sentences formatted into the batch
// (formatNmeaOut: HDT, THS and HDG, the most it sends), the formatters alone, and the handoff
// to the network thread. Not run by
// CTest: build/tests/headingd-nmea-out-bench prints the figures.
#include <benchmark/benchmark.h>

#include <chrono>
#include <numbers>
#include <thread>

#include "headingd/core/angles.hpp"
#include "headingd/daemon/outputs/nmea_out_sentences.hpp"
#include "headingd/daemon/outputs/nmea_out_server.hpp"
#include "headingd/nmea/heading_sentences.hpp"

namespace {

using namespace headingd;

core::HeadingOutput estimate(double true_deg) {
  core::HeadingOutput h;
  h.attitude.valid = true;
  h.attitude.mag_used = true;
  h.heading_true_rad = true_deg * headingd::core::kRadPerDeg;
  h.declination_rad = 0.05;
  h.heading_mag_rad = h.heading_true_rad - h.declination_rad;
  h.declination_sources = core::kDeclWmm;
  return h;
}

void BM_FormatNmeaOutHdtThsHdg(benchmark::State& state) {
  daemon::NmeaOutConfig config;
  config.hdg = true;
  daemon::NmeaOutBatch batch;
  double deg = 0.0;
  for (auto _ : state) {
    deg = deg < 359.0 ? deg + 0.37 : 0.0;
    daemon::formatNmeaOut(config, estimate(deg), daemon::Validity::kFresh, false, batch);
    benchmark::DoNotOptimize(batch.bytes.data());
  }
  state.SetLabel("3 sentences per send");
}
BENCHMARK(BM_FormatNmeaOutHdtThsHdg);

void BM_FormatHdt(benchmark::State& state) {
  double deg = 0.0;
  for (auto _ : state) {
    deg = deg < 359.0 ? deg + 0.37 : 0.0;
    const nmea::SentenceText s = nmea::formatHdt("HE", deg);
    benchmark::DoNotOptimize(s.view().data());
  }
}
BENCHMARK(BM_FormatHdt);

// The handoff: the batch copied into the lock-free ring, the network thread draining it on its
// timer. No socket: tcp and udp off, so nothing leaves the process.
void BM_OfferToTheNetworkThread(benchmark::State& state) {
  daemon::NmeaOutConfig config;
  config.tcp = false;
  config.udp = false;
  config.hdg = true;
  config.rate_hz = 100.0;  // the network thread looks every 5 ms
  daemon::NmeaOutServer server(config, 5, 10.0);
  server.start();
  daemon::NmeaOutBatch batch;
  daemon::formatNmeaOut(config, estimate(123.4), daemon::Validity::kFresh, false, batch);
  std::uint64_t refused = 0;
  for (auto _ : state) {
    // Timed alone, then 50 us for the network thread to drain it (as at 10 Hz, where it is idle).
    const auto t0 = std::chrono::steady_clock::now();
    refused += server.offer(batch) ? 0 : 1;
    const auto t1 = std::chrono::steady_clock::now();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
  server.stop();
  state.counters["ring_full"] = static_cast<double>(refused);
}
BENCHMARK(BM_OfferToTheNetworkThread)->UseManualTime()->Iterations(20000);

}  // namespace

BENCHMARK_MAIN();
