#include "port_holder.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace headingd::test {
namespace {

// The child: only system calls from here on (it was forked from a process with threads).
[[noreturn]] void holdUntilReleased(const char* device, HoldWith how, const char* name, int control_fd, int ready_fd,
                                    std::atomic<std::uint64_t>* read) {
  ::prctl(PR_SET_NAME, name);
  const int fd = ::open(device, O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) ::_exit(10);
  if (how != HoldWith::kFlock && ::ioctl(fd, TIOCEXCL) != 0) ::_exit(11);
  if (how != HoldWith::kExclusiveMode && ::flock(fd, LOCK_EX | LOCK_NB) != 0) ::_exit(12);
  const char ok = 1;
  if (::write(ready_fd, &ok, 1) != 1) ::_exit(13);
  ::close(ready_fd);
  char buffer[4096];
  auto drain = [&] {
    for (;;) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n <= 0) return;
      read->fetch_add(static_cast<std::uint64_t>(n));
    }
  };
  for (;;) {
    pollfd p[2] = {{fd, POLLIN, 0}, {control_fd, POLLIN, 0}};
    if (::poll(p, 2, -1) < 0 && errno != EINTR) ::_exit(14);
    if (p[0].revents & POLLIN) drain();
    if (p[1].revents != 0) break;  // the parent closed its end: let go
  }
  drain();
  if (how != HoldWith::kFlock) ::ioctl(fd, TIOCNXCL);
  ::close(fd);
  ::_exit(0);
}

}  // namespace

const char* holdWithName(HoldWith h) {
  switch (h) {
    case HoldWith::kExclusiveMode: return "ExclusiveMode";
    case HoldWith::kFlock: return "Flock";
    case HoldWith::kBoth: return "Both";
  }
  return "?";
}

PortHolder::PortHolder(const std::string& device, HoldWith how, const std::string& name) {
  void* shared =
      ::mmap(nullptr, sizeof(std::atomic<std::uint64_t>), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED) throw std::runtime_error(std::string("mmap: ") + std::strerror(errno));
  read_ = new (shared) std::atomic<std::uint64_t>(0);
  int control[2], ready[2];
  if (::pipe2(control, O_CLOEXEC) != 0 || ::pipe2(ready, O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  }
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid_ == 0) {
    ::close(control[1]);
    ::close(ready[0]);
    holdUntilReleased(device.c_str(), how, name.c_str(), control[0], ready[1], read_);
  }
  ::close(control[0]);
  ::close(ready[1]);
  control_fd_ = control[1];
  char ok = 0;
  const ssize_t n = ::read(ready[0], &ok, 1);
  ::close(ready[0]);
  if (n != 1) {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    throw std::runtime_error("port holder could not take " + device + " (child exit status " +
                             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
}

PortHolder::~PortHolder() {
  release();
  if (read_ != nullptr) ::munmap(read_, sizeof *read_);
}

std::uint64_t PortHolder::bytesRead() const { return read_->load(); }

void PortHolder::release() {
  if (control_fd_ >= 0) ::close(control_fd_);
  control_fd_ = -1;
  if (pid_ > 0) ::waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

}  // namespace headingd::test
