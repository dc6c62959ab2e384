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

const char* sentenceTypeName(SentenceType t) {
  switch (t) {
    case SentenceType::kGGA: return "GGA";
    case SentenceType::kRMC: return "RMC";
    case SentenceType::kVTG: return "VTG";
    case SentenceType::kGNS: return "GNS";
    case SentenceType::kGSA: return "GSA";
    case SentenceType::kGST: return "GST";
    case SentenceType::kHDT: return "HDT";
    case SentenceType::kZDA: return "ZDA";
    case SentenceType::kGLL: return "GLL";
  }
  return "???";
}

std::optional<Talker> talkerFromCode(std::string_view code) {
  for (const Talker t : {Talker::kGP, Talker::kGN, Talker::kGL, Talker::kGA, Talker::kGB, Talker::kGQ, Talker::kBD}) {
    if (code == talkerName(t)) return t;
  }
  return std::nullopt;
}

std::optional<SentenceType> sentenceTypeFromCode(std::string_view code) {
  for (const SentenceType t :
       {SentenceType::kGGA, SentenceType::kRMC, SentenceType::kVTG, SentenceType::kGNS, SentenceType::kGSA,
        SentenceType::kGST, SentenceType::kHDT, SentenceType::kZDA, SentenceType::kGLL}) {
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
