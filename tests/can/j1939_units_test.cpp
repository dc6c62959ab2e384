// J1939 PGN extraction (PDU1 and PDU2) and unit conversion to SI.
#include <gtest/gtest.h>

#include <numbers>

#include "headingd/can/j1939.hpp"
#include "headingd/can/units.hpp"
#include "headingd/core/angles.hpp"

namespace headingd::can {
namespace {

TEST(J1939, Pdu2PgnIncludesGroupExtension) {
  // OpenIMU angular rate: priority 6, PGN 61482 (0xF02A), source address 0x80.
  const std::uint32_t id = 0x18F02A80u;
  EXPECT_EQ(j1939Priority(id), 6);
  EXPECT_EQ(j1939PduFormat(id), 0xF0);
  EXPECT_EQ(j1939PduSpecific(id), 0x2A);
  EXPECT_EQ(j1939SourceAddress(id), 0x80);
  EXPECT_TRUE(j1939IsPdu2(id));
  EXPECT_EQ(j1939Pgn(id), 61482u);
  EXPECT_EQ(j1939Pgn(0x0CFF6A23u), 65386u);  // other priority and source address, same PGN
  EXPECT_EQ(j1939Id(6, 61482, 0x80), id);
}

TEST(J1939, Pdu1PgnDropsDestinationAddress) {
  // PGN 59904 (0xEA00, request), PF 0xEA < 240: PS is the destination address.
  const std::uint32_t to_21 = j1939Id(6, 59904, 0x80, 0x21);
  const std::uint32_t to_global = j1939Id(3, 59904, 0x17, 0xFF);
  EXPECT_FALSE(j1939IsPdu2(to_21));
  EXPECT_EQ(j1939PduSpecific(to_21), 0x21);
  EXPECT_EQ(j1939Pgn(to_21), 59904u);
  EXPECT_EQ(j1939Pgn(to_global), 59904u);
  EXPECT_EQ(to_21 & j1939PgnMask(to_21), to_global & j1939PgnMask(to_global));
}

TEST(J1939, DataPageIsPartOfThePgn) {
  const std::uint32_t dp1 = 0x19F02A80u;  // data page bit set
  EXPECT_EQ(j1939Pgn(dp1), 0x1F02Au);
  EXPECT_NE(dp1 & j1939PgnMask(dp1), 0x18F02A80u & j1939PgnMask(0x18F02A80u));
}

TEST(Units, FactorsToSi) {
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::angular_rate, "rad/s"), 1.0);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::angular_rate, "deg/s"), core::kRadPerDeg);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::angular_rate, " dps "), core::kRadPerDeg);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::angular_rate, "\xC2\xB0/s"), core::kRadPerDeg);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::acceleration, "g"), 9.80665);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::acceleration, "mg"), 9.80665e-3);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::acceleration, "m/s^2"), 1.0);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::magnetic_field, "uT"), 1.0);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::magnetic_field, "nT"), 1e-3);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::magnetic_field, "gauss"), 100.0);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::magnetic_field, "G"), 100.0);
  EXPECT_DOUBLE_EQ(*unitFactorToSi(Quantity::magnetic_field, "mG"), 0.1);
  // Wrong quantity or unknown spelling: no factor.
  EXPECT_FALSE(unitFactorToSi(Quantity::magnetic_field, "mg"));
  EXPECT_FALSE(unitFactorToSi(Quantity::acceleration, "G"));
  EXPECT_FALSE(unitFactorToSi(Quantity::angular_rate, "m/s^2"));
  EXPECT_FALSE(unitFactorToSi(Quantity::angular_rate, ""));
  EXPECT_FALSE(unitFactorToSi(Quantity::angular_rate, "furlongs/fortnight"));
}

}  // namespace
}  // namespace headingd::can
