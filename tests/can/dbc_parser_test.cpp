// DBC subset parser: BO_/SG_ fields, skipped sections, and errors that name source:line.
#include <gtest/gtest.h>

#include "can_test_support.hpp"
#include "headingd/can/dbc.hpp"

namespace headingd::can {
namespace {

constexpr const char* kSample = R"(VERSION "x"

NS_ :
	NS_DESC_
	CM_
	BA_DEF_
	BO_TX_BU_
	SIG_VALTYPE_

BS_:

BU_: IMU ECU

BO_ 291 IMU_A: 8 IMU
 SG_ RateX : 0|16@1- (0.01,0) [-327.68|327.67] "deg/s" ECU
 SG_ Temp : 23|8@0+ (1,-40) [-40|215] "degC"  ECU,IMU
 SG_ Mux M : 63|2@0+ (1,0) [0|3] "" ECU

BO_ 2565876352 J_MSG: 6 IMU
 SG_ Big : 7|16@0- (1E-003,+1.5) [0|0] "m/s^2" Vector__XXX

CM_ "a comment
over several lines with BO_ 1 FAKE: 8 X
and a SG_ line inside";
BA_DEF_ BO_ "GenMsgCycleTime" INT 0 10000;
BA_ "GenMsgCycleTime" BO_ 291 10;
VAL_ 291 Mux 0 "a" 1 "b" ;
BO_ 3221225472 VECTOR__INDEPENDENT_SIG_MSG: 0 Vector__XXX
 SG_ Orphan : 0|8@1+ (1,0) [0|0] "" Vector__XXX
)";

TEST(DbcParser, ReadsMessagesAndSignals) {
  const DbcDatabase db = parseDbc(kSample, "sample.dbc");
  ASSERT_EQ(db.messages.size(), 2u);
  const DbcMessage& a = db.messages[0];
  EXPECT_EQ(a.name, "IMU_A");
  EXPECT_EQ(a.id, 291u);
  EXPECT_FALSE(a.extended);
  EXPECT_EQ(a.dlc, 8u);
  EXPECT_EQ(a.transmitter, "IMU");
  EXPECT_EQ(a.line, 14);
  ASSERT_EQ(a.signals.size(), 3u);
  const DbcSignal& rate = a.signals[0];
  EXPECT_EQ(rate.name, "RateX");
  EXPECT_EQ(rate.start_bit, 0u);
  EXPECT_EQ(rate.length, 16u);
  EXPECT_EQ(rate.byte_order, ByteOrder::little_endian);
  EXPECT_TRUE(rate.is_signed);
  EXPECT_DOUBLE_EQ(rate.factor, 0.01);
  EXPECT_DOUBLE_EQ(rate.offset, 0.0);
  EXPECT_DOUBLE_EQ(rate.minimum, -327.68);
  EXPECT_DOUBLE_EQ(rate.maximum, 327.67);
  EXPECT_EQ(rate.unit, "deg/s");
  EXPECT_EQ(rate.receivers, std::vector<std::string>{"ECU"});
  EXPECT_EQ(rate.line, 15);
  const DbcSignal& temp = a.signals[1];
  EXPECT_EQ(temp.byte_order, ByteOrder::big_endian);
  EXPECT_FALSE(temp.is_signed);
  EXPECT_DOUBLE_EQ(temp.offset, -40.0);
  EXPECT_EQ(temp.receivers, (std::vector<std::string>{"ECU", "IMU"}));
  EXPECT_TRUE(a.signals[2].multiplexed);

  const DbcMessage& j = db.messages[1];
  EXPECT_TRUE(j.extended);
  EXPECT_EQ(j.id, 0x18F02A80u);
  EXPECT_EQ(j.dlc, 6u);
  EXPECT_DOUBLE_EQ(j.signals[0].factor, 1e-3);
  EXPECT_DOUBLE_EQ(j.signals[0].offset, 1.5);
  EXPECT_EQ(db.findMessage("J_MSG"), &j);
  EXPECT_EQ(db.findMessage("FAKE"), nullptr);  // inside a comment
  EXPECT_EQ(j.findSignal("Big"), &j.signals[0]);
}

void expectError(const std::string& text, const std::string& fragment) {
  try {
    parseDbc(text, "bad.dbc");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const DbcError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(DbcParser, ErrorsNameLineAndExpectation) {
  expectError("\nBO_ 12 A 8 X\n", "bad.dbc:2: expected ':' after the message name");
  expectError("BO_ 12 A: 9 X\n", "bad.dbc:1: expected a length of at most 8 bytes");
  expectError("BO_ 2048 A: 8 X\n", "bad.dbc:1: expected a standard id up to 0x7FF");
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|8@2+ (1,0) [0|0] \"\" X\n", "bad.dbc:2: expected byte order 0");
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|8@1* (1,0) [0|0] \"\" X\n", "bad.dbc:2: expected '+' (unsigned)");
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|8@1+ (1;0) [0|0] \"\" X\n", "bad.dbc:2: expected ',' between factor");
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|8@1+ (1,0) [0|0] deg X\n", "bad.dbc:2: expected the unit in double quotes");
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|0@1+ (1,0) [0|0] \"\" X\n", "signal length of 1..64");
  expectError("BO_ 12 A: 2 X\n SG_ S : 8|16@1+ (1,0) [0|0] \"\" X\n",
              "bad.dbc:2: expected a signal inside the message's 2 bytes (it needs 3)");
  expectError("BO_ 12 A: 8 X\n SG_ S : 7|16@0+ (1,0) [0|0] \"\" X\n SG_ S : 0|8@1+ (1,0) [0|0] \"\" X\n",
              "bad.dbc:3: expected a signal name not used before");
  expectError("BO_ 12 A: 8 X\nBO_ 12 B: 8 X\n", "bad.dbc:2: expected a message id not used before (line 1)");
  expectError("CM_ \"open\n", "expected a closing '\"'");
  expectError("BU_: X\n SG_ S : 0|8@1+ (1,0) [0|0] \"\" X\n", "bad.dbc:2: expected SG_ lines directly after their BO_");
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|8@1+ (0,0) [0|0] \"\" X\n", "non-zero factor");
  // A factor or offset that is not finite would turn every decoded value into nan or inf,
  // and every sample would be rejected: the file is refused instead.
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|8@1+ (nan,0) [0|0] \"\" X\n", "bad.dbc:2: expected a finite, non-zero factor");
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|8@1+ (inf,0) [0|0] \"\" X\n", "bad.dbc:2: expected a finite, non-zero factor");
  expectError("BO_ 12 A: 8 X\n SG_ S : 0|8@1+ (1,-nan) [0|0] \"\" X\n", "bad.dbc:2: expected a finite offset");
}

