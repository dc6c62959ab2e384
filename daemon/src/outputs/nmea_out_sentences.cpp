#include "headingd/daemon/outputs/nmea_out_sentences.hpp"

#include <cstring>
#include <numbers>
#include <optional>

#include "headingd/core/angles.hpp"

namespace headingd::daemon {
namespace {

using core::kDegPerRad;

bool hasTrueHeading(const core::HeadingOutput& h, Validity v) {
  return v != Validity::kNone && h.declination_sources != core::kDeclNone;
}

void append(NmeaOutBatch& out, const nmea::SentenceText& s) {
  const std::string_view text = s.view();
  if (out.size + text.size() > out.bytes.size()) return;  // cannot happen: three short sentences
  std::memcpy(out.bytes.data() + out.size, text.data(), text.size());
  out.size += text.size();
  ++out.sentences;
}

}  // namespace

nmea::ThsMode thsMode(const core::HeadingOutput& h, Validity v, bool from_files) {
  if (v != Validity::kFresh || !hasTrueHeading(h, v)) return nmea::ThsMode::kInvalid;
  if (from_files) return nmea::ThsMode::kSimulator;
  if (h.attitude.mag_disturbed || !h.attitude.mag_used) return nmea::ThsMode::kEstimated;
  return nmea::ThsMode::kAutonomous;
}

void formatNmeaOut(const NmeaOutConfig& config, const core::HeadingOutput& h, Validity v, bool from_files,
                   NmeaOutBatch& out) {
  out.size = 0;
  out.sentences = 0;
  const nmea::ThsMode mode = thsMode(h, v, from_files);
  const std::optional<double> true_deg =
      hasTrueHeading(h, v) ? std::optional<double>(h.heading_true_rad * kDegPerRad) : std::nullopt;
  if (config.hdt && mode != nmea::ThsMode::kInvalid) append(out, nmea::formatHdt(config.talker, true_deg));
  if (config.ths) append(out, nmea::formatThs(config.talker, true_deg, mode));
  if (config.hdg && v == Validity::kFresh) {
    const double magnetic_deg = (h.heading_mag_rad - h.mount_yaw_rad) * kDegPerRad;
    const std::optional<double> variation_deg =
        h.declination_sources != core::kDeclNone ? std::optional<double>(h.declination_rad * kDegPerRad) : std::nullopt;
    append(out, nmea::formatHdg(config.talker, magnetic_deg, 0.0, variation_deg));
  }
}

}  // namespace headingd::daemon
