#pragma once
// The subset of the DBC format (Vector's CAN database, also read by cantools and SavvyCAN)
// that IMU decoding needs: messages (BO_) and their signals (SG_). Everything else (CM_, BA_,
// VAL_, NS_, BS_, BU_, ...) is skipped. Parsing is pure: text in, database out.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace headingd::can {

// A DBC file that does not parse: the message names source:line and what was expected.
class DbcError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ByteOrder {
  little_endian,  // "@1", Intel: start bit is the least significant bit
  big_endian,     // "@0", Motorola: start bit is the most significant bit (DBC bit numbering)
};

struct DbcSignal {
  std::string name;
  unsigned start_bit = 0;  // as written in the file (its meaning depends on byte_order)
  unsigned length = 1;     // bits, 1..64
  ByteOrder byte_order = ByteOrder::little_endian;
  bool is_signed = false;
  double factor = 1.0;
  double offset = 0.0;
  double minimum = 0.0;  // [min|max] as written; 0|0 means "not given" in DBC practice
  double maximum = 0.0;
  std::string unit;
  std::vector<std::string> receivers;
  bool multiplexed = false;  // "M" or "mN": not decodable without the multiplexer; kept for messages
  int line = 0;              // where it was defined, for configuration errors
};

struct DbcMessage {
  std::uint32_t id = 0;   // without the extended flag
  bool extended = false;  // bit 31 (0x80000000) of the id in the file
  std::string name;
  unsigned dlc = 8;  // bytes
  std::string transmitter;
  std::vector<DbcSignal> signals;
  int line = 0;

  const DbcSignal* findSignal(std::string_view signal_name) const;
};

struct DbcDatabase {
  std::string source;  // file name used in messages
  std::vector<DbcMessage> messages;

  const DbcMessage* findMessage(std::string_view message_name) const;
};

// Parses DBC text; `source_name` prefixes error messages ("imu.dbc:12: ..."). Throws DbcError
// on malformed BO_/SG_ lines, duplicate names, and signals that do not fit their message.
DbcDatabase parseDbc(std::string_view text, const std::string& source_name);

// Reads and parses a file; throws DbcError (also when the file cannot be read).
DbcDatabase loadDbcFile(const std::string& path);

}  // namespace headingd::can
