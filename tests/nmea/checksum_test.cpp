#include <gtest/gtest.h>

#include "headingd/nmea/checksum.hpp"

namespace headingd::nmea {
namespace {

TEST(Checksum, MatchesRealReceiverLines) {
  // From the gpsd corpus (GPSmap-76S.log, nmea-fuzzy-cases.log, ais-18-27.log style).
  EXPECT_EQ(verifyChecksum("$GPRMC,125106,V,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W,S*28"),
            ChecksumVerdict::kOk);
  EXPECT_EQ(
      verifyChecksum("$GPGGA,132820.60,4134.49821229,N,09345.03351845,W,2,09,1.0,278.020,M,-31.442,M,7.6,0133*7E"),
      ChecksumVerdict::kOk);
  EXPECT_EQ(verifyChecksum("$GPGSA,A,1,,,,,,,,,,,,,,,*1E"), ChecksumVerdict::kOk);
  EXPECT_EQ(checksumOf("GPGSA,A,1,,,,,,,,,,,,,,,"), 0x1E);
}

TEST(Checksum, AcceptsLowerCaseHex) { EXPECT_EQ(verifyChecksum("$GPGSA,A,1,,,,,,,,,,,,,,,*1e"), ChecksumVerdict::kOk); }

TEST(Checksum, DetectsCorruption) {
  EXPECT_EQ(verifyChecksum("$GPGSA,A,2,,,,,,,,,,,,,,,*1E"), ChecksumVerdict::kBad);
  EXPECT_EQ(verifyChecksum("$GPGSA,A,1,,,,,,,,,,,,,,,*1F"), ChecksumVerdict::kBad);
}

TEST(Checksum, MissingOrMalformedChecksumIsMissing) {
  EXPECT_EQ(verifyChecksum("$GPGSA,A,1,,,,,,,,,,,,,,,"), ChecksumVerdict::kMissing);
  EXPECT_EQ(verifyChecksum("$GPGSA,A,1,,,,,,,,,,,,,,,*1"), ChecksumVerdict::kMissing);
  EXPECT_EQ(verifyChecksum("$GPGSA,A,1,,,,,,,,,,,,,,,*G1"), ChecksumVerdict::kMissing);
  EXPECT_EQ(verifyChecksum("$GPGSA,A,1,,,,,,,,,,,,,,,*1E "), ChecksumVerdict::kMissing);
  EXPECT_EQ(verifyChecksum("$*"), ChecksumVerdict::kMissing);
  EXPECT_EQ(verifyChecksum(""), ChecksumVerdict::kMissing);
}

TEST(Checksum, EmptyBodyHasChecksumZero) { EXPECT_EQ(verifyChecksum("$*00"), ChecksumVerdict::kOk); }

}  // namespace
}  // namespace headingd::nmea
