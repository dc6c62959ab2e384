// [nmea_out]'s cost on the estimator thread per send: the sentences formatted into the batch
// (formatNmeaOut: HDT, THS and HDG, the most it sends), and the formatters alone. Not run by
// CTest: build/tests/headingd-nmea-out-bench prints the figures.
#include <benchmark/benchmark.h>

#include <numbers>

#include "headingd/daemon/nmea_out_sentences.hpp"
#include "headingd/nmea/heading_sentences.hpp"

namespace {

using namespace headingd;

core::HeadingOutput estimate(double true_deg) {
  core::HeadingOutput h;
  h.attitude.valid = true;
  h.attitude.mag_used = true;
  h.heading_true_rad = true_deg * std::numbers::pi / 180.0;
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

}  // namespace

BENCHMARK_MAIN();
