#pragma once
// The whole pipeline: bytes -> Framer -> decodeSentence -> FixAccumulator. Pure and
// single-threaded; the serial driver and the replay reader feed it whatever they read.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/nmea/counters.hpp"
#include "headingd/nmea/fix.hpp"
#include "headingd/nmea/fix_accumulator.hpp"
#include "headingd/nmea/framer.hpp"
#include "headingd/nmea/sentence.hpp"

namespace headingd::nmea {

struct ParserConfig {
  FramerConfig framer;
  FixAccumulatorConfig accumulator;
};

// The Fix after one decoded sentence.
struct FixUpdate {
  Talker talker = Talker::kGP;
  SentenceType type = SentenceType::kGGA;
  std::string sentence;  // the line as received, '$' through "*HH"
  Fix fix;
};

class Parser {
 public:
  explicit Parser(ParserConfig config = {});

  // Appends one FixUpdate per decoded sentence completed by these bytes.
  void feed(std::span<const std::uint8_t> bytes, std::vector<FixUpdate>& updates);
  void feed(std::string_view bytes, std::vector<FixUpdate>& updates);
  // End of stream (counts a line left open as truncated).
  void finish();

  Counters counters() const;
  const Fix& fix() const { return accumulator_.fix(); }
  std::size_t buffered() const { return framer_.buffered(); }

 private:
  void handleLine(std::string_view line, std::vector<FixUpdate>& updates);

  Framer framer_;
  FixAccumulator accumulator_;
  SentenceCounters sentences_;
};

}  // namespace headingd::nmea
