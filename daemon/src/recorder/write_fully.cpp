#include "headingd/daemon/recorder/write_fully.hpp"

#include <unistd.h>
#include <cerrno>

namespace headingd::daemon {

WriteOutcome writeFully(int fd, const char* data, std::size_t size) {
  WriteOutcome out;
  while (out.written < size) {
    const ssize_t n = ::write(fd, data + out.written, size - out.written);
    if (n > 0) {
      out.written += static_cast<std::size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      out.error = n < 0 ? errno : EIO;  // 0 bytes for a non-empty write: the device took nothing
      break;
    }
  }
  return out;
}

}  // namespace headingd::daemon
