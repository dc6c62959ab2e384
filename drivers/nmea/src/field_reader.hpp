#pragma once
// Private to the decoders: typed access to the fields of one sentence that counts fields
// which are present but unusable (an empty field is absent, not invalid).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "headingd/nmea/fields.hpp"
#include "headingd/nmea/sentence.hpp"
#include "headingd/nmea/sentences.hpp"

namespace headingd::nmea::detail {

class FieldReader {
 public:
  FieldReader(const FieldList& fields, int& invalid_fields) : f_(fields), invalid_(invalid_fields) {}

  std::string_view raw(std::size_t i) const { return f_.field(i); }
  std::size_t dataFields() const { return f_.count() - 1; }

  std::optional<double> decimal(std::size_t i) { return counted(i, parseDecimal(raw(i))); }
  std::optional<int> integer(std::size_t i) { return counted(i, parseInteger(raw(i))); }
  std::optional<std::int64_t> timeOfDay(std::size_t i) { return counted(i, parseTimeOfDay(raw(i))); }
  std::optional<double> bearing(std::size_t i) { return counted(i, parseBearing(raw(i))); }
  std::optional<DayMonthYy> ddmmyy(std::size_t i) { return counted(i, parseDdmmyy(raw(i))); }

  // A one-letter field (status, mode indicator).
  std::optional<char> letter(std::size_t i) {
    const auto s = raw(i);
    if (s.empty()) return std::nullopt;
    if (s.size() != 1) {
      ++invalid_;
      return std::nullopt;
    }
    return s[0];
  }

  // A non-negative quantity (DOP, speed, sigma).
  std::optional<double> nonNegative(std::size_t i) {
    auto v = decimal(i);
    if (v && *v < 0.0) {
      ++invalid_;
      return std::nullopt;
    }
    return v;
  }

  // Latitude, N/S, longitude, E/W in fields i..i+3. All four empty is "no position".
  std::optional<Position> position(std::size_t i) {
    if (raw(i).empty() && raw(i + 1).empty() && raw(i + 2).empty() && raw(i + 3).empty()) return std::nullopt;
    const auto lat = parseLatitude(raw(i), raw(i + 1));
    const auto lon = parseLongitude(raw(i + 2), raw(i + 3));
    if (!lat || !lon) {
      ++invalid_;
      return std::nullopt;
    }
    return Position{*lat, *lon};
  }

  // A value with a unit letter in the next field (GGA altitude "545.4,M").
  std::optional<double> withUnit(std::size_t i, char unit) {
    auto v = decimal(i);
    if (v && !raw(i + 1).empty() && raw(i + 1) != std::string_view(&unit, 1)) {
      ++invalid_;
      return std::nullopt;
    }
    return v;
  }

  void countInvalid() { ++invalid_; }

 private:
  template <class T>
  std::optional<T> counted(std::size_t i, std::optional<T> v) {
    if (!v && !raw(i).empty()) ++invalid_;
    return v;
  }

  const FieldList& f_;
  int& invalid_;
};

}  // namespace headingd::nmea::detail
