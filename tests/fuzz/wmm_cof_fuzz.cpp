// World Magnetic Model coefficients (NOAA's COF layout), the [daemon] wmm file:
// parseWmmCoefficients on arbitrary text. Invariants: only WmmParseError is thrown; what
// parses builds a WorldMagneticModel; with coefficients of a plausible size (below 10^6 nT,
// the main field is 6*10^4) its field at a valid position and date is finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_check.hpp"
#include "headingd/core/wmm.hpp"

using namespace headingd;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  core::WmmCoefficients coefficients;
  try {
    coefficients = core::parseWmmCoefficients(text, "fuzz.cof");
  } catch (const core::WmmParseError&) {
    return 0;
  }
  FUZZ_CHECK(coefficients.degree >= 1 && coefficients.degree <= core::kWmmMaxDegree);
  const core::WorldMagneticModel model(coefficients);
  const core::MagneticFieldElements field =
      model.field(core::GeodeticPosition{48.1, 11.6, 0.5}, model.epochYear() + 1.0);
  bool plausible = true;
  for (const core::WmmTerm& t : coefficients.terms) {
    plausible = plausible && std::abs(t.g_nT) < 1e6 && std::abs(t.h_nT) < 1e6 && std::abs(t.g_rate_nT_per_year) < 1e6 &&
                std::abs(t.h_rate_nT_per_year) < 1e6;
  }
  if (plausible) {
    FUZZ_CHECK(std::isfinite(field.f_nT) && std::isfinite(field.declination_deg) &&
               std::isfinite(field.inclination_deg));
  }
  return 0;
}
