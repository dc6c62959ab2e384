#pragma once
// write(2) until everything is written or an error: partial writes continue, EINTR retries.
#include <cstddef>

namespace headingd::daemon {

struct WriteOutcome {
  std::size_t written = 0;  // bytes that reached the file
  int error = 0;            // errno of the failed call, 0 when everything was written
};

WriteOutcome writeFully(int fd, const char* data, std::size_t size);

}  // namespace headingd::daemon
