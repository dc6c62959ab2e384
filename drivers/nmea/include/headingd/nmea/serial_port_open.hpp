#pragma once
// Opening a serial device the way a GPS receiver needs it: 8N1, raw (no echo, no canonical
// line editing, no CR/LF translation, no signals), no hardware or software flow control,
// modem lines ignored (CLOCAL), reads returning as soon as one byte is there.
#include <string>
#include <variant>

namespace headingd::nmea {

struct OpenedSerialDevice {
  int fd = -1;  // non-blocking, close-on-exec; the caller owns it
};

struct SerialOpenFailure {
  bool device_missing = false;  // the path (or what a symlink points to) does not exist
  std::string message;          // names the path and says what is wrong
};

// baud must be a standard rate (isStandardBaudRate); anything else fails with a message.
std::variant<OpenedSerialDevice, SerialOpenFailure> openSerialDevice(const std::string& path, unsigned baud);

}  // namespace headingd::nmea
