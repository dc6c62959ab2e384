#pragma once
// Another program holding a serial port, as gpsd does: a child process (its own pid, named
// by prctl so /proc/PID/comm shows it) that opens the device, takes it the way it is told
// (exclusive mode with TIOCEXCL, as gpsd; flock, as picocom; or both) and reads and discards
// everything that arrives, counting it, until it is told to let go. Then it clears the
// exclusive mode (gpsd does the same on close), closes the device and exits.
#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <ostream>
#include <string>

namespace headingd::test {

enum class HoldWith { kExclusiveMode, kFlock, kBoth };
const char* holdWithName(HoldWith h);                                          // "ExclusiveMode", "Flock", "Both"
inline void PrintTo(HoldWith h, std::ostream* os) { *os << holdWithName(h); }  // for GoogleTest

class PortHolder {
 public:
  // Returns once the child holds the device. `name` is at most 15 characters (the kernel's
  // limit for a process name). Throws std::runtime_error if the child cannot take it.
  PortHolder(const std::string& device, HoldWith how, const std::string& name);
  ~PortHolder();  // lets go if not done yet
  PortHolder(const PortHolder&) = delete;
  PortHolder& operator=(const PortHolder&) = delete;

  pid_t pid() const { return pid_; }
  // Bytes the holder has read from the device so far.
  std::uint64_t bytesRead() const;
  // Tells the child to let go and waits for it to exit.
  void release();

 private:
  pid_t pid_ = -1;
  int control_fd_ = -1;                         // closed to tell the child to let go
  std::atomic<std::uint64_t>* read_ = nullptr;  // in memory shared with the child
};

}  // namespace headingd::test
