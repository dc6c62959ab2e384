#pragma once
// Every output file of the tools is written through this: into a temporary file in the same
// folder (".NAME.XXXXXX"), renamed over NAME only when all was written (rename(2) is atomic
// within a file system). A failed or interrupted run never leaves a half-written file under
// the final name, and an existing file of that name stays as it was until the new one is whole;
// the temporary file is removed when the run fails, and when it is killed by SIGINT, SIGTERM,
// SIGHUP or SIGQUIT (temporary_file_cleanup.hpp).
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "headingd/files/input_file.hpp"  // FileError

namespace headingd::files {

class OutputFile {
 public:
  // Creates the temporary file; throws FileError naming `path`. An existing `path` that is not
  // a regular file (/dev/null, a FIFO, a terminal) is written directly: it cannot be replaced,
  // and it holds no earlier result to protect. A symbolic link is followed: its target is
  // replaced, not the link. "-" is standard output, written directly.
  explicit OutputFile(const std::string& path);
  // Not committed: the temporary file is removed, `path` is untouched.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::FILE* stream() { return file_; }
  // Writes `text`; errors are remembered and reported by commit().
  void write(std::string_view text);
  // Flushes, closes and renames into place; throws FileError on any write, close or rename error.
  void commit();
  const std::string& path() const { return path_; }

 private:
  std::string path_;        // as given (messages)
  std::string final_path_;  // what is replaced (a link's target)
  std::string temp_path_;   // "" when written directly
  int cleanup_slot_ = -1;   // removeOnFatalSignal's, while temp_path_ exists
  std::FILE* file_ = nullptr;
  bool failed_ = false;
};

// An output option and its value, or an input option and its value.
using NamedPath = std::pair<std::string, std::string>;

// Throws FileError when `output` is the same file as one of `inputs` (same device and inode:
// also through a symbolic or hard link), e.g. "--out 'a.csv' is the same file as --imu-csv
// 'b.csv': refusing to overwrite an input". Inputs that do not exist (yet) are skipped.
void refuseOutputOverInputs(const NamedPath& output, const std::vector<NamedPath>& inputs);

// Writes a whole output file at once through an OutputFile.
void writeWholeOutputFile(const std::string& path, std::string_view text);

}  // namespace headingd::files
