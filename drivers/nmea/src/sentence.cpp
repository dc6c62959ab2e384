#include "headingd/nmea/sentence.hpp"

namespace headingd::nmea {

const char* talkerName(Talker t) {
  switch (t) {
    case Talker::kGP: return "GP";
    case Talker::kGN: return "GN";
    case Talker::kGL: return "GL";
    case Talker::kGA: return "GA";
    case Talker::kGB: return "GB";
    case Talker::kGQ: return "GQ";
    case Talker::kBD: return "BD";
  }
  return "??";
}

namespace {

// Indexed by SentenceType: the address's three letters, and the name of its STATUS counter.
struct SentenceTypeNames {
  const char* code;
  const char* counter;
};
constexpr std::array<SentenceTypeNames, kSentenceTypes.size()> kSentenceTypeNames{{{"GGA", "gga"},
                                                                                   {"RMC", "rmc"},
                                                                                   {"VTG", "vtg"},
                                                                                   {"GNS", "gns"},
                                                                                   {"GSA", "gsa"},
                                                                                   {"GST", "gst"},
                                                                                   {"HDT", "hdt"},
                                                                                   {"ZDA", "zda"},
                                                                                   {"GLL", "gll"}}};

}  // namespace

const char* sentenceTypeName(SentenceType t) { return kSentenceTypeNames.at(static_cast<std::size_t>(t)).code; }
const char* sentenceTypeCounterName(SentenceType t) {
  return kSentenceTypeNames.at(static_cast<std::size_t>(t)).counter;
}

std::optional<Talker> talkerFromCode(std::string_view code) {
  for (const Talker t : {Talker::kGP, Talker::kGN, Talker::kGL, Talker::kGA, Talker::kGB, Talker::kGQ, Talker::kBD}) {
    if (code == talkerName(t)) return t;
  }
  return std::nullopt;
}

std::optional<SentenceType> sentenceTypeFromCode(std::string_view code) {
  for (const SentenceType t : kSentenceTypes) {
    if (code == sentenceTypeName(t)) return t;
  }
  return std::nullopt;
}

std::optional<FieldList> FieldList::split(std::string_view line) {
  // Drop the start character and "*HH"; what is left is address,field,field,...
  if (line.size() < 4) return std::nullopt;
  std::string_view body = line.substr(1, line.size() - 4);
  FieldList list;
  while (true) {
    if (list.count_ == kMaxFields) return std::nullopt;
    const auto comma = body.find(',');
    list.fields_[list.count_++] = body.substr(0, comma);
    if (comma == std::string_view::npos) break;
    body.remove_prefix(comma + 1);
  }
  return list;
}

}  // namespace headingd::nmea
