#pragma once
// For the tests of the daemon's configuration errors (config_test.cpp, nmea_out_test.cpp,
// recorder_config_test.cpp): the message that loading a text gives, and the "file:line: "
// every message about a line starts with.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "daemon_test_support.hpp"
#include "headingd/core/config_error.hpp"
#include "headingd/daemon/config/config.hpp"

namespace headingd::daemon::test {

// The message of the ConfigError that loading `text`, written to dir/`file`, throws ("" if none).
inline std::string configErrorOf(const TempDir& dir, const std::string& text, const std::string& file = "bad.toml") {
  const std::string path = dir.write(file, text);
  try {
    loadDaemonConfig(path);
  } catch (const core::ConfigError& e) {
    return e.what();
  }
  return "";
}

// A folder for the configuration file (named `file`), and the file's errors.
class ConfigErrors : public ::testing::Test {
 protected:
  explicit ConfigErrors(std::string file = "bad.toml") : file_(std::move(file)) {}
  std::string errorOf(const std::string& text) const { return configErrorOf(dir, text, file_); }
  std::string at(int line) const { return dir.file(file_) + ":" + std::to_string(line) + ": "; }

  TempDir dir;

 private:
  std::string file_;
};

}  // namespace headingd::daemon::test
