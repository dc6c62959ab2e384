#pragma once
// Opening a file named by a user (configuration, command line) so that no name can stall or
// flood the reader: the open never blocks (O_NONBLOCK, so a FIFO without a writer does not
// wait), the kind is checked on the opened descriptor (fstat, so no race with a rename), and
// whatever is read whole has a size limit fitting its kind. Endless or slow things
// (/dev/zero, a FIFO, a directory) are refused with a message naming the file.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace headingd::files {

class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Size limits by kind of file (bytes; for gzip files, of the decompressed text). Each is far
// above any real file of its kind and far below what would hurt a small computer. Documented in
// daemon/README.md ("Files and their limits").
inline constexpr std::uint64_t kMiB = 1024 * 1024;
inline constexpr std::uint64_t kConfigFileLimit = 1 * kMiB;  // TOML: daemon, CAN, calibration
inline constexpr std::uint64_t kDbcFileLimit = 16 * kMiB;    // vendor DBC files run to a few MB
inline constexpr std::uint64_t kWmmFileLimit = 4 * kMiB;     // WMM.COF is 13 kB, WMMHR 0.5 MB
// Logs that a reader holds whole in memory (the daemon's candump and NMEA log sources, the
// tools' NMEA captures): 1 GiB is days of a 100 Hz IMU's candump text.
inline constexpr std::uint64_t kWholeLogLimit = 1024 * kMiB;
// Line-by-line readers (candump, NMEA, CSV logs, recordings) have no total limit, only this
// per line, so a file without line breaks cannot make them grow without bound.
inline constexpr std::size_t kMaxLineBytes = 1 * kMiB;

// An open, regular file's descriptor (blocking reads again), closed on destruction.
class InputFile {
 public:
  // Throws FileError "PATH: cannot open: REASON", "PATH: is a directory, not a file", ...
  // `limit` (bytes, 0 = none) is checked against the size on disk.
  explicit InputFile(const std::string& path, std::uint64_t limit = 0);
  ~InputFile();
  InputFile(InputFile&& other) noexcept : fd_(other.fd_), size_(other.size_) { other.fd_ = -1; }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  InputFile& operator=(InputFile&&) = delete;

  int fd() const { return fd_; }
  std::uint64_t size() const { return size_; }
  // Gives the descriptor away (to zlib's gzdopen, which closes it).
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

// What is wrong with `path` as an input file of at most `limit` bytes (0 = no limit), or ""
// when it opens as a regular file within the limit. For configuration checks that report the
// key naming the file.
std::string inputFileProblem(const std::string& path, std::uint64_t limit);

// The whole file, plain bytes, at most `limit` bytes (FileError naming the file and limit).
std::string readWholeFile(const std::string& path, std::uint64_t limit);

// "1 MiB", "16 MiB", "2 kiB", "2.9 kiB": limits in messages.
std::string bytesText(std::uint64_t bytes);

}  // namespace headingd::files
