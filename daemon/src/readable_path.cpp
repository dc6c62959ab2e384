#include "headingd/daemon/readable_path.hpp"

#include <fstream>

namespace headingd::daemon {

std::string readablePath(core::TomlTableReader& r, std::string_view key, const std::string& fallback,
                         const std::string& base_dir, bool required) {
  std::string path = r.path(key, fallback, base_dir);
  if (required && !path.empty() && !std::ifstream(path).good()) r.fail(key, "cannot open '" + path + "' for reading");
  return path;
}

}  // namespace headingd::daemon
