#pragma once
// What [nmea_out] sends for one estimate: the configured sentences (HDT, THS, HDG, in that
// order) in one fixed buffer, built on the estimator thread without allocating. Pure.
//
// THS's mode says how far to trust the heading:
//   V  no true heading: no estimate yet, the estimate is stale ([daemon] imu_timeout_s), or no
//      declination is known (no WMM position, no GPS, no receiver variation): the heading
//      would be magnetic. THS then has the last true heading (stale) or none.
//   S  the sources are files (a log, a CSV, a recording): a replay, not the world now.
//   E  the magnetometer is disturbed or not used: the heading runs on the gyroscope alone.
//   A  otherwise.
// HDT has no mode: it is sent only when THS would not say V. HDG (the body's magnetic
// heading, deviation 0.0 -- the calibration is applied --, variation = the declination in
// use, empty when none is known) only while the estimate is fresh.
#include <array>
#include <cstddef>
#include <string_view>

#include "headingd/core/heading_pipeline.hpp"
#include "headingd/daemon/outputs/lcm_messages.hpp"  // Validity
#include "headingd/daemon/outputs/nmea_out_config.hpp"
#include "headingd/nmea/heading_sentences.hpp"

namespace headingd::daemon {

struct NmeaOutBatch {
  std::array<char, 3 * nmea::SentenceText::kMaxLength> bytes{};
  std::size_t size = 0;
  std::size_t sentences = 0;
  std::string_view view() const { return {bytes.data(), size}; }
};

nmea::ThsMode thsMode(const core::HeadingOutput& h, Validity v, bool from_files);

// Fills `out` with the sentences `config` asks for (those that apply, see above).
void formatNmeaOut(const NmeaOutConfig& config, const core::HeadingOutput& h, Validity v, bool from_files,
                   NmeaOutBatch& out);

}  // namespace headingd::daemon
