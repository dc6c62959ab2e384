#include "headingd/nmea/sentences.hpp"

namespace headingd::nmea {
namespace {

template <class T>
DecodeResult decodeWith(std::optional<T> (*decoder)(const FieldList&, int&), Talker talker, SentenceType type,
                        const FieldList& fields) {
  int invalid_fields = 0;
  const std::optional<T> data = decoder(fields, invalid_fields);
  if (!data) return {DecodeStatus::kMalformed, std::nullopt};
  return {DecodeStatus::kDecoded, DecodedSentence{talker, type, SentenceData{*data}, invalid_fields}};
}

}  // namespace

DecodeResult decodeSentence(std::string_view line) {
  if (line.empty() || line.front() != '$') return {DecodeStatus::kUnsupportedTalker, std::nullopt};
  const auto fields = FieldList::split(line);
  if (!fields) return {DecodeStatus::kMalformed, std::nullopt};
  const std::string_view address = fields->address();
  // Standard sentences have a 2-letter talker and a 3-letter type; proprietary ones start
  // with 'P' and are never ours.
  const auto talker = address.size() == 5 ? talkerFromCode(address.substr(0, 2)) : std::nullopt;
  if (!talker) return {DecodeStatus::kUnsupportedTalker, std::nullopt};
  const auto type = sentenceTypeFromCode(address.substr(2));
  if (!type) return {DecodeStatus::kUnsupportedType, std::nullopt};

  switch (*type) {
    case SentenceType::kGGA: return decodeWith(decodeGga, *talker, *type, *fields);
    case SentenceType::kRMC: return decodeWith(decodeRmc, *talker, *type, *fields);
    case SentenceType::kVTG: return decodeWith(decodeVtg, *talker, *type, *fields);
    case SentenceType::kGNS: return decodeWith(decodeGns, *talker, *type, *fields);
    case SentenceType::kGSA: return decodeWith(decodeGsa, *talker, *type, *fields);
    case SentenceType::kGST: return decodeWith(decodeGst, *talker, *type, *fields);
    case SentenceType::kHDT: return decodeWith(decodeHdt, *talker, *type, *fields);
    case SentenceType::kZDA: return decodeWith(decodeZda, *talker, *type, *fields);
    case SentenceType::kGLL: return decodeWith(decodeGll, *talker, *type, *fields);
  }
  return {DecodeStatus::kMalformed, std::nullopt};
}

}  // namespace headingd::nmea
