#pragma once
// A checksummed line split into its address (talker + sentence type) and data fields.
#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace headingd::nmea {

// The GNSS talkers we decode. Anything else (proprietary $P..., $II, $HE, $AI, ...) is
// counted and ignored.
enum class Talker { kGP, kGN, kGL, kGA, kGB, kGQ, kBD };

// The sentences we decode. Others from a known talker (GSV, GLL, TXT, ...) are counted
// and ignored.
// GLL is decoded too: its time marks the start of an epoch on receivers that send it
// first (ericsson-gru04.log: GLL, VTG, ZDA, GNS), which keeps VTG in the right epoch.
enum class SentenceType { kGGA, kRMC, kVTG, kGNS, kGSA, kGST, kHDT, kZDA, kGLL };
inline constexpr std::array<SentenceType, 9> kSentenceTypes{SentenceType::kGGA, SentenceType::kRMC, SentenceType::kVTG,
                                                            SentenceType::kGNS, SentenceType::kGSA, SentenceType::kGST,
                                                            SentenceType::kHDT, SentenceType::kZDA, SentenceType::kGLL};

const char* talkerName(Talker t);
const char* sentenceTypeName(SentenceType t);         // "GGA"
const char* sentenceTypeCounterName(SentenceType t);  // "gga", its count's name on STATUS
std::optional<Talker> talkerFromCode(std::string_view two_letters);
std::optional<SentenceType> sentenceTypeFromCode(std::string_view three_letters);

// Views into the line; valid as long as the line is. field(0) is the address ("GPGGA"),
// field(i) the i-th data field as numbered in NMEA 0183 (GGA field 1 = UTC time). Asking for
// a field past the end gives "", the same as an empty field: receivers drop trailing fields.
class FieldList {
 public:
  static constexpr std::size_t kMaxFields = 64;  // GSA with 24 PRNs has 30; more is not NMEA

  // Splits a line that passed verifyChecksum(); nullopt if it has more than kMaxFields fields.
  static std::optional<FieldList> split(std::string_view line);

  std::string_view field(std::size_t i) const { return i < count_ ? fields_[i] : std::string_view{}; }
  std::size_t count() const { return count_; }  // including the address
  std::string_view address() const { return field(0); }

 private:
  std::array<std::string_view, kMaxFields> fields_{};
  std::size_t count_ = 0;
};

}  // namespace headingd::nmea
