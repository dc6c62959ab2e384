#pragma once
// Bytes from a live source (serial port, paced log) in, one Fix per completed epoch out.
//
// The Parser gives a Fix after every decoded sentence; consumers want one per receiver epoch
// (one UTC time of fix). An epoch is complete when a sentence of the next epoch arrives, the
// same rule as replay's readNmeaEpochs(), so a live source and the pure parser on the same
// bytes give the same sequence of Fix values. Waiting for the next epoch costs one epoch
// period of latency, so a source that knows more (the line went quiet, the device is gone,
// the log's group of lines ended) calls completeEpoch() to deliver the epoch at once; any
// sentence of that epoch arriving afterwards is counted as late, never delivered twice.
//
// A Fix is stamped with the receive time of the chunk holding the last byte of the epoch's
// last decoded sentence (CLOCK_MONOTONIC ns, given by the caller), not the time it is
// delivered: that is when the receiver had finished saying it.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "headingd/nmea/counters.hpp"
#include "headingd/nmea/fix.hpp"
#include "headingd/nmea/framer.hpp"
#include "headingd/nmea/parser.hpp"

namespace headingd::nmea {

// One Fix per completed epoch, with the monotonic receive time of the byte that completed it.
using FixHandler = std::function<void(const Fix& fix, std::int64_t receive_ns)>;
// Every line that passed the checksum ('$' and '!', decoded or not), '$'..."*HH" without
// CR/LF, for logging and recording.
using LineHandler = std::function<void(std::string_view line, std::int64_t receive_ns)>;

// Sees every call an EpochAssembler gets from a live reader, with its time, in order: the
// same calls replayed into another assembler with the same ParserConfig give the same Fix
// values with the same receive times (the black box records them; drivers/recording).
class AssemblerInputTap {
 public:
  virtual ~AssemblerInputTap() = default;
  virtual void fed(std::span<const std::uint8_t> bytes, std::int64_t receive_ns) = 0;
  virtual void epochCompleted(std::int64_t now_ns) = 0;  // completeEpoch() with an epoch pending
  virtual void streamEnded(std::int64_t now_ns) = 0;     // endOfStream()
};

struct EpochCounters {
  std::uint64_t epochs = 0;          // Fix values delivered
  std::uint64_t late_sentences = 0;  // decoded after their epoch was delivered (not delivered)
};

class EpochAssembler {
 public:
  EpochAssembler(ParserConfig config, FixHandler on_fix, LineHandler on_line = {});

  // Bytes received at receive_ns (CLOCK_MONOTONIC). Calls the handlers before returning.
  void feed(std::span<const std::uint8_t> bytes, std::int64_t receive_ns);
  // Delivers the epoch in progress now, if it has not been delivered yet.
  void completeEpoch();
  // The stream ended (device lost, end of file): a line still open is counted as truncated
  // and dropped, and the epoch in progress is delivered. Feeding may resume afterwards.
  void endOfStream();

  // True while an epoch has been started and not delivered yet.
  bool epochPending() const { return current_.has_value() && !delivered_; }
  Counters parserCounters() const { return parser_.counters(); }
  const EpochCounters& epochCounters() const { return counters_; }

 private:
  void onUpdate(const FixUpdate& update, std::int64_t receive_ns);
  void deliver();

  Parser parser_;
  Framer line_framer_;  // only for on_line_: the Parser keeps its lines to itself
  FixHandler on_fix_;
  LineHandler on_line_;
  std::vector<FixUpdate> updates_;  // reused between bytes
  std::optional<Fix> current_;      // the epoch in progress, after its latest sentence
  std::int64_t current_receive_ns_ = 0;
  bool delivered_ = false;
  EpochCounters counters_;
};

}  // namespace headingd::nmea
