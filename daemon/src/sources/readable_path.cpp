#include "headingd/daemon/sources/readable_path.hpp"

#include "headingd/files/input_file.hpp"

namespace headingd::daemon {

std::string readablePath(core::TomlTableReader& r, std::string_view key, const std::string& fallback,
                         const std::string& base_dir, bool required, std::uint64_t limit) {
  std::string path = r.path(key, fallback, base_dir);
  if (required && !path.empty()) {
    if (const std::string problem = files::inputFileProblem(path, limit); !problem.empty()) r.fail(key, problem);
  }
  return path;
}

}  // namespace headingd::daemon
