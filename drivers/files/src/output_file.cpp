#include "headingd/files/output_file.hpp"

#include "headingd/files/temporary_file_cleanup.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace headingd::files {
namespace {

std::string errnoText() { return std::strerror(errno); }

// The mode a plain fopen("w") would give: 0666 less the umask (mkstemp gives 0600).
mode_t newFileMode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

}  // namespace

OutputFile::OutputFile(const std::string& path) : path_(path), final_path_(path) {
  if (path.empty()) throw FileError("an output file name is empty");
  if (path == "-") {  // the convention of Unix tools: standard output, written directly
    const int fd = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 0);
    file_ = fd < 0 ? nullptr : ::fdopen(fd, "w");
    if (file_ == nullptr) {
      if (fd >= 0) ::close(fd);
      throw FileError("-: cannot write to standard output: " + errnoText());
    }
    return;
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw FileError(path + ": is a directory, expected an output file name");
    file_ = std::fopen(path.c_str(), "w");
    if (file_ == nullptr) throw FileError(path + ": cannot open for writing: " + errnoText());
    return;
  }
  struct stat link {};
  if (::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) {
    std::error_code ec;
    final_path_ = std::filesystem::weakly_canonical(path, ec).string();
    if (ec) throw FileError(path + ": cannot resolve the link: " + ec.message());
  }
  const std::filesystem::path final_path(final_path_);
  const std::filesystem::path folder = final_path.has_parent_path() ? final_path.parent_path() : ".";
  std::string temp = (folder / ("." + final_path.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkostemp(temp.data(), O_CLOEXEC);
  if (fd < 0) throw FileError(path + ": cannot create a temporary file in " + folder.string() + ": " + errnoText());
  ::fchmod(fd, st.st_ino != 0 && S_ISREG(st.st_mode) ? (st.st_mode & 07777) : newFileMode());
  temp_path_ = temp;
  cleanup_slot_ = removeOnFatalSignal(temp_path_.c_str());
  file_ = ::fdopen(fd, "w");
  if (file_ == nullptr) {
    ::close(fd);
    ::unlink(temp_path_.c_str());
    throw FileError(path + ": cannot open for writing: " + errnoText());
  }
}

OutputFile::~OutputFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
  forgetOnFatalSignal(cleanup_slot_);
}

void OutputFile::write(std::string_view text) {
  if (file_ == nullptr) {
    failed_ = true;
    return;
  }
  if (!text.empty() && std::fwrite(text.data(), 1, text.size(), file_) != text.size()) failed_ = true;
}

void OutputFile::commit() {
  if (file_ == nullptr) throw FileError(path_ + ": written already");
  const bool flushed = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (failed_ || !flushed || !closed) {
    throw FileError(path_ + ": write failed: " + std::strerror(flushed ? errno : flush_errno) +
                    (temp_path_.empty() ? "" : "; the earlier file, if any, is left as it was"));
  }
  if (temp_path_.empty()) return;
  if (::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
    throw FileError(path_ + ": cannot rename the finished file into place: " + errnoText());
  }
  temp_path_.clear();
  forgetOnFatalSignal(cleanup_slot_);
  cleanup_slot_ = -1;
}

void refuseOutputOverInputs(const NamedPath& output, const std::vector<NamedPath>& inputs) {
  struct stat out {};
  if (::stat(output.second.c_str(), &out) != 0) return;  // a new file: no input can be it
  for (const auto& [option, path] : inputs) {
    struct stat in {};
    if (path.empty() || ::stat(path.c_str(), &in) != 0) continue;
    if (in.st_dev == out.st_dev && in.st_ino == out.st_ino) {
      throw FileError(output.first + " '" + output.second + "' is the same file as " + option + " '" + path +
                      "': refusing to overwrite an input");
    }
  }
}

void writeWholeOutputFile(const std::string& path, std::string_view text) {
  OutputFile out(path);
  out.write(text);
  out.commit();
}

}  // namespace headingd::files
