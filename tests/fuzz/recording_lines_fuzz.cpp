// The black box's line formats (recording_format.hpp) on arbitrary lines: the can stream's
// notes, the gps and estimator streams' lines. Invariants: parsing never trips the
// sanitizers; what parsed is written back by the recorder's own formatters to lines that
// parse to the same values (a gps read's bytes may be split over several lines).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "headingd/recording/recording_format.hpp"

using namespace headingd;

namespace {

std::string_view asView(const recording::LineBuffer& buffer, std::size_t n) {
  FUZZ_CHECK(n <= recording::kMaxLineBytes);
  return std::string_view(buffer, n);
}

void checkCanNote(std::string_view line) {
  const auto note = recording::parseCanNote(line);
  if (!note) return;
  FUZZ_CHECK(note->candump_ns >= 0);
  recording::LineBuffer out;
  const std::size_t n = note->kind == recording::CanNote::kFlush ? recording::formatCanFlush(note->candump_ns, out)
                                                                 : recording::formatCanDropped(note->candump_ns, out);
  const auto again = recording::parseCanNote(asView(out, n));
  FUZZ_CHECK(again && again->kind == note->kind && again->candump_ns == note->candump_ns);
}

void checkGpsLine(std::string_view line) {
  recording::ParsedGpsLine parsed;
  std::string error;
  if (!recording::parseGpsLine(line, parsed, &error)) {
    FUZZ_CHECK(!error.empty());
    return;
  }
  recording::LineBuffer out;
  recording::ParsedGpsLine again;
  if (parsed.op != recording::GpsOp::kRead) {
    const std::size_t n = parsed.op == recording::GpsOp::kIdle ? recording::formatGpsIdle(parsed.t_ns, out)
                                                               : recording::formatGpsEnd(parsed.t_ns, out);
    FUZZ_CHECK(recording::parseGpsLine(asView(out, n), again, &error));
    FUZZ_CHECK(again.op == parsed.op && again.t_ns == parsed.t_ns);
    return;
  }
  const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(parsed.bytes.data()),
                                            parsed.bytes.size());
  std::string read_back;
  for (std::size_t at = 0; at < bytes.size();) {
    std::size_t used = 0;
    const std::size_t n = recording::formatGpsRead(parsed.t_ns, bytes.subspan(at), out, &used);
    FUZZ_CHECK(used >= 1);
    FUZZ_CHECK(recording::parseGpsLine(asView(out, n), again, &error));
    FUZZ_CHECK(again.op == recording::GpsOp::kRead && again.t_ns == parsed.t_ns);
    read_back += again.bytes;
    at += used;
  }
  FUZZ_CHECK(read_back == parsed.bytes);
}

void checkEstimatorLine(std::string_view line) {
  recording::ParsedEstimatorLine parsed;
  std::string error;
  if (!recording::parseEstimatorLine(line, parsed, &error)) {
    FUZZ_CHECK(!error.empty());
    return;
  }
  recording::LineBuffer out;
  const std::size_t n = parsed.op == recording::EstimatorOp::kGpsPlaced
                            ? recording::formatGpsPlaced(parsed.t_ns, parsed.imu_samples_before, out)
                            : recording::formatCalibrationReloaded(parsed.t_ns, parsed.imu_samples_before, out);
  recording::ParsedEstimatorLine again;
  FUZZ_CHECK(recording::parseEstimatorLine(asView(out, n), again, &error));
  FUZZ_CHECK(again.op == parsed.op && again.t_ns == parsed.t_ns &&
             again.imu_samples_before == parsed.imu_samples_before);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    const std::string_view line = rest.substr(0, end);
    rest.remove_prefix(end == std::string_view::npos ? rest.size() : end + 1);
    checkCanNote(line);
    (void)recording::parseLostNote(line);
    checkGpsLine(line);
    checkEstimatorLine(line);
  }
  return 0;
}
