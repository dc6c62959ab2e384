// Cost of the estimator per IMU sample: Estimator::process on synthetic data and on a real
// BROAD trial, and the attitude EKF's predict + gravity update alone.
//
//   headingd-bench [--benchmark_filter=...] [--benchmark_repetitions=5]
//
// items_per_second is samples per second; time_per_sample is the time of one sample.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "headingd/core/attitude_ekf.hpp"
#include "headingd/core/estimator.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/numeric_csv.hpp"

namespace {

using headingd::core::AttitudeEkf;
using headingd::core::Estimator;
using headingd::core::ImuSample;
using headingd::core::Quat;
using headingd::core::Vec3;

// 60 s at 200 Hz: a rest, then rotation about a slowly changing axis with a little noise,
// gravity 9.81 and a 20/2/45 µT field. Deterministic (fixed seed).
std::vector<ImuSample> syntheticTrial() {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  auto gaussian = [&](double sigma) {
    Vec3 v;
    for (int i = 0; i < 3; ++i) v(i) = sigma * noise(rng);
    return v;
  };
  const Vec3 field_n(20.0, 2.0, 45.0), bias(0.01, -0.015, 0.008);
  const double dt = 1.0 / 200.0;
  std::vector<ImuSample> samples;
  Quat q = Quat::Identity();
  for (int i = 0; i < 12000; ++i) {
    const double t = i * dt;
    Vec3 w = Vec3::Zero();
    if (t >= 5.0) w = Vec3(std::sin(0.3 * t), 0.5 * std::cos(0.7 * t), 1.0);
    if (w.norm() > 0.0) q = (q * Quat(Eigen::AngleAxisd(w.norm() * dt, w.normalized()))).normalized();
    ImuSample s;
    s.t_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    s.gyro_rad_s = w + bias + gaussian(0.002);
    s.accel_m_s2 = q.inverse() * Vec3(0.0, 0.0, -9.81) + gaussian(0.05);
    s.mag_uT = q.inverse() * field_n + gaussian(0.2);
    samples.push_back(s);
  }
  return samples;
}

void runEstimator(benchmark::State& state, const std::vector<ImuSample>& samples) {
  for (auto _ : state) {
    Estimator est;
    for (const ImuSample& s : samples) est.process(s);
    benchmark::DoNotOptimize(est.output().q_nb);
    benchmark::ClobberMemory();
  }
  const auto n = static_cast<std::int64_t>(samples.size());
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["samples"] = static_cast<double>(n);
  state.counters["time_per_sample"] = benchmark::Counter(static_cast<double>(state.iterations() * n),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_EstimatorSynthetic(benchmark::State& state) {
  static const std::vector<ImuSample> samples = syntheticTrial();
  runEstimator(state, samples);
}
BENCHMARK(BM_EstimatorSynthetic)->Unit(benchmark::kMillisecond);

void BM_EstimatorBroadTrial(benchmark::State& state) {
  static std::string error;
  static const std::vector<ImuSample> samples = []() {
    try {
      return headingd::files::readImuCsv(HEADINGD_BENCH_BROAD_TRIAL);
    } catch (const headingd::files::CsvError& e) {
      error = e.what();
      return std::vector<ImuSample>{};
    }
  }();
  if (samples.empty()) {
    state.SkipWithError(("cannot read the BROAD trial: " + error).c_str());
    return;
  }
  // The trial's file name, as the set it comes from depends on the checkout (tests/CMakeLists.txt).
  state.SetLabel(std::filesystem::path(HEADINGD_BENCH_BROAD_TRIAL).filename().string());
  runEstimator(state, samples);
}
BENCHMARK(BM_EstimatorBroadTrial)->Unit(benchmark::kMillisecond);

// One predict (eq. 3.2-3.3) and one gravity update (eq. 3.5-3.8) per iteration.
void BM_AttitudeEkfPredictUpdate(benchmark::State& state) {
  static const std::vector<ImuSample> samples = syntheticTrial();
  AttitudeEkf ekf;
  ekf.setCovariance(0.05 * 0.05 * headingd::core::Mat4::Identity());
  std::size_t i = 0;
  for (auto _ : state) {
    const ImuSample& s = samples[i];
    i = i + 1 == samples.size() ? 0 : i + 1;
    ekf.predict(s.gyro_rad_s, 0.005, 0.004);
    ekf.updateGravity(s.accel_m_s2, 0.5, 9.81);
    benchmark::DoNotOptimize(ekf.state());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["time_per_sample"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_AttitudeEkfPredictUpdate);

}  // namespace

BENCHMARK_MAIN();
