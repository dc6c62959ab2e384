#pragma once
// A real pseudo-terminal standing in for a GPS receiver on a serial port: the code under
// test opens the slave path (or a symlink to it, as udev's /dev/gps0), the test writes the
// receiver's bytes to the master at a chosen line rate. close() is the USB unplug.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace headingd::test {

class PtyPair {
 public:
  // posix_openpt/grantpt/unlockpt/ptsname; the slave is set raw (no echo, no CR/LF
  // translation) at once, so bytes written before the reader configures it arrive intact.
  // Throws std::system_error.
  PtyPair();
  ~PtyPair();
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  const std::string& slavePath() const { return slave_path_; }
  bool isOpen() const { return master_fd_ >= 0; }

  // Writes all bytes, waiting (poll) while the slave's input queue is full. Throws
  // std::runtime_error if nothing can be written for stall_timeout (a reader that stopped
  // reading), so a broken test fails instead of hanging.
  void write(std::span<const std::uint8_t> bytes,
             std::chrono::milliseconds stall_timeout = std::chrono::milliseconds(5000));
  // The same, chunk by chunk at absolute deadlines so the average rate is bytes_per_second
  // (a serial line at B baud 8N1 carries B/10 bytes per second).
  void writePaced(std::span<const std::uint8_t> bytes, double bytes_per_second, std::size_t chunk_bytes = 32);

  // Closes the master and the fixture's slave descriptor: the reader's side hangs up and the
  // slave path disappears once the reader closes it too.
  void close();

 private:
  int master_fd_ = -1;
  int slave_fd_ = -1;  // held so the slave's settings stay and the master never sees EIO
  std::string slave_path_;
};

// Bytes per second of a serial line at `baud`, 8N1 (start bit, 8 data bits, stop bit).
inline double lineBytesPerSecond(unsigned baud) { return baud / 10.0; }

// A capture from data/gpsd-logs as it was on the wire: the file without its '#' comment
// lines (nmea::CommentFilter). Throws std::runtime_error if the file cannot be read.
std::vector<std::uint8_t> readWireBytes(const std::filesystem::path& capture);

// Creates or atomically re-points link -> target (rename over the old link), as udev does
// with /dev/gps0 when a receiver is plugged in again.
void pointSymlink(const std::filesystem::path& link, const std::filesystem::path& target);

// A fresh directory under the system temp dir, removed with its contents on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace headingd::test
