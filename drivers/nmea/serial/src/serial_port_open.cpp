#include "headingd/nmea/serial_port_open.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>

#include "headingd/nmea/device_holders.hpp"

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
  return SerialOpenFailure{missing, false, m};
}

// The port is held by someone else: name them if /proc lets us see them.
SerialOpenFailure busy(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::canonical(path, ec);
  const auto holders = ec ? std::vector<DeviceHolder>{} : findDeviceHolders(real.string(), ::getpid());
  std::string m = path + ": busy, held by " + describeDeviceHolders(holders);
  if (holders.empty()) m += " (gpsd is the usual one)";
  return SerialOpenFailure{false, true, m};
}

// Unix98 pty slaves (/dev/pts/N) have majors 136 .. 143 (the kernel's devices.txt).
bool isPtySlave(const struct stat& st) {
  const unsigned m = major(st.st_rdev);
  return m >= 136 && m <= 143;
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
    if (err == EBUSY) return busy(path);  // another program set TIOCEXCL (gpsd does) and we are not root
    return failure(path, "cannot open", err);
  }
  bool exclusive = false;  // TIOCEXCL set by us: cleared again on failure
  auto fail = [&](const std::string& what, int err) {
    if (exclusive) releaseSerialDevice(fd);
    ::close(fd);
    return failure(path, what, err);
  };

  struct stat st {};
  if (::fstat(fd, &st) != 0) return fail("cannot stat", errno);
  if (!S_ISCHR(st.st_mode)) return fail("is not a tty (not even a character device)", 0);
  if (!::isatty(fd)) return fail("is not a tty", errno);

  // Ours alone, checked before anything is changed on the port. No one lock sees every
  // other program, so three steps:
  // - TIOCEXCL (tty_ioctl(4), below) puts the tty in exclusive mode: every further open() by a
  //   process without CAP_SYS_ADMIN fails with EBUSY. gpsd sets it on the serial devices it
  //   opens (and clears it on close), so that EBUSY, above, is how an unprivileged headingd --
  //   the unit's user -- sees gpsd. Set by us, it keeps gpsd (which drops root) and anything
  //   unprivileged off our port.
  // - Root is exempt from TIOCEXCL, so a root headingd opens gpsd's port anyway; TIOCGEXCL
  //   then says the mode is already set, by a holder still there (the mode lives as long as
  //   someone has the tty open, and we clear ours on close: releaseSerialDevice), and we
  //   back off all the same.
  // - flock(LOCK_EX | LOCK_NB): advisory, and root is not exempt, so two programs that both
  //   take it (a second headingd, picocom) see each other even when neither is privileged
  //   enough to care about TIOCEXCL, or when one of them never set it.
  // What none of these catches: a program as root that takes neither lock nor exclusive mode
  // (`cat /dev/ttyUSB0` as root). gpsd in turn refuses a device another process has open (it
  // counts /proc/*/fd links), so beside gpsd whichever opens first keeps the port.
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd);
    if (err == EWOULDBLOCK) return busy(path);
    return failure(path, "cannot lock", err);
  }
  int exclusive_already = 0;
  if (::ioctl(fd, TIOCGEXCL, &exclusive_already) == 0 && exclusive_already != 0) {
    ::close(fd);  // the flock goes with it; the other holder's exclusive mode stays
    return busy(path);
  }
  // Not on a pty (gpsd makes the same exception): exclusive mode lives as long as anyone has
  // the tty open, and a pty's creator often keeps its slave open, so a headingd killed without
  // clearing it (SIGKILL, the watchdog's SIGABRT) would leave the pty refusing its own
  // restart, unprivileged, for good. On a real port the mode ends with the last close. The
  // flock, which dies with the process, still guards a pty.
  if (!isPtySlave(st)) {
    if (::ioctl(fd, TIOCEXCL) != 0) return fail("cannot take exclusive use (TIOCEXCL)", errno);
    exclusive = true;
  }

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

void releaseSerialDevice(int fd) {
  if (fd >= 0) ::ioctl(fd, TIOCNXCL);
}

}  // namespace headingd::nmea