TEST(DbcParser, ShippedFilesParse) {
  const DbcDatabase own = loadDbcFile(test::configPath("dbc/headingd_imu.dbc"));
  ASSERT_EQ(own.messages.size(), 3u);
  for (const auto& m : own.messages) {
    EXPECT_FALSE(m.extended);
    EXPECT_EQ(m.signals.size(), 4u) << m.name;
  }
  const DbcDatabase openimu = loadDbcFile(test::configPath("dbc/openimu_j1939.dbc"));
  ASSERT_EQ(openimu.messages.size(), 3u);
  for (const auto& m : openimu.messages) EXPECT_TRUE(m.extended) << m.name;
  EXPECT_THROW(loadDbcFile("/nonexistent/file.dbc"), DbcError);
}

TEST(DbcParser, GarbageNeverCrashes) {
  std::string text = kSample;
  std::uint32_t state = 12345;
  for (int round = 0; round < 2000; ++round) {
    std::string mutated = text;
    for (int k = 0; k < 4; ++k) {
      state = state * 1664525u + 1013904223u;
      mutated[state % mutated.size()] = static_cast<char>(state >> 24);
    }
    try {
      parseDbc(mutated, "fuzz.dbc");
    } catch (const DbcError&) {
    }
  }
  SUCCEED();
}

}  // namespace
}  // namespace headingd::can
