#include "headingd/files/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace headingd::files {
namespace {

std::string kindProblem(const struct stat& st) {
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  if (S_ISFIFO(st.st_mode)) return "is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(st.st_mode)) return "is a character device, not a regular file";
  if (S_ISBLK(st.st_mode)) return "is a block device, not a regular file";
  if (S_ISSOCK(st.st_mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

std::string tooLarge(std::uint64_t size, std::uint64_t limit) {
  return "is " + std::to_string(size) + " bytes, more than the " + bytesText(limit) + " such a file may have";
}

}  // namespace

std::string bytesText(std::uint64_t bytes) {
  char text[48];
  if (bytes >= kMiB && bytes % kMiB == 0) {
    std::snprintf(text, sizeof text, "%llu MiB", static_cast<unsigned long long>(bytes / kMiB));
  } else if (bytes >= kMiB) {
    std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / static_cast<double>(kMiB));
  } else if (bytes >= 1024 && bytes % 1024 == 0) {
    std::snprintf(text, sizeof text, "%llu kiB", static_cast<unsigned long long>(bytes / 1024));
  } else if (bytes >= 1024) {
    std::snprintf(text, sizeof text, "%.1f kiB", static_cast<double>(bytes) / 1024.0);
  } else {
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  }
  return text;
}

InputFile::InputFile(const std::string& path, std::uint64_t limit) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer, for ever.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd_ < 0) throw FileError(path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  std::string problem;
  if (::fstat(fd_, &st) != 0) {
    problem = std::string("cannot stat: ") + std::strerror(errno);
  } else {
    problem = kindProblem(st);
  }
  if (problem.empty() && limit != 0 && static_cast<std::uint64_t>(st.st_size) > limit) {
    problem = tooLarge(static_cast<std::uint64_t>(st.st_size), limit);
  }
  // Reads of a regular file block on the disk alone; back to ordinary blocking reads.
  if (problem.empty() && ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK) != 0) {
    problem = std::string("cannot set blocking reads: ") + std::strerror(errno);
  }
  if (!problem.empty()) {
    ::close(fd_);
    fd_ = -1;
    throw FileError(path + ": " + problem);
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::string inputFileProblem(const std::string& path, std::uint64_t limit) {
  try {
    InputFile file(path, limit);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

std::string readWholeFile(const std::string& path, std::uint64_t limit) {
  InputFile file(path, limit);
  std::string data;
  data.resize(static_cast<std::size_t>(file.size()));
  std::size_t used = 0;
  // The file may grow after fstat: read on until the end, but never past the limit.
  while (true) {
    if (used == data.size()) {
      if (limit != 0 && used > limit) throw FileError(path + ": " + tooLarge(used, limit));
      data.resize(used + 65536);
    }
    const ssize_t n = ::read(file.fd(), data.data() + used, data.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw FileError(path + ": read error: " + std::strerror(errno));
    if (n == 0) break;
    used += static_cast<std::size_t>(n);
  }
  data.resize(used);
  if (limit != 0 && used > limit) throw FileError(path + ": " + tooLarge(used, limit));
  return data;
}

}  // namespace headingd::files
