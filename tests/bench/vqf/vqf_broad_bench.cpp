// VQF's 9D filter (github.com/dlaidig/vqf, C++ version) timed on a BROAD trial exactly as
// headingd-bench's BM_EstimatorBroadTrial times core::Estimator: a fresh filter per pass over
// the whole trial, time_per_sample = run time / samples. Not part of the build: VQF is not a
// Debian package and its code is not copied here. tools/scripts/bench-against-vqf.sh compiles
// this file against a VQF checkout and runs both benchmarks in turn.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <vector>

#include "vqf.hpp"

namespace {

struct Row {
  vqf_real_t gyr[3], acc[3], mag[3];
};

// The trial's gzip'd BROAD CSV (t, gyr_*, acc_*, mag_*, ...), and its mean sample period.
std::vector<Row> readTrial(const std::string& path, double* sample_period_s) {
  std::vector<Row> rows;
  FILE* in = popen(("zcat '" + path + "'").c_str(), "r");
  if (in == nullptr) return rows;
  char line[4096];
  double first_t = 0.0, last_t = 0.0;
  if (std::fgets(line, sizeof line, in) != nullptr) {  // the header
    while (std::fgets(line, sizeof line, in) != nullptr) {
      Row r;
      double t, v[9];
      if (std::sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &t, &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                      &v[6], &v[7], &v[8]) != 10) {
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        r.gyr[k] = v[k];
        r.acc[k] = v[3 + k];
        r.mag[k] = v[6 + k];
      }
      if (rows.empty()) first_t = t;
      last_t = t;
      rows.push_back(r);
    }
  }
  pclose(in);
  *sample_period_s = rows.size() > 1 ? (last_t - first_t) / static_cast<double>(rows.size() - 1) : 0.0;
  return rows;
}

void BM_VqfBroadTrial(benchmark::State& state) {
  static double sample_period_s = 0.0;
  static const std::vector<Row> rows = readTrial(HEADINGD_BENCH_BROAD_TRIAL, &sample_period_s);
  if (rows.empty()) {
    state.SkipWithError("cannot read the BROAD trial");
    return;
  }
  for (auto _ : state) {
    VQF vqf(sample_period_s);
    for (const Row& r : rows) vqf.update(r.gyr, r.acc, r.mag);
    vqf_real_t q[4];
    vqf.getQuat9D(q);
    benchmark::DoNotOptimize(q);
    benchmark::ClobberMemory();
  }
  const auto n = static_cast<std::int64_t>(rows.size());
  state.counters["samples"] = static_cast<double>(n);
  state.counters["time_per_sample"] = benchmark::Counter(static_cast<double>(state.iterations() * n),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_VqfBroadTrial)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
