#include "headingd/can/candump_writer.hpp"

#include "headingd/can/candump_log.hpp"

namespace headingd::can {

CandumpWriteStats writeCandumpLog(const std::vector<core::ImuSample>& samples, const ImuFrameCodec& codec,
                                  const CandumpWriteOptions& options, std::ostream& out) {
  CandumpWriteStats stats;
  const std::uint64_t sequence_mask = codec.sequenceBits() == 0 ? 0 : (1ull << codec.sequenceBits()) - 1;
  std::vector<CanFrame> frames;
  std::vector<const CanFrame*> ordered;
  const int mag_every = options.mag_every < 1 ? 1 : options.mag_every;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const core::ImuSample& s = samples[i];
    const bool with_mag = s.has_mag && codec.hasMag() && i % static_cast<std::size_t>(mag_every) == 0;
    if (!s.has_mag) ++stats.epochs_without_mag_data;
    frames.clear();
    stats.clamped_values += static_cast<std::uint64_t>(codec.encode(s, i & sequence_mask, with_mag, frames));
    // Magnetometer-only messages first; encode() keeps the binding order otherwise.
    ordered.clear();
    const auto& bindings = codec.messages();
    for (int pass = 0; pass < 2; ++pass) {
      std::size_t k = 0;
      for (const auto& b : bindings) {
        if (!with_mag && (b.axis_mask & ~kMagAxes) == 0) continue;
        const bool mag_only = (b.axis_mask & ~kMagAxes) == 0;
        if ((pass == 0) == mag_only) ordered.push_back(&frames[k]);
        ++k;
      }
    }
    std::int64_t t = options.start_time_ns + s.t_ns;
    for (const CanFrame* f : ordered) {
      CanFrame stamped = *f;
      stamped.t_ns = t;
      out << formatCandumpLine(stamped, options.interface) << '\n';
      t += options.frame_spacing_ns;
      ++stats.frames;
    }
    ++stats.epochs;
  }
  return stats;
}

}  // namespace headingd::can
