#pragma once
// Helpers shared by the NMEA tests.
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/nmea/checksum.hpp"
#include "headingd/nmea/parser.hpp"
#include "headingd/nmea/sentences.hpp"

namespace headingd::nmea::test {

// "$" + body + "*HH" with the right checksum (checksumOf is itself checked against lines
// taken from real receivers in checksum_test.cpp).
inline std::string sentence(std::string_view body, char start = '$') {
  char cs[4];
  std::snprintf(cs, sizeof cs, "*%02X", checksumOf(body));
  return std::string(1, start) + std::string(body) + cs;
}

inline DecodedSentence decodeOk(std::string_view body) {
  const DecodeResult r = decodeSentence(sentence(body));
  if (r.status != DecodeStatus::kDecoded) throw std::runtime_error("not decoded: " + std::string(body));
  return *r.sentence;
}

template <class T>
T decodeAs(std::string_view body) {
  return std::get<T>(decodeOk(body).data);
}

// Runs whole lines (CRLF added) through a fresh Parser.
inline std::vector<FixUpdate> parseLines(const std::vector<std::string>& lines, Parser* parser_out = nullptr) {
  Parser local;
  Parser& p = parser_out ? *parser_out : local;
  std::vector<FixUpdate> updates;
  for (const auto& l : lines) p.feed(l + "\r\n", updates);
  return updates;
}

}  // namespace headingd::nmea::test
