#include "headingd/nmea/serial_port_open.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>

namespace headingd::nmea {
namespace {

std::optional<speed_t> speedFor(unsigned baud) {
  switch (baud) {
    case 1200: return B1200;
    case 2400: return B2400;
    case 4800: return B4800;
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return std::nullopt;
  }
}

SerialOpenFailure failure(const std::string& path, const std::string& what, int err, bool missing = false) {
  std::string m = path + ": " + what;
  if (err != 0) m += std::string(" (") + std::strerror(err) + ")";
  return SerialOpenFailure{missing, m};
}

}  // namespace

std::variant<OpenedSerialDevice, SerialOpenFailure> openSerialDevice(const std::string& path, unsigned baud) {
  const std::optional<speed_t> speed = speedFor(baud);
  if (!speed) return failure(path, std::to_string(baud) + " is not a standard baud rate", 0);

  // O_NONBLOCK: open must not wait for carrier detect on a port whose CLOCAL is still off.
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    if (err == ENOENT) return failure(path, "device does not exist, waiting for it to appear", err, true);
    if (err == EACCES) return failure(path, "permission denied (is the user in the dialout group?)", err);
    return failure(path, "cannot open", err);
  }
  auto fail = [&](const std::string& what, int err) {
    ::close(fd);
    return failure(path, what, err);
  };

  struct stat st {};
  if (::fstat(fd, &st) != 0) return fail("cannot stat", errno);
  if (!S_ISCHR(st.st_mode)) return fail("is not a tty (not even a character device)", 0);
  if (!::isatty(fd)) return fail("is not a tty", errno);

  termios t{};
  if (::tcgetattr(fd, &t) != 0) return fail("cannot read terminal settings", errno);
  ::cfmakeraw(&t);
  t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
  t.c_cflag |= CS8 | CREAD | CLOCAL;
  t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  t.c_cc[VMIN] = 1;
  t.c_cc[VTIME] = 0;
  if (::cfsetispeed(&t, *speed) != 0 || ::cfsetospeed(&t, *speed) != 0) {
    return fail("cannot set " + std::to_string(baud) + " baud", errno);
  }
  if (::tcsetattr(fd, TCSANOW, &t) != 0) return fail("cannot set terminal settings", errno);
  return OpenedSerialDevice{fd};
}

}  // namespace headingd::nmea
