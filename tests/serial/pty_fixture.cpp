#include "pty_fixture.hpp"

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "headingd/nmea/comment_filter.hpp"

namespace headingd::test {
namespace {

[[noreturn]] void throwErrno(const std::string& what) { throw std::system_error(errno, std::generic_category(), what); }

}  // namespace

PtyPair::PtyPair() {
  master_fd_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master_fd_ < 0) throwErrno("posix_openpt");
  try {
    if (::grantpt(master_fd_) != 0) throwErrno("grantpt");
    if (::unlockpt(master_fd_) != 0) throwErrno("unlockpt");
    char name[128];
    if (::ptsname_r(master_fd_, name, sizeof name) != 0) throwErrno("ptsname");
    slave_path_ = name;
    slave_fd_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (slave_fd_ < 0) throwErrno(std::string("open ") + name);
    termios t{};
    if (::tcgetattr(slave_fd_, &t) != 0) throwErrno("tcgetattr");
    ::cfmakeraw(&t);
    if (::tcsetattr(slave_fd_, TCSANOW, &t) != 0) throwErrno("tcsetattr");
    const int flags = ::fcntl(master_fd_, F_GETFL);
    if (flags < 0 || ::fcntl(master_fd_, F_SETFL, flags | O_NONBLOCK) != 0) throwErrno("fcntl O_NONBLOCK");
  } catch (...) {
    close();
    throw;
  }
}

PtyPair::~PtyPair() { close(); }

void PtyPair::close() {
  if (slave_fd_ >= 0) ::close(slave_fd_);
  if (master_fd_ >= 0) ::close(master_fd_);
  slave_fd_ = -1;
  master_fd_ = -1;
}

void PtyPair::write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds stall_timeout) {
  if (master_fd_ < 0) throw std::runtime_error("PtyPair::write: closed");
  while (!bytes.empty()) {
    const ssize_t n = ::write(master_fd_, bytes.data(), bytes.size());
    if (n > 0) {
      bytes = bytes.subspan(static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN) throwErrno("write to pty master");
    pollfd p{master_fd_, POLLOUT, 0};
    const int r = ::poll(&p, 1, static_cast<int>(stall_timeout.count()));
    if (r == 0)
      throw std::runtime_error("pty master: the reader took no bytes for " + std::to_string(stall_timeout.count()) +
                               " ms");
    if (r < 0 && errno != EINTR) throwErrno("poll pty master");
  }
}

void PtyPair::writePaced(std::span<const std::uint8_t> bytes, double bytes_per_second, std::size_t chunk_bytes) {
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t at = 0; at < bytes.size(); at += chunk_bytes) {
    const auto due = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(static_cast<double>(at) / bytes_per_second));
    std::this_thread::sleep_until(due);
    write(bytes.subspan(at, std::min(chunk_bytes, bytes.size() - at)));
  }
}

std::vector<std::uint8_t> readWireBytes(const std::filesystem::path& capture) {
  std::ifstream in(capture, std::ios::binary);
  if (!in) throw std::runtime_error(capture.string() + ": cannot open");
  const std::vector<std::uint8_t> raw{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::vector<std::uint8_t> wire;
  nmea::CommentFilter comments;
  comments.filter(raw, wire);
  return wire;
}

void pointSymlink(const std::filesystem::path& link, const std::filesystem::path& target) {
  std::filesystem::path tmp = link;
  tmp += ".new";
  std::filesystem::remove(tmp);
  std::filesystem::create_symlink(target, tmp);
  std::filesystem::rename(tmp, link);
}

TempDir::TempDir() {
  std::string templ = (std::filesystem::temp_directory_path() / "headingd-serial-XXXXXX").string();
  if (::mkdtemp(templ.data()) == nullptr) throwErrno("mkdtemp");
  path_ = templ;
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace headingd::test
