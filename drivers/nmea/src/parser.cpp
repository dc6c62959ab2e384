#include "headingd/nmea/parser.hpp"

#include "headingd/nmea/sentences.hpp"

namespace headingd::nmea {
Parser::Parser(ParserConfig config) : framer_(config.framer), accumulator_(config.accumulator) {}

void Parser::feed(std::span<const std::uint8_t> bytes, std::vector<FixUpdate>& updates) {
  for (const std::uint8_t b : bytes) {
    if (const auto line = framer_.push(b)) handleLine(*line, updates);
  }
}

void Parser::feed(std::string_view bytes, std::vector<FixUpdate>& updates) {
  feed(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), updates);
}

void Parser::finish() { framer_.finish(); }

Counters Parser::counters() const { return Counters{framer_.counters(), sentences_}; }

void Parser::handleLine(std::string_view line, std::vector<FixUpdate>& updates) {
  if (line.front() == '!') {
    ++sentences_.ais;
    return;
  }
  const DecodeResult r = decodeSentence(line);
  switch (r.status) {
    case DecodeStatus::kUnsupportedTalker: ++sentences_.unsupported_talker; return;
    case DecodeStatus::kUnsupportedType: ++sentences_.unsupported_type; return;
    case DecodeStatus::kMalformed: ++sentences_.malformed; return;
    case DecodeStatus::kDecoded: break;
  }
  const DecodedSentence& s = *r.sentence;
  ++sentences_.decoded;
  ++sentences_.decodedOf(s.type);
  sentences_.invalid_fields += static_cast<std::uint64_t>(s.invalid_fields);
  accumulator_.apply(s);
  updates.push_back(FixUpdate{s.talker, s.type, std::string(line), accumulator_.fix()});
}

}  // namespace headingd::nmea
