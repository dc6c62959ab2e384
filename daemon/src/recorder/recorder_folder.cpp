#include "headingd/daemon/recorder/recorder_folder.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "headingd/daemon/recorder/write_fully.hpp"

namespace headingd::daemon {
namespace {

std::runtime_error systemError(const std::string& what, const std::string& path, int error) {
  return std::runtime_error("recorder: cannot " + what + " " + path + ": " + std::strerror(error));
}

void writeFile(const std::string& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw systemError("create", path, errno);
  const WriteOutcome w = writeFully(fd, content.data(), content.size());
  const int close_error = ::close(fd) == 0 ? 0 : errno;
  if (w.error != 0) throw systemError("write", path, w.error);
  if (close_error != 0) throw systemError("write", path, close_error);
}

// Splits "NAME-N" into NAME and N (N = 1 without a numeric suffix).
std::pair<std::string_view, std::uint64_t> baseAndSuffix(std::string_view name) {
  const std::size_t dash = name.rfind('-');
  if (dash != std::string_view::npos && dash + 1 < name.size()) {
    std::uint64_t n = 0;
    const char* first = name.data() + dash + 1;
    const char* last = name.data() + name.size();
    const auto [end, ec] = std::from_chars(first, last, n);
    if (ec == std::errc() && end == last) return {name.substr(0, dash), n};
  }
  return {name, 1};
}

}  // namespace

std::string recordingFolderName(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char name[32];
  std::strftime(name, sizeof name, "%Y-%m-%dT%H-%M-%SZ", &utc);
  return name;
}

std::string makeRecordingFolder(const std::string& dir, std::chrono::system_clock::time_point t,
                                const std::vector<std::pair<std::string, std::string>>& files) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw systemError("create the recording directory", dir, ec.value());
  const std::string base = dir + "/" + recordingFolderName(t);
  std::string folder = base;
  for (int suffix = 2;; ++suffix) {
    if (::mkdir(folder.c_str(), 0755) == 0) break;
    if (errno != EEXIST || suffix > 1000) throw systemError("create the recording folder", folder, errno);
    folder = base + "-" + std::to_string(suffix);
  }
  try {
    for (const auto& [name, content] : files) {
      if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") {
        throw std::runtime_error("recorder: '" + name + "' is not a file name for the recording folder");
      }
      writeFile(folder + "/" + name, content);
    }
  } catch (...) {
    std::filesystem::remove_all(folder, ec);
    throw;
  }
  return folder;
}

std::string segmentFileName(std::string_view stream, std::uint64_t number) {
  char digits[24];
  std::snprintf(digits, sizeof digits, "%06llu", static_cast<unsigned long long>(number));
  return std::string(stream) + "." + digits + ".log";
}

std::optional<SegmentFileName> parseSegmentFileName(std::string_view file_name) {
  constexpr std::string_view kSuffix = ".log";
  if (file_name.size() <= kSuffix.size() || file_name.substr(file_name.size() - kSuffix.size()) != kSuffix) {
    return std::nullopt;
  }
  const std::string_view stem = file_name.substr(0, file_name.size() - kSuffix.size());
  const std::size_t dot = stem.rfind('.');
  if (dot == std::string_view::npos || dot == 0 || stem.size() - dot - 1 < 6) return std::nullopt;
  SegmentFileName parsed;
  const char* first = stem.data() + dot + 1;
  const char* last = stem.data() + stem.size();
  const auto [end, ec] = std::from_chars(first, last, parsed.number);
  if (ec != std::errc() || end != last) return std::nullopt;
  parsed.stream = std::string(stem.substr(0, dot));
  return parsed;
}

bool recordingFolderBefore(const std::string& a, const std::string& b) {
  const auto [base_a, n_a] = baseAndSuffix(a);
  const auto [base_b, n_b] = baseAndSuffix(b);
  if (base_a != base_b) return base_a < base_b;
  return n_a < n_b;
}

}  // namespace headingd::daemon
