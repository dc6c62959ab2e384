#pragma once
// Opening a serial device the way a GPS receiver needs it: 8N1, raw (no echo, no canonical
// line editing, no CR/LF translation, no signals), no hardware or software flow control,
// modem lines ignored (CLOCAL), reads returning as soon as one byte is there; and ours
// alone: a port another program holds is refused as busy (naming that program when it can be
// seen), never shared, since two readers of one serial port each get part of the byte stream.
#include <string>
#include <variant>

namespace headingd::nmea {

struct OpenedSerialDevice {
  int fd = -1;  // non-blocking, close-on-exec; the caller owns it
};

struct SerialOpenFailure {
  bool device_missing = false;  // the path (or what a symlink points to) does not exist
  bool busy = false;            // another program holds the port (TIOCEXCL or flock)
  std::string message;          // names the path and says what is wrong (and who holds it, if busy)
};

// baud must be a standard rate (isStandardBaudRate); anything else fails with a message.
// On success the descriptor holds an exclusive flock and the tty is in exclusive mode
// (TIOCEXCL; not a pty, see the .cpp); releaseSerialDevice undoes the latter before the
// descriptor is closed.
std::variant<OpenedSerialDevice, SerialOpenFailure> openSerialDevice(const std::string& path, unsigned baud);

// Clears the tty's exclusive mode (TIOCNXCL) on a descriptor from openSerialDevice, before it
// is closed. The mode belongs to the tty, not to the descriptor: it outlives our close while
// anything else still has the tty open (a pty's creator keeps its slave), and would then
// refuse the next unprivileged open, ours included. The flock goes with the descriptor.
void releaseSerialDevice(int fd);

}  // namespace headingd::nmea
