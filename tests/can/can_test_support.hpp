#pragma once
// Helpers for the CAN tests: the shipped configuration files, temporary files, frames.
#include <unistd.h>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "headingd/can/can_frame.hpp"

namespace headingd::test {

inline std::string configPath(const std::string& name) { return std::string(HEADINGD_CONFIG_DIR) + "/" + name; }

// A private folder under the system temp dir, removed with its contents at scope exit.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "headingd-can-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data()) != nullptr ? pattern : std::string();
  }
  ~TempDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = path_ + "/" + name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

 private:
  std::string path_;
};

inline can::CanFrame frame(std::uint32_t id, bool extended, std::initializer_list<std::uint8_t> bytes,
                           std::int64_t t_ns = 0) {
  can::CanFrame f;
  f.id = id;
  f.extended = extended;
  f.t_ns = t_ns;
  for (std::uint8_t b : bytes) f.data[f.len++] = b;
  return f;
}

}  // namespace headingd::test
